# pcl_holefill: shape controllable hole filling for oriented point clouds.
# SPDX-License-Identifier: BSD-3-Clause
"""A single-view range scan of dense samples, shared by the Python tests and
bench/range_scan_check.py."""
import numpy as np


def single_view(points, normals, sensor, n):
    """A range scan of the dense samples \\a points from \\a sensor: on a
    pinhole's pixel grid sized for about n samples, the nearest sample of
    each pixel that faces the sensor (a z-buffer)."""
    rays = points - sensor
    depth = np.linalg.norm(rays, axis=1)
    axis = points.mean(axis=0) - sensor
    axis /= np.linalg.norm(axis)
    e1 = np.cross(axis, [0.123, 1.0, 0.05])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(axis, e1)
    along = rays @ axis
    u, v = rays @ e1 / along, rays @ e2 / along
    facing = np.sum(normals * (sensor - points), axis=1) > 0
    step = np.sqrt(np.ptp(u[facing]) * np.ptp(v[facing]) / (1.3 * n))
    pixel = ((u - u.min()) / step).astype(np.int64) * 1000003 + ((v - v.min()) / step).astype(np.int64)
    order = np.lexsort((depth, pixel))
    first = order[np.r_[True, pixel[order][1:] != pixel[order][:-1]]]
    first = first[facing[first]]
    return points[first], normals[first]
