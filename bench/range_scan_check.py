#!/usr/bin/env python3
# pcl_holefill: shape controllable hole filling for oriented point clouds.
# SPDX-License-Identifier: BSD-3-Clause
"""Single-view range scans: the probe that found patches grown past their
holes (doc/parameters.md, "A patch that grew past its hole").

Each shape of bench/independent_check.py and bench/probe_check.py is seen
from one sensor 2.5 from its middle: dense samples (3,000,000) on a pinhole's
pixel grid sized for about 20,000 points, the nearest sample of each pixel
that faces the sensor (a z-buffer). The scan leaves the occluded side
unseen; up to three balls 10 to 22 pitches across are cut where the scan
is all round them (the centroid of the points within the ball and 6 pitches
more lies within 0.6 pitch of its centre). Clean with exact normals, clean
and 0.3 % noise without normals. Scored as independent_check's run_case:
holes found, false holes (here mostly the loop around the unseen side),
coverage, error to 1,500,000 dense samples, points added more than 2 pitches
outside the cut balls; and how many patches the command withdrew.

Usage: range_scan_check.py COMMAND [seed]
  seed 0: the first views (a bowl from above one side, a bored cube seen
  obliquely, ...); other seeds: two random views of each shape.
"""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
from scipy.spatial import cKDTree

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "test", "python"))
import independent_check as ic  # noqa: E402
import probe_check  # noqa: E402
from single_view import single_view  # noqa: E402

FIRST_VIEWS = {"blob": [0.5, 0.6, 3.0], "bored cube": [2.0, 1.8, 2.5], "saddle": [0.5, 0.5, 2.0],
               "bowl": [0.5, 2.5, 1.5]}


def scan(shape, sensor, n, rng):
    """The z-buffer of 3,000,000 samples of the shape seen from sensor."""
    return single_view(*ic.SHAPES[shape](3000000, rng), sensor, n)


def holes_inside(points, pitch, rng):
    """Up to three balls with the scan all round them, apart from each other."""
    tree = cKDTree(points)
    centres, radii = [], []
    for _ in range(2000):
        if len(centres) == 3:
            break
        c, r = points[rng.integers(len(points))], rng.uniform(5, 11) * pitch
        if np.linalg.norm(points[tree.query_ball_point(c, r + 6 * pitch)].mean(axis=0) - c) > 0.6 * pitch:
            continue
        if all(np.linalg.norm(c - c2) > r + r2 + 6 * pitch for c2, r2 in zip(centres, radii)):
            centres.append(c)
            radii.append(r)
    return np.array(centres), np.array(radii)


def run_case(command, shape, sensor, noise, given_normals, truth, workdir, seed=7):
    rng = np.random.default_rng(seed)
    points, normals = scan(shape, np.asarray(sensor), 20000, rng)
    pitch = np.median(cKDTree(points).query(points, 2)[0][:, 1])  # a grid's nearest neighbour
    centres, radii = holes_inside(points, pitch, rng)
    if not len(centres):
        return None
    cut = np.any(np.linalg.norm(points[:, None, :] - centres[None], axis=2) < radii[None], axis=1)
    kept, kept_normals, removed = points[~cut], normals[~cut], points[cut]
    diagonal = np.linalg.norm(np.ptp(points, axis=0))
    kept = kept + kept_normals * rng.normal(scale=noise * diagonal, size=(len(kept), 1))
    source, target, report = (os.path.join(workdir, f) for f in ("in.xyz", "out.xyz", "report.json"))
    np.savetxt(source, np.c_[kept, kept_normals] if given_normals else kept, fmt="%.10g")
    subprocess.run([command, source, target, "-report", report, "-q"], check=True)
    out = np.loadtxt(target)
    filled = out[out[:, -1] == 1][:, :3]
    holes = json.load(open(report))["holes"]
    found, false_holes = np.zeros(len(centres), dtype=bool), 0
    for hole in holes:
        off = np.linalg.norm(centres - np.array(hole["centre"]), axis=1)
        if (off < radii + 3 * pitch).any():
            found[np.argmin(off)] = True
        else:
            false_holes += 1
    coverage = (cKDTree(np.vstack([kept, filled])).query(removed)[0] <= 1.5 * pitch).mean()
    errors = cKDTree(truth).query(filled)[0] if len(filled) else np.zeros(1)
    outside = np.all(np.linalg.norm(filled[:, None, :] - centres[None], axis=2) > radii[None] + 2 * pitch, axis=1)
    return {"points": len(points), "found": int(found.sum()), "cut": len(centres), "false": false_holes,
            "withdrawn": sum(h["withdrawn"] for h in holes), "coverage": coverage, "max": errors.max() / pitch,
            "outside": int(outside.sum())}


def main():
    command = sys.argv[1]
    seed = int(sys.argv[2]) if len(sys.argv) > 2 else 0
    ic.SHAPES.update(probe_check.PROBE_SHAPES)
    views = np.random.default_rng(seed)
    print("| shape | sensor | noise | normals | points | holes found / cut | false holes | withdrawn | coverage "
          "| max error / pitch | added outside |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    with tempfile.TemporaryDirectory() as workdir:
        for shape in FIRST_VIEWS if seed == 0 else ic.SHAPES:
            truth, _ = ic.SHAPES[shape](1500000, np.random.default_rng(99))
            sensors = [FIRST_VIEWS[shape]] if seed == 0 else []
            for _ in range(0 if seed == 0 else 2):
                d = views.normal(size=3)
                if shape in ("ripples", "saddle"):  # open sheets: seen from above
                    d[2] = abs(d[2]) + 0.8 * np.linalg.norm(d)
                sensors.append(list(0.5 + 2.5 * d / np.linalg.norm(d)))
            for sensor in sensors:
                for noise, given in ((0.0, True), (0.0, False), (0.003, False)):
                    r = run_case(command, shape, sensor, noise, given, truth, workdir)
                    where = ", ".join(f"{x:.2f}" for x in sensor)
                    if r is None:
                        print(f"| {shape} | {where} | - | - | - | no room for a hole | - | - | - | - | - |")
                        continue
                    print(f"| {shape} | {where} | {100 * noise:.1f}% | {'exact' if given else 'none'} "
                          f"| {r['points']} | {r['found']} / {r['cut']} | {r['false']} | {r['withdrawn']} "
                          f"| {100 * r['coverage']:.1f}% | {r['max']:.2f} | {r['outside']} |", flush=True)


if __name__ == "__main__":
    main()
