#!/usr/bin/python3
"""The whole command on a file against PCL's NormalEstimationOMP on the same file.

command_vs_normals.py COMMAND YARDSTICK [POINTS] [ROUNDS]

Writes a binary PCD of POINTS (default 1,000,000) uniformly random samples of
a sphere of radius 0.5 with exact normals and 10 holes (balls of radius 0.03
around random surface points, about 34 pitches across), then alternates, ROUNDS
times (default 5): COMMAND (pcl_holefill) reading it and writing the filled
cloud, and YARDSTICK --normals FILE (bench_large_hole: a process that reads the
file and runs NormalEstimationOMP, k = 16, 2 threads). Prints wall seconds and
their ratio per round: issue 8's speed target is a ratio of 0.5 at most.
"""
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
import open3d as o3d


def write_cloud(path, points):
    rng = np.random.default_rng(3)
    normals = rng.normal(size=(points, 3))
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    positions = 0.5 * normals
    centres = rng.normal(size=(10, 3))
    centres *= 0.5 / np.linalg.norm(centres, axis=1, keepdims=True)
    keep = np.ones(points, bool)
    for c in centres:
        keep &= np.linalg.norm(positions - c, axis=1) > 0.03
    cloud = o3d.geometry.PointCloud()
    cloud.points = o3d.utility.Vector3dVector(positions[keep])
    cloud.normals = o3d.utility.Vector3dVector(normals[keep])
    o3d.io.write_point_cloud(path, cloud, write_ascii=False)
    return int(keep.sum())


def seconds(argv):
    start = time.perf_counter()
    subprocess.run(argv, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def main():
    command, yardstick = sys.argv[1], sys.argv[2]
    points = int(sys.argv[3]) if len(sys.argv) > 3 else 1000000
    rounds = int(sys.argv[4]) if len(sys.argv) > 4 else 5
    with tempfile.TemporaryDirectory() as folder:
        given = os.path.join(folder, "sphere.pcd")
        filled = os.path.join(folder, "filled.pcd")
        kept = write_cloud(given, points)
        print(f"{kept} points, 10 holes\n")
        print("| round | pcl_holefill command (s) | read + NormalEstimationOMP process (s) | ratio |")
        print("| --- | --- | --- | --- |")
        for r in range(rounds):
            ours = seconds([command, given, filled, "-q"])
            theirs = seconds([yardstick, "--normals", given])
            print(f"| {r + 1} | {ours:.2f} | {theirs:.2f} | {ours / theirs:.2f} |", flush=True)


if __name__ == "__main__":
    main()
