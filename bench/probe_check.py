#!/usr/bin/env python3
# pcl_holefill: shape controllable hole filling for oriented point clouds.
# SPDX-License-Identifier: BSD-3-Clause
"""A probe on shapes and samplers that neither the robustness corpus nor
bench/independent_check.py has, scored as that script scores (its
run_case: holes found, false holes, coverage, error to 1,500,000 dense
samples, points added outside the cut balls).

Shapes: an ellipsoid 0.5 x 0.25 x 0.07 (a rim 1.5 pitches in radius), a
cone whose base rim is acute (63 degrees) and whose apex is sharp, a
five-pointed star prism (tips of 44 degrees) and a rippled open sheet.
Samplers: uniform random, Poisson-disk, voxel grid (independent_check's),
density varying 4 times along x, and slices (parallel planes 2 pitches
apart, random along each: on a surface facing the planes the lines spread
to many pitches, an anisotropy far beyond the corpus's scan lines).

Usage: probe_check.py COMMAND [seed] [fill|normals]
  fill     (default) the command with no option, one row per case;
  normals  the command's estimated normals (-detect_only on clouds without
           normals, 20,000 samples, seed 11) against the exact ones: how
           many point inside-out and how many lie more than 29 degrees
           off, judged against the six nearest samples (on an edge either
           face's normal will do); the independent check's blob, bowl and
           bored cube too.
"""
import os
import subprocess
import sys
import tempfile

import numpy as np
from scipy.spatial import cKDTree

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import independent_check as ic  # noqa: E402


def ellipsoid(n, rng, axes=np.array([0.5, 0.25, 0.07])):
    """Area-uniform by rejection on the area element of x = A d (d on the unit sphere)."""
    kept = []
    while sum(len(k) for k in kept) < n:
        d = ic.sphere_directions(4 * n, rng)
        element = np.linalg.norm(d / axes, axis=1)
        kept.append(d[rng.uniform(0, element.max() * 1.0001, len(d)) < element])
    d = np.vstack(kept)[:n]
    normals = d / axes
    return d * axes + 0.5, normals / np.linalg.norm(normals, axis=1)[:, None]


def cone(n, rng, radius=0.4, height=0.8):
    slant = np.hypot(radius, height)
    side, base = np.pi * radius * slant, np.pi * radius ** 2
    n_side = rng.binomial(n, side / (side + base))
    t, a = np.sqrt(rng.random(n_side)), rng.uniform(0, 2 * np.pi, n_side)  # t: 0 at the apex
    side_points = np.c_[t * radius * np.cos(a), t * radius * np.sin(a), height * (1 - t)]
    side_normals = np.c_[height / slant * np.cos(a), height / slant * np.sin(a), np.full(n_side, radius / slant)]
    r, b = radius * np.sqrt(rng.random(n - n_side)), rng.uniform(0, 2 * np.pi, n - n_side)
    base_points = np.c_[r * np.cos(b), r * np.sin(b), np.zeros(n - n_side)]
    base_normals = np.tile([0.0, 0.0, -1.0], (n - n_side, 1))
    order = rng.permutation(n)
    return (np.vstack([side_points, base_points]) + [0.5, 0.5, 0.1])[order], np.vstack([side_normals, base_normals])[order]


def star_outline(tips=5, outer=0.45, inner=0.2):
    """Counter-clockwise, a tip first."""
    angles = np.pi / 2 + np.arange(2 * tips) * np.pi / tips
    radii = np.where(np.arange(2 * tips) % 2 == 0, outer, inner)
    return np.c_[radii * np.cos(angles), radii * np.sin(angles)]


def inside_polygon(points, polygon):
    """Even-odd rule, a ray along +x."""
    inside = np.zeros(len(points), dtype=bool)
    for a, b in zip(polygon, np.roll(polygon, -1, axis=0)):
        crosses = (a[1] > points[:, 1]) != (b[1] > points[:, 1])
        x = a[0] + (points[:, 1] - a[1]) * (b[0] - a[0]) / np.where(b[1] != a[1], b[1] - a[1], 1.0)
        inside ^= crosses & (points[:, 0] < x)
    return inside


def star_prism(n, rng, height=0.3):
    outline = star_outline()
    edges = list(zip(outline, np.roll(outline, -1, axis=0)))
    lengths = np.array([np.linalg.norm(b - a) for a, b in edges])
    x, y = outline[:, 0], outline[:, 1]
    area = 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
    weights = np.r_[lengths * height, area, area]
    counts = rng.multinomial(n, weights / weights.sum())
    points, normals = [], []
    for (a, b), count in zip(edges, counts):
        along = a + rng.random(count)[:, None] * (b - a)
        out = np.array([b[1] - a[1], -(b[0] - a[0])]) / np.linalg.norm(b - a)
        points.append(np.c_[along, rng.random(count) * height])
        normals.append(np.tile([out[0], out[1], 0.0], (count, 1)))
    for count, z, up in ((counts[-2], 0.0, -1.0), (counts[-1], height, 1.0)):
        drawn = []
        while sum(len(d) for d in drawn) < count:
            q = rng.uniform(-0.45, 0.45, (4 * count + 10, 2))
            drawn.append(q[inside_polygon(q, outline)])
        points.append(np.c_[np.vstack(drawn)[:count], np.full(count, z)])
        normals.append(np.tile([0.0, 0.0, up], (count, 1)))
    order = rng.permutation(n)
    return (np.vstack(points) + [0.5, 0.5, 0.35])[order], np.vstack(normals)[order]


def ripples(n, rng, amplitude=0.04, frequency=3.0):
    """z = a sin(2 pi f x) sin(2 pi f y) over the unit square (open), area-uniform by rejection."""
    xy = rng.uniform(0, 1, (3 * n, 2))
    w = 2 * np.pi * frequency
    gx = amplitude * w * np.cos(w * xy[:, 0]) * np.sin(w * xy[:, 1])
    gy = amplitude * w * np.sin(w * xy[:, 0]) * np.cos(w * xy[:, 1])
    element = np.sqrt(1 + gx ** 2 + gy ** 2)
    keep = np.flatnonzero(rng.uniform(0, element.max(), len(xy)) < element)[:n]
    x, y = xy[keep, 0], xy[keep, 1]
    normals = np.c_[-gx[keep], -gy[keep], np.ones(len(keep))]
    return (np.c_[x, y, amplitude * np.sin(w * x) * np.sin(w * y) + 0.5],
            normals / np.linalg.norm(normals, axis=1)[:, None])


PROBE_SHAPES = {"ellipsoid": ellipsoid, "cone": cone, "star prism": star_prism, "ripples": ripples}
SAMPLERS = ("random", "Poisson-disk", "voxel grid", "varying", "slices")
independent_sample = ic.sample


def sample(shape, sampler, n, rng):
    """independent_check's samplers, and varying and slices."""
    if sampler not in ("varying", "slices"):
        return independent_sample(shape, sampler, n, rng)
    dense, normals = ic.SHAPES[shape](10 * n, rng)
    if sampler == "varying":
        x = dense[:, 0]
        keep = np.flatnonzero(rng.random(len(dense)) < 0.25 + 0.75 * (x - x.min()) / np.ptp(x))
        keep = keep[rng.permutation(len(keep))[:n]]
        return dense[keep], normals[keep]
    some = dense[:200000]
    area = len(some) * (2 * cKDTree(some).query(some, k=2)[0][:, 1].mean()) ** 2  # random: NN = pitch / 2
    planes = dense @ np.array([0.6, 0.8, 0.0]) / (2 * np.sqrt(area / n))  # 2 pitches apart
    keep = np.abs(planes - np.round(planes)) < 0.05
    return dense[keep], normals[keep]


def fill_table(command, seed):
    print("| shape | sampling | noise | normals | holes found / cut | false holes | coverage | max error "
          "| max error / pitch | added outside | density |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    with tempfile.TemporaryDirectory() as workdir:
        for shape in PROBE_SHAPES:
            truth, _ = ic.SHAPES[shape](1500000, np.random.default_rng(999))
            for sampler in SAMPLERS:
                for noise in (0.0, 0.003):
                    for given in (True, False):
                        r = ic.run_case(command, shape, sampler, noise, given, seed, truth, workdir)
                        print(f"| {shape} | {sampler} | {100 * noise:.1f}% | {'exact' if given else 'none'} "
                              f"| {r['found']} / {r['cut']} | {r['false']} | {100 * r['coverage']:.1f}% "
                              f"| {r['max']:.4f} | {r['max'] / r['pitch']:.2f} | {r['outside']} "
                              f"| {r['density']:.2f} |", flush=True)


def normals_table(command):
    print("| shape | sampling | noise | inside-out | off by more than 29 degrees | points |")
    print("| --- | --- | --- | --- | --- | --- |")
    total = np.zeros(3, dtype=int)
    with tempfile.TemporaryDirectory() as workdir:
        source, target = os.path.join(workdir, "in.xyz"), os.path.join(workdir, "out.xyz")
        for shape in list(PROBE_SHAPES) + ["blob", "bowl", "bored cube"]:
            for sampler in ("random", "Poisson-disk", "voxel grid", "varying"):
                for noise in (0.0, 0.003):
                    rng = np.random.default_rng(11)
                    points, exact = ic.sample(shape, sampler, 20000, rng)
                    diagonal = np.linalg.norm(np.ptp(points, axis=0))
                    points = points + exact * rng.normal(scale=noise * diagonal, size=(len(points), 1))
                    np.savetxt(source, points, fmt="%.8f")
                    subprocess.run([command, source, target, "-detect_only", "-q"], check=True)
                    estimated = np.loadtxt(target)[:, 3:6]
                    estimated /= np.linalg.norm(estimated, axis=1)[:, None]
                    near = cKDTree(points).query(points, 6)[1]
                    cosines = np.einsum("ij,ikj->ik", estimated, exact[near])
                    row = np.array([(cosines.max(1) < 0).sum(), (np.abs(cosines).max(1) < np.cos(0.5)).sum(),
                                    len(points)])
                    total += row
                    print(f"| {shape} | {sampler} | {100 * noise:.1f}% | {row[0]} | {row[1]} | {row[2]} |", flush=True)
    print(f"\nTotal: {total[0]} inside-out, {total[1]} off by more than 29 degrees, of {total[2]} points")


def main():
    command = sys.argv[1]
    seed = int(sys.argv[2]) if len(sys.argv) > 2 else 7
    mode = sys.argv[3] if len(sys.argv) > 3 else "fill"
    ic.SHAPES.update(PROBE_SHAPES)
    ic.BORDERS["ripples"] = lambda c: min(c[0], 1 - c[0], c[1], 1 - c[1])
    ic.sample = sample  # run_case samples through the module's function
    if mode == "normals":
        normals_table(command)
    else:
        fill_table(command, seed)


if __name__ == "__main__":
    main()
