#!/usr/bin/env python3
# pcl_holefill: shape controllable hole filling for oriented point clouds.
# SPDX-License-Identifier: BSD-3-Clause
"""Runs the command, with no option, on a mesh's vertices used as the cloud
(what a user who has only a CAD mesh passes: dense along curved strips,
sparse across flat faces, a sampling none of the corpus's samplers makes),
one ball cut at a time, and prints a Markdown table and a summary.

Balls: centred on random vertices (seed 100 + trial), radius 4 to 10 mean
nearest-neighbour spacings h of the vertices. Normals: 'exact' (the
area-weighted mean of the faces around each vertex) or 'none' (the command
estimates them). Ground truth, independent of the code: coverage is the
share of 400,000 area-uniform samples of the mesh inside the ball within
1.5 max(h, the nearest vertex's spacing) of an output point; 'vertices' the
share of cut vertices within 1.5 h of one; error the distance of a filled
point to the mesh's triangles; 'past the ball' how far the farthest filled
point lies outside the cut ball.

Usage: mesh_vertices_check.py COMMAND [MESH.off] [exact|none] [balls]
(default: fandisk from libcgal-demo's data as the corpus unpacks it into
build/test/corpus/data/meshes/, exact, 40 balls). Do not run it on the
other meshes of libcgal-demo: they belong to the independent evaluation.
"""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
from scipy.spatial import cKDTree


def read_off(path):
    with open(path) as f:
        tokens = f.read().split()
    assert tokens[0].upper().startswith("OFF"), path + " is not an OFF mesh"
    nv, nf = int(tokens[1]), int(tokens[2])
    i = 4
    vertices = np.array(tokens[i:i + 3 * nv], float).reshape(nv, 3)
    i += 3 * nv
    triangles = []
    for _ in range(nf):
        k = int(tokens[i])
        face = [int(t) for t in tokens[i + 1:i + 1 + k]]
        triangles += [[face[0], face[j], face[j + 1]] for j in range(1, k - 1)]
        i += 1 + k
    return vertices, np.array(triangles)


def vertex_normals(vertices, triangles):
    v = vertices[triangles]
    area_normals = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0])
    normals = np.zeros_like(vertices)
    for k in range(3):
        np.add.at(normals, triangles[:, k], area_normals)
    return normals / np.maximum(np.linalg.norm(normals, axis=1)[:, None], 1e-30)


def surface_samples(vertices, triangles, n, rng):
    v = vertices[triangles]
    areas = 0.5 * np.linalg.norm(np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]), axis=1)
    pick = rng.choice(len(triangles), n, p=areas / areas.sum())
    r1, r2 = np.sqrt(rng.random(n))[:, None], rng.random(n)[:, None]
    a, b, c = v[pick, 0], v[pick, 1], v[pick, 2]
    return (1 - r1) * a + r1 * (1 - r2) * b + r1 * r2 * c


def distance_to_triangles(points, vertices, triangles):
    """Exact point-to-triangle distance, minimised over every triangle."""
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    ab, ac = b - a, c - a
    out = np.full(len(points), np.inf)
    for s in range(0, len(points), 64):
        p = points[s:s + 64][:, None, :]

        def to_segment(x, y):
            xy = y - x
            t = np.clip(((p - x) * xy).sum(-1) / np.maximum((xy * xy).sum(-1), 1e-300), 0, 1)
            return np.linalg.norm(p - (x + t[..., None] * xy), axis=-1)

        n = np.cross(ab, ac)
        n2 = np.maximum((n * n).sum(-1), 1e-300)
        ap = p - a
        # Barycentric coordinates of the projection onto each triangle's plane.
        w = (np.cross(ab, ap) * n).sum(-1) / n2
        v = (np.cross(ap, ac) * n).sum(-1) / n2
        inside = (v >= 0) & (w >= 0) & (v + w <= 1)
        plane = np.abs((ap * n).sum(-1)) / np.sqrt(n2)
        edges = np.minimum(np.minimum(to_segment(a, b), to_segment(b, c)), to_segment(a, c))
        out[s:s + 64] = np.where(inside, plane, edges).min(1)
    return out


def main():
    command = sys.argv[1]
    mesh = sys.argv[2] if len(sys.argv) > 2 else "build/test/corpus/data/meshes/fandisk.off"
    mode = sys.argv[3] if len(sys.argv) > 3 else "exact"
    balls = int(sys.argv[4]) if len(sys.argv) > 4 else 40
    vertices, triangles = read_off(mesh)
    normals = vertex_normals(vertices, triangles)
    tree = cKDTree(vertices)
    spacing = tree.query(vertices, 2)[0][:, 1]
    h = spacing.mean()
    dense = surface_samples(vertices, triangles, 400000, np.random.default_rng(7))
    print(f"{os.path.basename(mesh)}: {len(vertices)} vertices, h = {h:.5f}, normals {mode}\n")
    print("| ball | radius / h | cut vertices | points added | holes | reported closed | coverage | vertices "
          "| max error / h | past the ball / h |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    rows = []
    with tempfile.TemporaryDirectory() as workdir:
        for trial in range(balls):
            rng = np.random.default_rng(100 + trial)
            centre = vertices[rng.integers(len(vertices))]
            radius = h * rng.uniform(4, 10)
            cut = np.linalg.norm(vertices - centre, axis=1) < radius
            data = np.c_[vertices[~cut], normals[~cut]] if mode == "exact" else vertices[~cut]
            source, target = os.path.join(workdir, "in.xyz"), os.path.join(workdir, "out.xyz")
            report = os.path.join(workdir, "report.json")
            np.savetxt(source, data, fmt="%.9g")
            subprocess.run([command, source, target, "-q", "-report", report], check=True)
            out = np.loadtxt(target, ndmin=2)
            filled = out[len(data):, :3]
            near = cKDTree(out[:, :3])
            inside = dense[np.linalg.norm(dense - centre, axis=1) < radius]
            nearest_vertex = tree.query(inside)[1]
            reach = 1.5 * np.maximum(spacing[nearest_vertex], h)
            coverage = (near.query(inside)[0] <= reach).mean() if len(inside) else 1.0
            cut_covered = (near.query(vertices[cut])[0] <= 1.5 * h).mean()
            error = distance_to_triangles(filled, vertices, triangles).max() / h if len(filled) else 0.0
            past = max(0.0, (np.linalg.norm(filled - centre, axis=1) - radius).max() / h) if len(filled) else 0.0
            holes = json.load(open(report))["holes"]
            closed = sum(1 for hole in holes if hole["closed"])
            rows.append((coverage, cut_covered, error, past))
            print(f"| {trial} | {radius / h:.1f} | {cut.sum()} | {len(filled)} | {len(holes)} | {closed} "
                  f"| {100 * coverage:.1f}% | {100 * cut_covered:.1f}% | {error:.2f} | {past:.2f} |", flush=True)
    r = np.array(rows)
    print(f"\nSummary: coverage >= 99 %: {(r[:, 0] >= 0.99).sum()} of {len(r)}; mean {100 * r[:, 0].mean():.1f} %, "
          f"lowest {100 * r[:, 0].min():.1f} %; cut vertices covered, mean {100 * r[:, 1].mean():.1f} %; "
          f"max error: largest {r[:, 2].max():.2f} h, sum {r[:, 2].sum():.2f} h; past the ball: largest "
          f"{r[:, 3].max():.2f} h")


if __name__ == "__main__":
    main()
