#!/usr/bin/env python3
# pcl_holefill: shape controllable hole filling for oriented point clouds.
# SPDX-License-Identifier: BSD-3-Clause
"""Runs the command, with no option, on clouds whose density changes
abruptly, as merged scans leave them, and prints a Markdown table scored
like bench/independent_check.py (run_case: the same holes, coverage, error
against 1,500,000 dense samples, points added outside the cut balls).

Samplers (written apart from the corpus, whose 'varying' density changes
smoothly): 'step x2' and 'step x4', uniformly random samples whose one half
(split by a plane) is 2 or 4 times sparser than the other; 'overlap', two
random scans of overlapping parts merged (a band of double density);
'overlap 0.2p off', the same with the second scan moved 0.2 pitch along
the normals (a misregistration); 'voxel grid thinned' and 'Poisson-disk
thinned', independent_check's even samplers with the low half thinned to
1 in 4 at random (a decimated region: even in one part, random in the
other). Shapes: independent_check's and
probe_check's; clean with exact normals, clean and 0.3 % noise without.

Usage: density_step_check.py COMMAND [seed] [shape,shape,...]
"""
import os
import sys
import tempfile

import numpy as np
from scipy.spatial import cKDTree

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import independent_check as ic  # noqa: E402
import probe_check as pc  # noqa: E402

SPLIT = np.array([0.8, 0.5, 0.33])  # the direction across the density step


def thin_low_half(points, rng, ratio):
    """Indices of points: all on the high side of the median plane across
    SPLIT, 1 in ratio of the others, drawn at random."""
    side = points @ SPLIT
    return np.flatnonzero((side > np.median(side)) | (rng.random(len(points)) < 1.0 / ratio))


def step(shape, n, rng, ratio):
    """Random samples, those on the low side of the median plane kept 1 in ratio."""
    dense, normals = ic.SHAPES[shape](12 * n, rng)
    keep = thin_low_half(dense, rng, ratio)
    keep = keep[rng.permutation(len(keep))[:n]]
    return dense[keep], normals[keep]


EVEN_SAMPLE = ic.sample  # independent_check's samplers, before main() replaces them


def thinned(shape, sampler, n, rng):
    """An even sampler's samples (1.6 n), those on the low side of the median
    plane kept 1 in 4 at random: about n left."""
    points, normals = EVEN_SAMPLE(shape, sampler, int(1.6 * n), rng)
    keep = thin_low_half(points, rng, 4)
    return points[keep], normals[keep]


def overlap(shape, n, rng, shift):
    """Two random scans, of the parts below the 65th and above the 35th
    percentile along SPLIT; the second moved shift pitches along its normals."""
    a, a_normals = ic.SHAPES[shape](n, rng)
    b, b_normals = ic.SHAPES[shape](n, rng)
    lo, hi = np.percentile(a @ SPLIT, 35), np.percentile(a @ SPLIT, 65)
    in_a, in_b = a @ SPLIT < hi, b @ SPLIT > lo
    some = a[:20000]
    pitch = 2 * cKDTree(some).query(some, 2)[0][:, 1].mean() * np.sqrt(len(some) / n)  # random: NN = pitch / 2
    points = np.vstack([a[in_a], b[in_b] + shift * pitch * b_normals[in_b]])
    normals = np.vstack([a_normals[in_a], b_normals[in_b]])
    order = rng.permutation(len(points))[:n]
    return points[order], normals[order]


SAMPLERS = {"step x2": lambda s, n, r: step(s, n, r, 2), "step x4": lambda s, n, r: step(s, n, r, 4),
            "overlap": lambda s, n, r: overlap(s, n, r, 0.0),
            "overlap 0.2p off": lambda s, n, r: overlap(s, n, r, 0.2),
            "voxel grid thinned": lambda s, n, r: thinned(s, "voxel grid", n, r),
            "Poisson-disk thinned": lambda s, n, r: thinned(s, "Poisson-disk", n, r)}


def main():
    command = sys.argv[1]
    seed = int(sys.argv[2]) if len(sys.argv) > 2 else 7
    ic.SHAPES.update(pc.PROBE_SHAPES)
    shapes = sys.argv[3].split(",") if len(sys.argv) > 3 else ["blob", "bored cube", "saddle", "cone", "star prism"]
    ic.sample = lambda shape, sampler, n, rng: SAMPLERS[sampler](shape, n, rng)
    print("| shape | sampling | noise | normals | holes found / cut | false holes | coverage | max error / pitch "
          "| added outside | density |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    with tempfile.TemporaryDirectory() as workdir:
        for shape in shapes:
            truth, _ = ic.SHAPES[shape](1500000, np.random.default_rng(999))
            for sampler in SAMPLERS:
                for noise, given in ((0.0, True), (0.0, False), (0.003, False)):
                    r = ic.run_case(command, shape, sampler, noise, given, seed, truth, workdir)
                    print(f"| {shape} | {sampler} | {100 * noise:.1f}% | {'exact' if given else 'none'} "
                          f"| {r['found']} / {r['cut']} | {r['false']} | {100 * r['coverage']:.1f}% "
                          f"| {r['max'] / r['pitch']:.2f} | {r['outside']} | {r['density']:.2f} |", flush=True)


if __name__ == "__main__":
    main()
