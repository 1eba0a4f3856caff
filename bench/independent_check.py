#!/usr/bin/env python3
# pcl_holefill: shape controllable hole filling for oriented point clouds.
# SPDX-License-Identifier: BSD-3-Clause
"""Runs the command, with no option, on shapes and samplers that the
robustness corpus (test/corpus) does not have, written apart from it, and
prints a Markdown table (doc/independent.md, made by
bench/make_independent.sh).

Shapes: a bumpy blob (strong, varying curvature), a thin bowl (a shell 5
pitches thick with a flat rim), a cube with a bore (convex edges next to a
concave wall) and a saddle (an open surface). Samplers: uniform random,
voxel grid (centroids of a dense random sampling) and Poisson-disk (dart
throwing). Three holes per cloud, 10 to 22 pitches across, away from
borders and from each other; noise 0 or 0.3 % of the diagonal along the
normal; normals exact or none (the command estimates them). Ground truth:
the distance to 1,500,000 dense samples of the shape (their own spacing,
about 0.0005, is the floor of every error).

Usage: independent_check.py COMMAND [seed]
"""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
from scipy.spatial import cKDTree


def sphere_directions(n, rng):
    v = rng.normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=1)[:, None]


def blob_radius(d):
    return 0.5 * (1 + 0.18 * np.sin(3 * d[:, 0] + 1) * np.sin(4 * d[:, 1]) + 0.12 * np.cos(5 * d[:, 2]))


def blob(n, rng):
    """r(direction) = blob_radius: area-uniform by rejection on the area element."""
    m = 4 * n
    d = sphere_directions(m, rng)
    t1 = np.cross(d, rng.normal(size=(m, 3)))
    t1 /= np.linalg.norm(t1, axis=1)[:, None]
    t2 = np.cross(d, t1)
    eps = 1e-4

    def surface(dd):
        dd = dd / np.linalg.norm(dd, axis=1)[:, None]
        return dd * blob_radius(dd)[:, None]

    a, b, c = surface(d), surface(d + eps * t1), surface(d + eps * t2)
    n_raw = np.cross(b - a, c - a)
    area = np.linalg.norm(n_raw, axis=1)
    normals = n_raw / area[:, None] * np.sign(np.sum(n_raw * d, axis=1))[:, None]
    keep = np.flatnonzero(rng.uniform(0, area.max(), m) < area)[:n]
    return a[keep] + 0.5, normals[keep]


def bowl(n, rng):
    """A hemispherical shell, outer radius 0.5, inner 0.44, closed by a flat rim."""
    outer, inner = 0.5, 0.44
    areas = np.array([2 * np.pi * outer ** 2, 2 * np.pi * inner ** 2, np.pi * (outer ** 2 - inner ** 2)])
    counts = rng.multinomial(n, areas / areas.sum())
    points, normals = [], []
    for radius, count, sign in ((outer, counts[0], 1), (inner, counts[1], -1)):
        d = sphere_directions(2 * count + 10, rng)
        d = d[d[:, 2] < 0][:count]
        points.append(d * radius)
        normals.append(sign * d)
    r = np.sqrt(rng.uniform(inner ** 2, outer ** 2, counts[2]))
    t = rng.uniform(0, 2 * np.pi, counts[2])
    points.append(np.c_[r * np.cos(t), r * np.sin(t), np.zeros(counts[2])])
    normals.append(np.tile([0.0, 0.0, 1.0], (counts[2], 1)))
    return np.vstack(points) + 0.5, np.vstack(normals)


def bored_cube(n, rng, bore=0.22):
    """The unit cube with a bore of radius 0.22 along z through its middle."""
    cap = 1 - np.pi * bore ** 2
    areas = np.array([1, 1, 1, 1, cap, cap, 2 * np.pi * bore])
    counts = rng.multinomial(n, areas / areas.sum())
    points, normals = [], []
    for k, (axis, side) in enumerate(((0, 0), (0, 1), (1, 0), (1, 1))):
        p = np.zeros((counts[k], 3))
        others = [a for a in range(3) if a != axis]
        p[:, others] = rng.random((counts[k], 2))
        p[:, axis] = side
        q = np.zeros_like(p)
        q[:, axis] = 2 * side - 1
        points.append(p)
        normals.append(q)
    for k, side in ((4, 0), (5, 1)):
        xy = rng.random((2 * counts[k] + 20, 2))
        xy = xy[np.hypot(xy[:, 0] - 0.5, xy[:, 1] - 0.5) > bore][:counts[k]]
        points.append(np.c_[xy, np.full(len(xy), float(side))])
        normals.append(np.tile([0.0, 0.0, 2.0 * side - 1], (len(xy), 1)))
    t = rng.uniform(0, 2 * np.pi, counts[6])
    points.append(np.c_[0.5 + bore * np.cos(t), 0.5 + bore * np.sin(t), rng.random(counts[6])])
    normals.append(-np.c_[np.cos(t), np.sin(t), np.zeros(counts[6])])
    p = np.vstack(points)
    order = rng.permutation(len(p))
    return p[order], np.vstack(normals)[order]


def saddle(n, rng):
    """z = 0.4 (x^2 - y^2) over a unit square: an open surface."""
    m = 3 * n
    xy = rng.uniform(-0.5, 0.5, (m, 2))
    area = np.sqrt(1 + (0.8 * xy[:, 0]) ** 2 + (0.8 * xy[:, 1]) ** 2)
    keep = np.flatnonzero(rng.uniform(0, area.max(), m) < area)[:n]
    x, y = xy[keep, 0], xy[keep, 1]
    normals = np.c_[-0.8 * x, 0.8 * y, np.ones(len(x))]
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    return np.c_[x + 0.5, y + 0.5, 0.4 * (x * x - y * y) + 0.5], normals


SHAPES = {"blob": blob, "bowl": bowl, "bored cube": bored_cube, "saddle": saddle}
# Distance of a point to the shape's border (open shapes only): holes stay clear of it.
BORDERS = {"saddle": lambda c: min(c[0], 1 - c[0], c[1], 1 - c[1])}


def voxel_grid(points, normals, n):
    """Centroids of the occupied voxels of a dense sampling, the voxel sized
    for about n of them; each takes the normal of the sample nearest to it."""
    lo, hi = 0.0, 0.1
    for _ in range(30):
        edge = 0.5 * (lo + hi)
        if len(np.unique(np.floor(points / edge).astype(np.int64), axis=0)) > n:
            lo = edge
        else:
            hi = edge
    keys = np.floor(points / hi).astype(np.int64)
    _, inverse = np.unique(keys, axis=0, return_inverse=True)
    inverse = inverse.ravel()
    centroids = np.zeros((inverse.max() + 1, 3))
    np.add.at(centroids, inverse, points)
    centroids /= np.bincount(inverse)[:, None]
    _, nearest = cKDTree(points).query(centroids)
    return centroids, normals[nearest]


def poisson_disk(points, normals, n, rng):
    """Dart throwing over a dense sampling, the radius bisected for about n points."""
    tree, order = cKDTree(points), rng.permutation(len(points))

    def thin(radius):
        taken = np.zeros(len(points), dtype=bool)
        blocked = np.zeros(len(points), dtype=bool)
        for i in order:
            if not blocked[i]:
                taken[i] = True
                blocked[tree.query_ball_point(points[i], radius)] = True
        return taken

    lo, hi = 0.0, 0.1
    for _ in range(12):
        radius = 0.5 * (lo + hi)
        if thin(radius).sum() > n:
            lo = radius
        else:
            hi = radius
    taken = thin(lo)
    return points[taken], normals[taken]


def sample(shape, sampler, n, rng):
    if sampler == "random":
        return SHAPES[shape](n, rng)
    dense = SHAPES[shape](8 * n, rng)
    return voxel_grid(*dense, n) if sampler == "voxel grid" else poisson_disk(*dense, n, rng)


def pitch_of(points, truth):
    """sqrt(area / points), the area from the dense (random) samples' spacing."""
    some = truth[np.random.default_rng(5).permutation(len(truth))[:200000]]
    spacing, _ = cKDTree(some).query(some, k=2)
    area = len(some) * (2 * spacing[:, 1].mean()) ** 2  # random samples: mean NN = pitch / 2
    return np.sqrt(area / len(points))


def holes(shape, points, pitch, rng):
    """Three balls on the surface, 10 to 22 pitches across, apart and off the border."""
    centres, radii = [], []
    border = BORDERS.get(shape, lambda c: np.inf)
    for _ in range(1000):
        if len(centres) == 3:
            break
        c, r = points[rng.integers(len(points))], rng.uniform(5, 11) * pitch
        if border(c) > r + 4 * pitch and all(np.linalg.norm(c - c2) > r + r2 + 6 * pitch
                                             for c2, r2 in zip(centres, radii)):
            centres.append(c)
            radii.append(r)
    return np.array(centres), np.array(radii)


def run_case(command, shape, sampler, noise, given_normals, seed, truth, workdir):
    rng = np.random.default_rng(seed)
    points, normals = sample(shape, sampler, 20000, rng)
    pitch = pitch_of(points, truth)
    centres, radii = holes(shape, points, pitch, rng)
    cut = np.any(np.linalg.norm(points[:, None, :] - centres[None], axis=2) < radii[None], axis=1)
    kept, kept_normals, removed = points[~cut], normals[~cut], points[cut]
    diagonal = np.linalg.norm(points.max(axis=0) - points.min(axis=0))
    kept = kept + kept_normals * rng.normal(scale=noise * diagonal, size=(len(kept), 1))
    source = os.path.join(workdir, "in.xyz")
    np.savetxt(source, np.c_[kept, kept_normals] if given_normals else kept, fmt="%.8f")
    target, report = os.path.join(workdir, "out.xyz"), os.path.join(workdir, "report.json")
    subprocess.run([command, source, target, "-report", report, "-q"], check=True)
    out = np.loadtxt(target)
    filled = out[out[:, -1] == 1][:, :3]
    moved = np.abs(out[out[:, -1] == 0][:, :3] - kept).max()
    found = np.zeros(len(centres), dtype=bool)
    false_holes = 0
    for hole in json.load(open(report))["holes"]:
        off = np.linalg.norm(centres - np.array(hole["centre"]), axis=1)
        if (off < radii + 3 * pitch).any():
            found[np.argmin(off)] = True
        else:
            false_holes += 1
    output = np.vstack([kept, filled])
    coverage = (cKDTree(output).query(removed)[0] <= 1.5 * pitch).mean()
    errors = cKDTree(truth).query(filled)[0] if len(filled) else np.zeros(1)
    beyond = np.all(np.linalg.norm(filled[:, None, :] - centres[None], axis=2) > radii[None] + 2 * pitch, axis=1)
    return {"found": int(found.sum()), "cut": len(centres), "false": false_holes, "coverage": coverage,
            "max": errors.max(), "p99": np.percentile(errors, 99), "outside": int(beyond.sum()),
            "density": len(filled) / max(1, len(removed)), "moved": moved, "pitch": pitch,
            "sigma": noise * diagonal}


def main():
    command = sys.argv[1]
    seed = int(sys.argv[2]) if len(sys.argv) > 2 else 7
    print("| shape | sampling | noise | normals | holes found / cut | false holes | coverage | max error "
          "| 99th percentile error | max error / pitch | added outside | density | input moved |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    with tempfile.TemporaryDirectory() as workdir:
        for shape in SHAPES:
            truth, _ = SHAPES[shape](1500000, np.random.default_rng(999))
            for sampler in ("random", "voxel grid", "Poisson-disk"):
                for noise in (0.0, 0.003):
                    for given in (True, False):
                        r = run_case(command, shape, sampler, noise, given, seed, truth, workdir)
                        print(f"| {shape} | {sampler} | {100 * noise:.1f}% | {'exact' if given else 'none'} "
                              f"| {r['found']} / {r['cut']} | {r['false']} | {100 * r['coverage']:.1f}% "
                              f"| {r['max']:.4f} | {r['p99']:.4f} | {r['max'] / r['pitch']:.2f} | {r['outside']} "
                              f"| {r['density']:.2f} | {'no' if r['moved'] <= 1e-6 else 'YES'} |", flush=True)


if __name__ == "__main__":
    main()
