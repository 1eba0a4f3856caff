#!/usr/bin/python3
# pcl_holefill: shape controllable hole filling for oriented point clouds.
# SPDX-License-Identifier: BSD-3-Clause
"""Fill the holes of a cloud loaded with Open3D, and show or save the result.

    python3 doc/open3d_example.py scan.ply filled.ply   # any format Open3D reads
    python3 doc/open3d_example.py                       # a built-in example: a sphere with a cap cut off
    python3 doc/open3d_example.py --check               # the built-in example, no window (for tests)

Filled points are coloured orange. Without an output file the result is shown
in an Open3D window (when there is a display).
"""
import os
import sys

import numpy as np
import open3d as o3d

import pcl_holefill


def built_in_cloud():
    """A sphere sampled the way mesh-sampling tools do, with a cap cut off."""
    o3d.utility.random.seed(1)
    mesh = o3d.geometry.TriangleMesh.create_sphere(radius=1.0, resolution=60)
    cloud = mesh.sample_points_uniformly(20000)
    points = np.asarray(cloud.points)
    keep = points[:, 2] < 0.85
    cloud = cloud.select_by_index(np.flatnonzero(keep))
    cloud.normals = o3d.utility.Vector3dVector(np.asarray(cloud.points))  # the sphere's exact normals
    return cloud


def main(argv):
    check = "--check" in argv
    paths = [a for a in argv if not a.startswith("--")]
    cloud = o3d.io.read_point_cloud(paths[0]) if paths else built_in_cloud()
    points = np.asarray(cloud.points)  # float64: fill keeps its precision
    normals = np.asarray(cloud.normals) if cloud.has_normals() else None
    colours = np.asarray(cloud.colors) if cloud.has_colors() else None

    result = pcl_holefill.fill(points, normals, extra=colours)
    for i, hole in enumerate(result.reports):
        state = "closed" if hole["closed"] else f"open, {hole['open_diameter']:.3g} across left"
        print(f"hole {i}: {hole['points_added']} points added, {state}")

    filled = o3d.geometry.PointCloud()
    filled.points = o3d.utility.Vector3dVector(result.points)
    filled.normals = o3d.utility.Vector3dVector(result.normals)
    colours_out = result.extra if colours is not None else np.full((len(result.points), 3), 0.7)
    colours_out = np.array(colours_out, dtype=np.float64)
    colours_out[result.filled] = (1.0, 0.5, 0.0)
    filled.colors = o3d.utility.Vector3dVector(colours_out)

    if check:
        # The cap (z >= 0.85 on a unit sphere) is covered, on the sphere.
        added = result.points[result.filled]
        assert len(result.reports) == 1 and result.reports[0]["closed"], result.reports
        assert np.abs(np.linalg.norm(added, axis=1) - 1.0).max() < 0.01
        assert added[:, 2].max() > 0.99
        print(f"ok: {len(added)} points added on the sphere")
        return 0
    if len(paths) > 1:
        o3d.io.write_point_cloud(paths[1], filled)
        print(f"wrote {paths[1]}")
    elif os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"):
        o3d.visualization.draw_geometries([filled])
    else:
        print("no display: give an output file to save the result")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
