# pcl_holefill: shape controllable hole filling for oriented point clouds.
# SPDX-License-Identifier: BSD-3-Clause
"""The Python module, as a user calls it: numpy in, numpy out.

Ground truth is the exact surface the clouds are sampled from (a unit cube, a
sphere), never a figure the module computes. Run by the README's test command
against the installed package (PYTHONPATH and PCL_HOLEFILL_COMMAND point at
the install); from a build tree, ctest sets them.
"""
import os
import subprocess
import threading

import numpy as np
import pytest

import pcl_holefill
from single_view import single_view

SAMPLES = 20000


def cube_samples(n, seed, rng=None):
    """Uniformly random samples of the unit cube's surface, exact outward normals
    (drawn from \a rng when given, which the caller may go on drawing from)."""
    rng = np.random.default_rng(seed) if rng is None else rng
    face = rng.integers(0, 6, n)
    axis, side = face // 2, (face % 2).astype(np.float64)
    uv = rng.random((n, 2))
    points = np.empty((n, 3))
    normals = np.zeros((n, 3))
    for a in range(3):
        on = axis == a
        others = [b for b in range(3) if b != a]
        points[on, a] = side[on]
        points[np.ix_(on, others)] = uv[on]
        normals[on, a] = 2 * side[on] - 1
    return points, normals


def cube_distance(p):
    """Distance to the surface of the unit cube (inside or outside)."""
    outside = np.linalg.norm(np.maximum(np.maximum(-p, p - 1), 0), axis=1)
    inside = np.minimum(p, 1 - p).min(axis=1)
    return np.where(outside > 0, outside, inside)


BORE = 0.22  # radius of the bore of bored_cube_samples, along z through (0.5, 0.5)


def bored_cube_samples(n, seed):
    """Uniformly random samples of the unit cube with a bore (radius BORE)
    along z through its middle: convex edges where the bore meets the top
    and bottom, a concave wall. Exact outward normals."""
    rng = np.random.default_rng(seed)
    cap = 1 - np.pi * BORE ** 2
    areas = np.array([1, 1, 1, 1, cap, cap, 2 * np.pi * BORE])
    piece = rng.choice(7, size=n, p=areas / areas.sum())
    points, normals = np.empty((n, 3)), np.zeros((n, 3))
    uv = rng.random((n, 2))
    for k, (axis, side) in enumerate([(0, 0), (0, 1), (1, 0), (1, 1)]):
        on = piece == k
        others = [b for b in range(3) if b != axis]
        points[on, axis] = side
        points[np.ix_(on, others)] = uv[on]
        normals[on, axis] = 2 * side - 1
    for k, side in ((4, 0), (5, 1)):
        on = np.flatnonzero(piece == k)
        xy = uv[on]
        in_bore = np.hypot(xy[:, 0] - 0.5, xy[:, 1] - 0.5) < BORE
        while in_bore.any():
            xy[in_bore] = rng.random((in_bore.sum(), 2))
            in_bore = np.hypot(xy[:, 0] - 0.5, xy[:, 1] - 0.5) < BORE
        points[on, :2], points[on, 2], normals[on, 2] = xy, side, 2 * side - 1
    on = piece == 6
    t = 2 * np.pi * uv[on, 0]
    points[on] = np.c_[0.5 + BORE * np.cos(t), 0.5 + BORE * np.sin(t), uv[on, 1]]
    normals[on] = -np.c_[np.cos(t), np.sin(t), np.zeros(on.sum())]
    return points, normals


def bored_cube_distance(p):
    """Distance to the surface of bored_cube_samples: the nearest of the
    nearest points of its pieces (four sides, two faces with a round
    opening, the bore's wall)."""
    clamped = np.clip(p, 0, 1)
    best = np.full(len(p), np.inf)
    for axis in (0, 1):
        for side in (0, 1):
            q = clamped.copy()
            q[:, axis] = side
            best = np.minimum(best, np.linalg.norm(p - q, axis=1))
    for side in (0, 1):
        q = clamped.copy()
        q[:, 2] = side
        r = np.hypot(q[:, 0] - 0.5, q[:, 1] - 0.5)
        out = np.where(r < BORE, BORE / np.maximum(r, 1e-12), 1.0)  # a point over the opening: its edge
        q[:, :2] = 0.5 + (q[:, :2] - 0.5) * out[:, None]
        best = np.minimum(best, np.linalg.norm(p - q, axis=1))
    r = np.maximum(np.hypot(p[:, 0] - 0.5, p[:, 1] - 0.5), 1e-12)
    wall = np.c_[0.5 + (p[:, :2] - 0.5) * (BORE / r)[:, None], np.clip(p[:, 2], 0, 1)]
    return np.minimum(best, np.linalg.norm(p - wall, axis=1))


def sphere_samples(n, seed):
    rng = np.random.default_rng(seed)
    v = rng.normal(size=(n, 3))
    v /= np.linalg.norm(v, axis=1)[:, None]
    return 0.5 + 0.5 * v, v


def sphere_distance(p):
    return np.abs(np.linalg.norm(p - 0.5, axis=1) - 0.5)


def cut(points, normals, balls):
    """Removes the samples inside any ball: (kept points, kept normals, removed points)."""
    inside = np.zeros(len(points), dtype=bool)
    for centre, radius in balls:
        inside |= np.linalg.norm(points - np.asarray(centre), axis=1) < radius
    return points[~inside], normals[~inside], points[inside]


def pitch(area):
    return np.sqrt(area / SAMPLES)


def gap(removed, output, reach=np.inf):
    """For each removed sample, the distance to the nearest output point
    (inf where none lies within reach: only the output points within reach
    of the removed samples' bounding box are compared, for large clouds)."""
    if np.isfinite(reach) and len(removed):
        near = np.all((output >= removed.min(axis=0) - reach) & (output <= removed.max(axis=0) + reach), axis=1)
        output = output[near]
    nearest = np.full(len(removed), np.inf)
    for start in range(0, len(output), 4096):
        block = output[start:start + 4096]
        d = np.linalg.norm(removed[:, None, :] - block[None, :, :], axis=2)
        nearest = np.minimum(nearest, d.min(axis=1))
    return nearest


@pytest.fixture(scope="module")
def corner():
    points, normals = cube_samples(SAMPLES, 1)
    return cut(points, normals, [((1, 1, 1), 0.2)])


def test_cube_corner_is_filled_sharp_and_the_input_is_untouched(corner):
    kept, kept_normals, removed = corner
    res = pcl_holefill.fill(kept, kept_normals, quiet=True)
    n = len(kept)
    assert res.points.dtype == np.float64
    assert np.array_equal(res.points[:n], kept)
    assert np.array_equal(res.normals[:n], kept_normals)
    assert not res.filled[:n].any() and res.filled[n:].all()
    assert len(res.reports) == 1 and res.reports[0]["closed"]
    assert res.reports[0]["sigma_n"] == pytest.approx(0.1)  # automatic: a clean, sharp rim
    # The report locates the hole: its boundary loop, as indices into the input rows.
    rim = kept[res.reports[0]["boundary"]]
    assert len(rim) >= 20
    distances = np.linalg.norm(rim - 1.0, axis=1)
    assert (distances >= 0.2 - 1e-9).all() and (distances <= 0.2 + 3 * pitch(6.0)).all()
    fill = res.points[res.filled]
    p = pitch(6.0)
    # Every removed sample within 1.5 pitches of an output point.
    assert gap(removed, res.points).max() <= 1.5 * p
    # reached 3e-8 (random samples, exact normals); the paper's Table 2 figure is 0.0046
    assert cube_distance(fill).max() < 0.001
    # Nothing farther than a pitch outside the cut ball.
    assert (np.linalg.norm(fill - 1, axis=1) <= 0.2 + p).all()


def test_sphere_cap_is_round():
    points, normals = sphere_samples(SAMPLES, 2)
    kept, kept_normals, removed = cut(points, normals, [((0.5, 0.5, 1.0), 0.15)])
    res = pcl_holefill.fill(kept.astype(np.float32), kept_normals.astype(np.float32), quiet=True)
    assert res.points.dtype == np.float32
    assert np.array_equal(res.points[:len(kept)], kept.astype(np.float32))
    p = pitch(np.pi)
    assert gap(removed, res.points.astype(np.float64)).max() <= 1.5 * p
    # reached 0.0021 (the sagitta of the cap is 0.023)
    assert sphere_distance(res.points[res.filled].astype(np.float64)).max() < 0.004


def noisy(points, normals, fraction, seed):
    """Points moved along their normals by Gaussian noise of std fraction x the diagonal."""
    sigma = fraction * np.sqrt(3.0)
    rng = np.random.default_rng(seed)
    return points + sigma * rng.normal(size=(len(points), 1)) * normals, sigma


@pytest.mark.parametrize("model", ["sphere", "cube"])
def test_noisy_random_samples_without_normals(model):
    """What a user of a mesh-sampling tool and a scanner has: uniformly random
    samples, noise of 0.3 % of the diagonal, no normals (estimated and
    oriented by the module). Judged on the noise-free truth: the surface to
    cover and the distance to the exact model, over five seeds."""
    samples, distance, area, ball, max_error = {
        "sphere": (sphere_samples, sphere_distance, np.pi, ((0.5, 0.85, 0.85), 0.13), 2.5),
        "cube": (cube_samples, cube_distance, 6.0, ((1, 1, 0.5), 0.15), 8.5),
    }[model]
    p = pitch(area)
    coverages = []
    for seed in (11, 21, 31, 41, 51):
        points, normals = samples(SAMPLES, seed)
        inside = np.linalg.norm(points - np.asarray(ball[0]), axis=1) < ball[1]
        moved, sigma = noisy(points, normals, 0.003, seed + 1)
        kept, missing = moved[~inside], points[inside]
        res = pcl_holefill.fill(kept, quiet=True)
        assert res.normals_estimated
        assert np.array_equal(res.points[:len(kept)], kept)
        assert len(res.reports) == 1, seed  # before the orientation vote: 0 on seeds 41 and 51
        fill = res.points[res.filled]
        coverages.append((gap(missing, res.points) <= 1.5 * p).mean())
        # reached: 99.5 % (cube, seed 31) to 100 %; max error 0.7 to 1.5 sigma
        # (sphere; 2.0 to 5.2 before its rough PCA normals were smoothed),
        # 2.7 to 7.4 sigma (cube edge); spill at most 1.1 pitches
        assert coverages[-1] >= 0.98, seed
        assert distance(fill).max() <= max_error * sigma, seed
        assert (np.linalg.norm(fill - np.asarray(ball[0]), axis=1) <= ball[1] + 2 * p).all(), seed
    assert np.mean(coverages) >= 0.99  # reached: 100 % (sphere), 99.9 % (cube)


@pytest.mark.parametrize("model,noise,bound", [
    ("sphere", 0.001, 0.003), ("sphere", 0.003, 0.009), ("cube", 0.001, 0.0098)])
def test_noisy_holes_from_estimated_normals(model, noise, bound):
    # Noisy random samples, normals estimated by the module (PCA, k = 16),
    # a sphere cap 32 pitches across or a cube corner, four seeds.
    # - Sphere: PCA normals at 0.3 % noise scatter by ~10 degrees, and the
    #   cap came out 0.03-0.22 off (80-94 % covered). Rough normals on a rim
    #   without a crease are now replaced by PCA over more neighbours, and
    #   the one-sided tilt at the rim by a quadric over more neighbours.
    #   Reached: 0.1 %: max error 0.0032-0.0042 (was 0.017-0.036); 0.3 %:
    #   0.0077-0.0147 (2.8 sigma at most); >= 99.9 % covered. With the
    #   quadric over up to 768 neighbours on such smoothed rims, and the
    #   module's normals over 27 neighbours at 0.3 %: 0.0015-0.0020 and
    #   0.0043-0.0063, 100 % covered.
    # - Cube corner at 0.1 % (0.27 pitch of noise): the crease refit now runs
    #   and the quadric takes more neighbours. Reached: 0.0033-0.0079 (was
    #   0.047-0.056); the bound is the target, 3 sigma + 0.0046.
    samples, distance, area, ball = {
        "sphere": (sphere_samples, sphere_distance, np.pi, ((0.5, 0.5, 1.0), 0.2)),
        "cube": (cube_samples, cube_distance, 6.0, ((1, 1, 1), 0.2)),
    }[model]
    for seed in (1, 2, 3, 4):
        points, normals = samples(SAMPLES, seed)
        kept, kept_normals, removed = cut(points, normals, [ball])
        moved = kept + kept_normals * np.random.default_rng(seed + 100).normal(
            size=(len(kept), 1)) * noise * np.sqrt(3)
        res = pcl_holefill.fill(moved, quiet=True)
        assert np.array_equal(res.points[:len(moved)], moved)
        assert distance(res.points[res.filled]).max() < bound, seed
        assert (gap(removed, res.points) <= 1.5 * pitch(area)).mean() >= 0.99, seed


@pytest.mark.parametrize("noise,bound", [(0.003, 0.025), (0.005, 0.03)])
def test_a_noisy_edge_with_exact_normals_stays_on_its_faces(noise, bound):
    # A cube edge hole (0.15 in radius) on noisy random samples with their
    # exact normals. The rim's tangent planes bounded the fill only on rims
    # under a quarter pitch of noise, and one face's front ran past the edge
    # before the other's reached it: 0.3 %: 0.097 (seed 3), 0.5 %: 0.110
    # (seed 4). The planes now bound every closed rim, at any noise (those
    # that support the rim). Reached: 0.3 %: 0.0036-0.018; 0.5 %: 0.006-0.020.
    for seed in (1, 2, 3, 4):
        points, normals = cube_samples(SAMPLES, seed)
        kept, kept_normals, removed = cut(points, normals, [((1, 1, 0.5), 0.15)])
        moved = kept + kept_normals * np.random.default_rng(seed + 100).normal(
            size=(len(kept), 1)) * noise * np.sqrt(3)
        res = pcl_holefill.fill(moved, kept_normals, quiet=True)
        assert np.array_equal(res.points[:len(moved)], moved)
        assert cube_distance(res.points[res.filled]).max() < bound, seed
        assert (gap(removed, res.points) <= 1.5 * pitch(6.0)).mean() >= 0.99, seed


@pytest.mark.parametrize("given_normals,bound,covered", [(True, 0.011, 0.9), (False, 0.02, 0.85)])
def test_a_hole_across_a_bore_edge_stays_on_the_part(given_normals, bound, covered):
    # A hole 0.2 in radius where the bore meets the bottom face, reaching
    # the side x = 0: flat faces, convex edges and the bore's concave wall
    # in one rim. The rim is not convex, so its tangent planes bounded
    # nothing, and the wall's front ran on below the bottom face: max error
    # 0.03-0.29 (exact normals), 0.13-0.15 (estimated). Now the planes of
    # the rim points that every other rim point lies below (the bottom face's
    # and the side's) bound it. Reached, seeds 1-3: exact 0.0009-0.0072,
    # estimated 0.0065-0.0110; covered 0.955-0.998 and 0.873-0.922 (seed 3
    # was 0.927 before a wall's point stopped bounding the face behind it:
    # the fronts met in another order and the last opening, on the bottom
    # face and 6 points of the bore's wall, was not taken up again).
    for seed in (1, 2, 3):
        points, normals = bored_cube_samples(SAMPLES, seed)
        kept, kept_normals, removed = cut(points, normals, [((0.194, 0.347, 0.0), 0.2)])
        res = pcl_holefill.fill(kept, kept_normals if given_normals else None, quiet=True)
        assert np.array_equal(res.points[:len(kept)], kept)
        assert bored_cube_distance(res.points[res.filled]).max() < bound, seed
        assert (gap(removed, res.points) <= 1.5 * pitch(7.08)).mean() >= covered, seed


@pytest.mark.parametrize("given_normals", [True, False])
def test_a_face_stops_at_a_bore_edge_whose_wall_the_hole_took(tmp_path, given_normals):
    # A hole 0.13 in radius centred on the bore's wall just above the bottom
    # face: the rim runs along the bottom face and up the wall. The bottom
    # face's front lay in its own plane, so no supporting plane held it, and
    # the wall's rim points are concave (their planes lie below it): it grew
    # on over the bore as a flat sheet. The rim's turn from face to wall and
    # back now gives the crease (a curve between the crossings, along the
    # faces' normals' cross product there), which holds the face. The
    # installed command, x y z (nx ny nz) text; seeds 1-3. Before: max error
    # 0.100-0.166; reached: 0.011-0.022 (exact normals), 0.016-0.024
    # (estimated). Covered 0.911-1.0 (before 0.971-0.994, partly by the sheet
    # that passed over the wall's foot; the wall's front now stops short of
    # it on one seed, and the hole is reported open).
    command = os.environ.get("PCL_HOLEFILL_COMMAND")
    assert command, "PCL_HOLEFILL_COMMAND must name the pcl_holefill command"
    centre = (0.5 + BORE * np.cos(2.0), 0.5 + BORE * np.sin(2.0), 0.07)
    for seed in (1, 2, 3):
        points, normals = bored_cube_samples(SAMPLES, seed)
        kept, kept_normals, removed = cut(points, normals, [(centre, 0.13)])
        np.savetxt(tmp_path / "in.xyz", np.c_[kept, kept_normals] if given_normals else kept, fmt="%.7f")
        subprocess.run([command, str(tmp_path / "in.xyz"), str(tmp_path / "out.xyz"), "-q"], check=True)
        out = np.loadtxt(tmp_path / "out.xyz")
        filled = out[out[:, -1] == 1][:, :3]
        assert np.array_equal(out[out[:, -1] == 0][:, :3], np.round(kept, 7)), seed
        assert bored_cube_distance(filled).max() < 0.035, seed
        assert (gap(removed, out[:, :3]) <= 1.5 * pitch(7.08)).mean() >= 0.88, seed


def test_a_lone_chain_of_three_stops(tmp_path):
    # A cube edge hole 0.15 in radius, 50,000 random samples drawn face by
    # face in one stream with their noise (0.1 %), written as x y z text and
    # filled by the installed command, which estimates the normals. The last
    # front was one open chain of three points, and it marched 27 passes into
    # the solid (max error 0.21). A boundary of fewer than 4 points now ends
    # the contraction. Reached: 0.070, covered 97.1 %.
    command = os.environ.get("PCL_HOLEFILL_COMMAND")
    assert command, "PCL_HOLEFILL_COMMAND must name the pcl_holefill command"
    rng = np.random.default_rng(1)
    n = 50000
    points, normals = cube_samples(n, None, rng)
    kept, kept_normals, removed = cut(points, normals, [((0.5, 0.0, 0.0), 0.15)])
    moved = kept + kept_normals * rng.normal(scale=0.001 * np.sqrt(3), size=(len(kept), 1))
    np.savetxt(tmp_path / "in.xyz", moved, fmt="%.7f")
    subprocess.run([command, str(tmp_path / "in.xyz"), str(tmp_path / "out.xyz"), "-q"], check=True)
    out = np.loadtxt(tmp_path / "out.xyz")
    filled = out[out[:, -1] == 1][:, :3]
    assert len(out) - len(filled) == len(moved)
    assert cube_distance(filled).max() < 0.09
    assert (gap(removed, out[:, :3]) <= 1.5 * np.sqrt(6.0 / n)).mean() >= 0.96


@pytest.mark.parametrize("noise", [0.0, 0.001])
def test_a_cube_without_its_underside_is_closed_across_it(noise):
    # The underside of a scanned object: a whole face missing, so the rim is
    # a crease all round and its normals (estimated here) lie along the
    # walls. The fronts carried the walls on down past the rim (max error
    # 1.07-1.10, 8 % of the face covered); now the fill runs across the
    # opening. 30,000 random samples, seeds 1-2; reached: max error 0.17-0.27
    # pitch, covered 99.4-100 %.
    n = 30000
    p = np.sqrt(6.0 / n)
    for seed in (1, 2):
        rng = np.random.default_rng(seed)
        points, normals = cube_samples(n, None, rng)
        bottom = points[:, 2] == 0.0
        kept = points[~bottom] + normals[~bottom] * rng.normal(scale=noise * np.sqrt(3), size=((~bottom).sum(), 1))
        res = pcl_holefill.fill(kept, None, quiet=True)
        assert np.array_equal(res.points[:len(kept)], kept)
        assert len(res.reports) == 1 and res.reports[0]["across_opening"], seed
        fill = res.points[res.filled]
        assert cube_distance(fill).max() < 0.5 * p + 3 * noise * np.sqrt(3), seed
        assert (gap(points[bottom], res.points) <= 1.5 * p).mean() >= 0.99, seed


def scan_line_box_without_underside(n, rng):
    """About n samples of the unit cube's five faces other than z = 0, on
    parallel lines 4 times farther apart than the points along them (a
    line scanner's pattern), jittered along the lines; the normals are left
    out. Returns the points and the pitch."""
    pitch = np.sqrt(5.0 / n)
    step, line_gap = pitch / 2, 2 * pitch
    u, v = np.meshgrid(np.arange(0.0, 1.0, step), np.arange(line_gap / 2, 1.0, line_gap))
    faces = []
    for axis, value in [(0, 0.0), (0, 1.0), (1, 0.0), (1, 1.0), (2, 1.0)]:
        uu = np.clip(u + rng.uniform(0, step, u.shape), 0.0, 1.0).ravel()
        others = [a for a in range(3) if a != axis]
        face = np.empty((uu.size, 3))
        face[:, axis] = value
        face[:, others[0]], face[:, others[1]] = uu, v.ravel()
        faces.append(face)
    return np.concatenate(faces), pitch


def command_with_report(tmp_path, points):
    """The installed command, with no option, on \a points written as x y z
    (7 decimals), its JSON report asked for: (output rows, filled points,
    the report's holes). The input points must come back unchanged."""
    import json
    command = os.environ.get("PCL_HOLEFILL_COMMAND")
    assert command, "PCL_HOLEFILL_COMMAND must name the pcl_holefill command"
    np.savetxt(tmp_path / "in.xyz", points, fmt="%.7f")
    subprocess.run([command, str(tmp_path / "in.xyz"), str(tmp_path / "out.xyz"), "-q",
                    "-report", str(tmp_path / "holes.json")], check=True)
    out = np.loadtxt(tmp_path / "out.xyz")
    assert np.array_equal(out[out[:, -1] == 0][:, :3], np.round(points, 7))
    return out, out[out[:, -1] == 1][:, :3], json.loads((tmp_path / "holes.json").read_text())["holes"]


def test_a_box_scanned_without_its_underside_is_closed_by_the_command(tmp_path):
    # A scan that never saw the underside, on scan lines, x y z only, as a
    # user runs it: the installed command estimates the normals, and its
    # JSON report tells the hole was closed across the opening. (The gtest
    # Openings.ABoxSampledWithoutItsLidIsClosedAcrossIt has the samplers on
    # which the first fill stopped at the rim.) Reached: flat at the lowest
    # line (1e-5 pitch off it), nothing past the walls, covered 100 %.
    points, p = scan_line_box_without_underside(30000, np.random.default_rng(4))
    out, filled, holes = command_with_report(tmp_path, points)
    assert len(holes) == 1 and holes[0]["across_opening"] and holes[0]["closed"]
    # The lowest scan line runs a pitch above the crease: nothing tells
    # where below it the face is, and the fill lies flat at that line.
    lowest = points[:, 2].min()
    assert np.abs(filled[:, 2] - lowest).max() < 0.25 * p
    assert (np.abs(np.clip(filled[:, :2], 0.0, 1.0) - filled[:, :2]) < 0.5 * p).all()
    underside = np.c_[np.random.default_rng(5).random((3000, 2)), np.full(3000, lowest)]
    assert (gap(underside, out[:, :3], 2 * p) <= 1.5 * p).mean() >= 0.99


def test_a_single_view_scan_gets_no_patch_past_its_holes(tmp_path):
    # A bored cube scanned from one side (x y z only, as a user runs the
    # command): the scan sees part of the bore's wall, and the loop around
    # the rest (the bore's near edge and the wall's shadow line) reads as a
    # hole. Its fill ran the wall on past the bore's end (3,624 points, up
    # to 24.5 pitches off the part) and was written, reported open; it is
    # withdrawn now (the report says so), while a hole cut into a side is
    # filled. Reached: the filled points on the part (0.00 pitch off: a
    # flat face), the cut hole covered 100 %.
    dense, dense_normals = bored_cube_samples(600000, 8)
    points, normals = single_view(dense, dense_normals, np.array([2.0, 1.8, 2.5]), SAMPLES)
    # The pixels' footprint: about the nearest-neighbour distance of a grid.
    p = np.median(np.sort(np.linalg.norm(points[:1000, None] - points[None], axis=2), axis=1)[:, 1])
    kept, _, removed = cut(points, normals, [((1.0, 0.55, 0.45), 8 * p)])
    out, filled, holes = command_with_report(tmp_path, kept)
    assert any(h["withdrawn"] and h["points_added"] == 0 and not h["closed"] for h in holes)
    assert len(filled) > 0 and bored_cube_distance(filled).max() < 1.0 * p
    assert (gap(removed, out[:, :3]) <= 1.5 * p).mean() >= 0.99


def ridge_samples(n, seed):
    """Uniformly random samples of a 90 degree ridge, z = 0.5 + y up to
    y = 0.5 and 1.5 - y beyond (x, y in [0, 1]), exact normals."""
    rng = np.random.default_rng(seed)
    x, y = rng.random(n), rng.random(n)
    points = np.c_[x, y, np.where(y < 0.5, 0.5 + y, 1.5 - y)]
    normals = np.where((y < 0.5)[:, None], [0.0, -1.0, 1.0], [0.0, 1.0, 1.0]) / np.sqrt(2)
    return points, normals


def test_holes_in_noisy_random_samples_are_found_from_pca_normals():
    # Noise 0.5 % of the diagonal (0.7 pitch), normals by Open3D's PCA
    # (k = 16) oriented as the true ones: at a rim they tilt by up to
    # 1.4 rad. The empty-disc test unfolded the neighbours along those normals
    # into the disc, and the loop tracing would not link rim points whose
    # normals came out more than 120 degrees apart (a ridge hole stayed two
    # open halves). Three holes (on the ridge, on each face) over five seeds:
    # 9 of 15 found before, 14 now; none where no hole was cut.
    import open3d as o3d
    balls = [((0.5, 0.5, 1.0), 0.07), ((0.3, 0.25, 0.75), 0.05), ((0.7, 0.78, 0.72), 0.06)]
    found = 0
    for seed in (1, 2, 3, 4, 5):
        points, normals = ridge_samples(25000, seed)
        kept, kept_normals, _ = cut(points, normals, balls)
        moved = kept + kept_normals * np.random.default_rng(seed + 100).normal(
            size=(len(kept), 1)) * 0.005 * np.sqrt(3)
        cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(moved))
        cloud.estimate_normals(o3d.geometry.KDTreeSearchParamKNN(16))
        pca = np.asarray(cloud.normals)
        pca *= np.sign((pca * kept_normals).sum(axis=1))[:, None]
        loops = pcl_holefill.detect_holes(moved, pca)
        near = [[np.linalg.norm(moved[loop].mean(axis=0) - np.asarray(c)) < r + 0.03 for c, r in balls]
                for loop in loops]
        assert all(any(n) for n in near), seed  # no hole where none was cut
        found += sum(any(n[b] for n in near) for b in range(len(balls)))
    assert found >= 14  # reached: 14 of 15 (one missed on seed 5); 9 on 0455018


def test_noisy_random_samples_without_a_hole_come_back_unchanged():
    points, normals = sphere_samples(SAMPLES, 13)
    moved, _ = noisy(points, normals, 0.003, 14)
    res = pcl_holefill.fill(moved, quiet=True)
    assert len(res.points) == len(moved) and not res.filled.any() and not res.reports


def test_detect_holes_finds_two_holes_and_fill_takes_them():
    points, normals = cube_samples(SAMPLES, 3)
    balls = [((1, 1, 1), 0.2), ((0.5, 0.5, 0.0), 0.12)]
    kept, kept_normals, removed = cut(points, normals, balls)
    loops = pcl_holefill.detect_holes(kept, kept_normals)
    assert len(loops) == 2
    for centre, radius in balls:
        around = [loop for loop in loops
                  if np.median(np.linalg.norm(kept[loop] - np.asarray(centre), axis=1)) < radius + 3 * pitch(6.0)]
        assert len(around) == 1
    assert all(loop.dtype == np.int64 and loop.ndim == 1 for loop in loops)
    res = pcl_holefill.fill(kept, kept_normals, holes=loops[:1], quiet=True)
    assert len(res.reports) == 1 and res.filled.any()
    # 'auto' is the default (0): the min hole size chosen from the sampling.
    assert pcl_holefill.DEFAULTS["min_hole_size"] == 0
    auto = pcl_holefill.detect_holes(kept, kept_normals, min_hole_size="auto")
    assert [list(a) for a in auto] == [list(loop) for loop in loops]


def test_normals_are_estimated_when_not_given(corner):
    kept, _, removed = corner
    res = pcl_holefill.fill(kept, quiet=True)
    assert res.normals_estimated
    # Estimated normals face out of the cube, every one.
    n = len(kept)
    assert (np.einsum("ij,ij->i", res.normals[:n], kept - 0.5) > 0).all()
    # The output keeps the estimated normals of the input rows (the fill
    # refits those PCA blended across the edges for itself only).
    again = pcl_holefill.fill(kept, res.normals[:n], quiet=True)
    assert np.array_equal(again.normals[:n], res.normals[:n])


@pytest.mark.parametrize("seed", [1, 2, 3, 4, 5, 6])
def test_corner_is_filled_sharp_from_estimated_normals(seed):
    # PCA normals turn across every edge within ~2 pitches of it; refitted
    # to their faces, the corner comes back sharp. Before the refit, these
    # six clouds were 89-98 % covered with max errors 0.016-0.11.
    # Reached: 98.8-100 % covered, max errors 0.0004-0.028, no removed
    # sample farther than 2.07 pitches from the output.
    points, normals = cube_samples(SAMPLES, seed)
    kept, _, removed = cut(points, normals, [((1, 1, 1), 0.2)])
    res = pcl_holefill.fill(kept, quiet=True)
    gaps = gap(removed, res.points) / pitch(6.0)
    assert (gaps <= 1.5).mean() >= 0.98
    assert cube_distance(res.points[res.filled]).max() < 0.035
    # A hole reported closed has no empty part wider than about 2 spacings.
    if res.reports[0]["closed"]:
        assert gaps.max() <= 2.2
    else:
        assert res.reports[0]["open_diameter"] > 0


@pytest.mark.parametrize("seed", [1, 2, 3, 4])
def test_sphere_cap_keeps_its_curvature_from_estimated_normals(seed):
    # A rim point's PCA normal is fitted to neighbours on one side of it and
    # leans away from the hole; the fill continued that lean and the cap came
    # out 0.014-0.017 too high (1.1-1.4 pitches). The normals near the rim
    # are refitted by a quadric. Reached: max error under 0.0001, 99.8-99.9 %
    # of the removed samples within 1.5 pitches.
    points, normals = sphere_samples(SAMPLES, seed)
    kept, _, removed = cut(points, normals, [((0.5, 0.5, 1.0), 0.2)])
    res = pcl_holefill.fill(kept, quiet=True)
    assert res.reports[0]["refitted_normals"] > 0
    assert sphere_distance(res.points[res.filled]).max() < 0.002
    assert (gap(removed, res.points) <= 1.5 * pitch(np.pi)).mean() >= 0.99


@pytest.mark.parametrize("seed", [5, 6])
def test_a_large_corner_hole_stays_on_the_cube(seed):
    # A corner hole 0.6 across on 100,000 random samples: one face's front
    # reached the corner before the others and ran on past it (seed 5: max
    # error 0.20, reported open). The fill of a convex rim now stays below
    # the rim's tangent planes. Reached: max error 0.0043 and 0.0000, both
    # closed, 100 % of the removed samples within 1.5 pitches.
    n = 100000
    points, normals = cube_samples(n, seed)
    kept, kept_normals, removed = cut(points, normals, [((1, 1, 1), 0.3)])
    res = pcl_holefill.fill(kept, kept_normals, quiet=True)
    assert cube_distance(res.points[res.filled]).max() < 0.01
    assert (gap(removed, res.points, 2 * np.sqrt(6.0 / n)) <= 1.5 * np.sqrt(6.0 / n)).mean() >= 0.99


def poisson_disk(points, normals, radius, seed):
    """Dart throwing: the candidates in random order, each kept when no kept
    point lies within radius (a grid of radius-sized cells). Another sampler
    than the uniform one, whose habits the code may have learnt."""
    order = np.random.default_rng(seed).permutation(len(points))
    cells = {}
    kept = []
    for i in order:
        key = tuple(np.floor(points[i] / radius).astype(int))
        near = (cells.get((key[0] + a, key[1] + b, key[2] + c), ())
                for a in (-1, 0, 1) for b in (-1, 0, 1) for c in (-1, 0, 1))
        if all(np.linalg.norm(points[j] - points[i]) >= radius for group in near for j in group):
            cells.setdefault(key, []).append(i)
            kept.append(i)
    kept = np.array(kept)
    return points[kept], normals[kept]


def check_noisy_cap_on_poisson_disk_samples(noise, radius, bound):
    """A cap cut from dart-throwing samples of the sphere (~17,000 of 80,000
    random candidates), moved along the normal by noise (share of the
    diagonal), filled from the module's estimated normals, for seeds 1-3:
    input untouched, max error < bound, >= 99 % of the cut samples covered."""
    for seed in (1, 2, 3):
        candidates, candidate_normals = sphere_samples(80000, seed)
        points, normals = poisson_disk(candidates, candidate_normals, 0.75 * pitch(np.pi), seed)
        kept, kept_normals, removed = cut(points, normals, [((0.5, 0.5, 1.0), radius)])
        moved = kept + kept_normals * np.random.default_rng(seed + 7).normal(
            size=(len(kept), 1)) * noise * np.sqrt(3)
        res = pcl_holefill.fill(moved, quiet=True)
        assert np.array_equal(res.points[:len(moved)], moved)
        assert sphere_distance(res.points[res.filled]).max() < bound, seed
        spacing = np.sqrt(np.pi / len(points))
        assert (gap(removed, res.points) <= 1.5 * spacing).mean() >= 0.99, seed


@pytest.mark.parametrize("noise,bound", [(0.001, 0.006), (0.003, 0.016)])
def test_noisy_cap_on_poisson_disk_samples_from_estimated_normals(noise, bound):
    # The noisy caps above on a second sampler. Before the rough normals were
    # smoothed: 0.1 %: max error 0.010-0.023; 0.3 %: 0.027-0.041, 85-96 %
    # covered (three seeds). Reached: 0.0031-0.0039 and 0.0105-0.0128, 100 %.
    check_noisy_cap_on_poisson_disk_samples(noise, 0.2, bound)


@pytest.mark.parametrize("noise,bound", [(0.003, 0.008), (0.005, 0.011)])
def test_a_large_noisy_cap_from_estimated_normals_stays_on_the_sphere(noise, bound):
    # A cap 0.3 in radius (a third of the sphere's height). The quadric that
    # takes the one-sided tilt out of the rim's normals ran only on rims under
    # 0.6 pitch of noise allowance, and its crease test read the raw PCA
    # normals beyond the smoothed band: the rim kept a tilt of ~1.6 degrees,
    # and the fill rode up to 0.03 above the cap, 82-95 % covered and reported
    # closed. Reached (three seeds): 0.3 % 0.0053-0.0056, 0.5 % 0.0072-0.0085,
    # 100 % covered.
    check_noisy_cap_on_poisson_disk_samples(noise, 0.3, bound)


def noisy_dense_cap(seed, noise):
    """A cap 0.3 in radius cut from 100,000 uniformly random sphere samples,
    moved along the normal by noise (share of the diagonal; noise seed 100 +
    seed): (moved points, their exact normals, removed samples, pitch)."""
    n = 100000
    points, normals = sphere_samples(n, seed)
    kept, kept_normals, removed = cut(points, normals, [((0.5, 0.5, 1.0), 0.3)])
    moved = kept + kept_normals * np.random.default_rng(100 + seed).normal(size=(len(kept), 1)) * noise * np.sqrt(3)
    return moved, kept_normals, removed, np.sqrt(np.pi / n)


def assert_sphere_fill(res, moved, removed, spacing, bound, covered):
    """The input rows untouched, every filled point within bound of the
    sphere, and at least the share covered of the removed samples within 1.5
    spacings of an output point."""
    assert np.array_equal(res.points[:len(moved)], moved)
    assert sphere_distance(res.points[res.filled]).max() < bound
    assert (gap(removed, res.points, 2 * spacing) <= 1.5 * spacing).mean() >= covered


@pytest.mark.parametrize("seed", [1, 2])
def test_a_large_noisy_hole_from_estimated_normals_on_dense_random_samples(seed):
    # The same cap on 100,000 uniformly random samples at 0.1 % noise (0.3
    # pitch), normals estimated by the module: 0.030-0.033 off and 55-69 %
    # covered before; the quadric needed ~1,600 neighbours per unit of noise
    # (noise / spacing), here 768: 384 left 0.008-0.010 and 98-100 %.
    # Reached over seeds 1-8: 0.0031-0.0070, 100 % covered.
    moved, _, removed, spacing = noisy_dense_cap(seed, 0.001)
    assert_sphere_fill(pcl_holefill.fill(moved, quiet=True), moved, removed, spacing, 0.006, 0.99)


def test_a_hole_in_a_cloud_noisier_than_its_pitch_is_found():
    # 100,000 random sphere samples at 0.3 % noise: 0.9 pitch. PCA over PCL's
    # 16 neighbours scatters the normals by 25 degrees, the orientation walk
    # left 1.2 % of them flipped, and the cap 0.3 in radius was found on one
    # seed of six. The module now measures the noise (PCA over 64 neighbours
    # of 2,000 points) and estimates the normals over 64 per pitch of it (56
    # here). Reached, seeds 1-3: found every time, max error 0.011-0.017
    # (3 sigma is 0.016), 90-97 % covered.
    moved, _, removed, spacing = noisy_dense_cap(1, 0.003)
    loops = pcl_holefill.detect_holes(moved)
    assert len(loops) == 1
    assert np.linalg.norm(moved[loops[0]] - [0.5, 0.5, 1.0], axis=1).max() < 0.3 + 0.02
    assert_sphere_fill(pcl_holefill.fill(moved, quiet=True), moved, removed, spacing, 0.022, 0.93)


def test_a_large_noisy_hole_is_found_whole():
    # A cap 0.3 in radius cut from 100,000 random samples of the sphere at
    # 0.1 % noise: the rim's flagged points left two gaps of 4.6 and 5.9
    # pitches (the link is 4.5), the walk gave two open pieces, and the hole
    # was neither reported nor filled. Open pieces continuing each other
    # across up to 2 links are now joined. Reached, exact normals: one
    # closed hole, 100 % covered, max error 0.0016. (With normals estimated
    # from the noisy points: the test on dense random samples above.)
    moved, kept_normals, removed, spacing = noisy_dense_cap(1, 0.001)
    assert len(pcl_holefill.detect_holes(moved)) == 1
    res = pcl_holefill.fill(moved, kept_normals, quiet=True)
    assert len(res.reports) == 1 and res.reports[0]["closed"]
    assert_sphere_fill(res, moved, removed, spacing, 0.003, 0.99)


def test_extra_columns_come_back_for_the_filled_points(corner):
    kept, kept_normals, _ = corner
    colour = np.tile(np.array([[7, 8, 9]], dtype=np.uint8), (len(kept), 1))
    res = pcl_holefill.fill(kept, kept_normals, extra=colour, quiet=True)
    assert res.extra.dtype == np.uint8 and res.extra.shape == (len(res.points), 3)
    assert (res.extra == [7, 8, 9]).all()


def test_large_coordinates_keep_their_precision(corner):
    kept, kept_normals, _ = corner
    shift = np.array([512345.678, 5401234.567, 312.5])
    near = pcl_holefill.fill(kept, kept_normals, quiet=True)
    far = pcl_holefill.fill(kept + shift, kept_normals, quiet=True)
    assert np.array_equal(far.points[:len(kept)], kept + shift)
    assert far.filled.sum() > 0
    # The same fill, shifted: within 1e-4 of the cloud's size (1), point for point
    # when the counts agree, else as sets.
    back = far.points[far.filled] - shift
    assert cube_distance(back).max() < 0.001
    d = gap(back, near.points[near.filled])
    assert np.median(d) < 1e-4 and abs(int(far.filled.sum()) - int(near.filled.sum())) <= 2
    assert np.allclose(far.reports[0]["centre"], np.asarray(near.reports[0]["centre"]) + shift, atol=1e-4)


def test_nan_rows_are_kept_and_skipped(corner):
    kept, kept_normals, removed = corner
    points = kept.copy()
    points[::100] = np.nan
    res = pcl_holefill.fill(points, kept_normals, quiet=True)
    assert np.array_equal(res.points[:len(points)], points, equal_nan=True)
    assert np.isfinite(res.points[res.filled]).all()
    assert res.filled.any()


@pytest.mark.parametrize("call, error, text", [
    (lambda p, n: pcl_holefill.fill(p[:, :2]), ValueError, "shape (N, 3)"),
    (lambda p, n: pcl_holefill.fill(p.astype(np.int32)), TypeError, "float32 or float64"),
    (lambda p, n: pcl_holefill.fill(p[:0]), ValueError, "empty"),
    (lambda p, n: pcl_holefill.fill(np.full((10, 3), np.nan)), ValueError, "no finite row"),
    (lambda p, n: pcl_holefill.fill(p, n[:-1]), ValueError, "shape of points"),
    (lambda p, n: pcl_holefill.fill(p, n, radius=-1), ValueError, "radius takes a number"),
    (lambda p, n: pcl_holefill.fill(p, n, sigma_n="sharp"), ValueError, "sigma_n takes a number >= 0, 'auto' (= 0) or 'sup'"),
    (lambda p, n: pcl_holefill.fill(p, n, sigma_n=[1]), TypeError, "sigma_n takes"),
    (lambda p, n: pcl_holefill.fill(p, n, max_passes=-1), ValueError, "max_passes takes a whole number"),
    (lambda p, n: pcl_holefill.fill(p, n, min_hole_size=1), ValueError, "or 'auto' (= 0)"),
    (lambda p, n: pcl_holefill.fill(p, n, min_hole_size="small"), ValueError, "min_hole_size takes a number"),
    (lambda p, n: pcl_holefill.fill(p, n, max_passes=2.5), TypeError, "whole number"),
    (lambda p, n: pcl_holefill.fill(p, n, threads=-1), ValueError, "threads takes a whole number"),
    (lambda p, n: pcl_holefill.fill(p, n, spacing=True), TypeError, "takes a number"),
    (lambda p, n: pcl_holefill.fill(p, n, denoise=1), TypeError, "True or False"),
    (lambda p, n: pcl_holefill.fill(p, n, colour=1), TypeError, "unknown option"),
    (lambda p, n: pcl_holefill.fill(p, n, holes=[[0, 1, len(p)]]), ValueError, "not a row of points"),
    (lambda p, n: pcl_holefill.fill(p, n, holes=[[0, 1]]), ValueError, "at least 3 points"),
    (lambda p, n: pcl_holefill.fill(p, n, extra=np.zeros(3)), ValueError, "one row per point"),
    (lambda p, n: pcl_holefill.detect_holes(p, n, radius=1.0), TypeError, "detect_holes takes"),
])
def test_bad_input_raises_a_clear_exception(corner, call, error, text):
    kept, kept_normals, _ = corner
    with pytest.raises(error) as caught:
        call(kept, kept_normals)
    assert text in str(caught.value)


def test_threads_give_the_same_result_and_calls_run_side_by_side(corner):
    kept, kept_normals, _ = corner
    one = pcl_holefill.fill(kept, kept_normals, threads=1, quiet=True)
    results = [None, None]

    def run(i):
        results[i] = pcl_holefill.fill(kept, kept_normals, threads=2, quiet=True)

    workers = [threading.Thread(target=run, args=(i,)) for i in range(2)]
    for w in workers:
        w.start()
    for w in workers:
        w.join()
    for r in results:
        assert np.array_equal(r.points, one.points)


def test_every_option_is_documented():
    text = pcl_holefill.fill.__doc__
    for name, default in pcl_holefill.DEFAULTS.items():
        assert name in text and repr(default) in text


def read_pcd(path):
    """x y z normal_x normal_y normal_z of a binary or ASCII PCD file."""
    with open(path, "rb") as f:
        header = {}
        while True:
            line = f.readline().decode().strip()
            key, _, value = line.partition(" ")
            header[key] = value.split()
            if key == "DATA":
                break
        names, sizes, types = header["FIELDS"], [int(s) for s in header["SIZE"]], header["TYPE"]
        counts = [int(c) for c in header.get("COUNT", ["1"] * len(names))]
        n = int(header["POINTS"][0])
        if header["DATA"][0] == "ascii":
            table = np.loadtxt(f, ndmin=2)
            columns = {name: table[:, i] for i, name in enumerate(names)}
        else:
            dtype = np.dtype([(name if name != "_" else f"_{i}", {"F": "<f", "U": "<u", "I": "<i"}[t] + str(s), (c,))
                              for i, (name, s, t, c) in enumerate(zip(names, sizes, types, counts))])
            data = np.frombuffer(f.read(n * dtype.itemsize), dtype=dtype)
            columns = {name: data[name][:, 0] for name in dtype.names}
    pick = lambda *k: np.stack([columns[c] for c in k], axis=1)
    return pick("x", "y", "z"), pick("normal_x", "normal_y", "normal_z")


def test_same_result_as_the_installed_command(corner, tmp_path):
    command = os.environ.get("PCL_HOLEFILL_COMMAND")
    assert command, "PCL_HOLEFILL_COMMAND must name the pcl_holefill command"
    kept, kept_normals, _ = corner
    points, normals = kept.astype(np.float32), kept_normals.astype(np.float32)
    with open(tmp_path / "in.pcd", "w") as f:
        f.write("VERSION .7\nFIELDS x y z normal_x normal_y normal_z\nSIZE 4 4 4 4 4 4\nTYPE F F F F F F\n"
                f"COUNT 1 1 1 1 1 1\nWIDTH {len(points)}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\n"
                f"POINTS {len(points)}\nDATA ascii\n")
        np.savetxt(f, np.hstack([points, normals]), fmt="%.9g")
    subprocess.run([command, str(tmp_path / "in.pcd"), str(tmp_path / "out.pcd"), "-q"], check=True)
    out_points, out_normals = read_pcd(tmp_path / "out.pcd")
    res = pcl_holefill.fill(points, normals, quiet=True)
    assert out_points.shape == res.points.shape
    assert np.array_equal(out_points, res.points)
    assert np.array_equal(out_normals, res.normals)
