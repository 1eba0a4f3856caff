# pcl_holefill: shape controllable hole filling for oriented point clouds.
# SPDX-License-Identifier: BSD-3-Clause
"""Fill the holes of a point cloud, from numpy arrays.

    import numpy as np, pcl_holefill
    res = pcl_holefill.fill(points)            # (N, 3) float32 or float64
    res.points[:len(points)]                   # the input rows, unchanged
    res.points[res.filled]                     # the filled points
    res.reports                                # one dict per hole
    loops = pcl_holefill.detect_holes(points)  # input indices around each hole

The method is Li et al., "Shape controllable geometry completion for point
cloud models" (The Visual Computer), as the PCL module pcl_holefill and its
command implement it: the options are the command's (`pcl_holefill -h`),
with the same names, defaults, ranges and messages.
"""

import json

import numpy as np

from . import _pcl_holefill as _ext

__all__ = ["fill", "detect_holes", "FillResult", "DEFAULTS"]

#: The command's defaults, by option name (taken from the C++ filter).
DEFAULTS = {name: float(f"{value:.7g}") if isinstance(value, float) else value
            for name, value in _ext.defaults().items()}

# Option name -> what it takes. Every one maps to the command's -name.
_FLOATS = ("radius", "sigma_r", "sigma_d", "shrink", "ratio", "spacing", "min_hole_size", "max_hole_size")
_INTS = ("max_passes", "threads")
_FLAGS = ("zero_order", "denoise", "quiet")

_OPTION_HELP = {
    "radius": "neighbourhood radius r of eq. (1), (7) in cloud units; 0 = max(4h, 3.5p, 2.5 d_eq)",
    "sigma_n": "normal dissimilarity std (no unit), 'auto' (= 0, per hole: 2 x the spread of the "
               "rim's normals, within 0.1..0.3) or 'sup' to switch it off (round patches); "
               "small values recover sharp edges",
    "sigma_r": "elastic force width; d_eq = sigma_r^2 ln(1e4); 0 = d_eq from spacing",
    "spacing": "d_eq = spacing x sampling pitch when sigma_r is 0 (0.25..10)",
    "sigma_d": "distance weight std; 0 = r / 2",
    "shrink": "r <- r / shrink after each pass (>= 1; the paper's 1.1)",
    "ratio": "stop a hole when kept control points / boundary points < ratio (0..0.999)",
    "max_passes": "bound on contraction passes per hole (0..100000); 0 = 4 x hole diameter / d_eq + 20",
    "zero_order": "the paper's eq. (1) as printed (cones on smooth holes)",
    "denoise": "bilateral preprocessing first (moves input points)",
    "min_hole_size": "smallest hole: an empty disc this many sampling pitches across (2..100), or "
                     "'auto' (= 0: from how evenly the cloud is sampled, 6 on uniformly random samples, "
                     "4 on even ones)",
    "max_hole_size": "leave holes wider than this (cloud units) alone; 0 = fill all",
    "threads": "0 = all cores (the output does not depend on it)",
    "quiet": "print errors only, no warnings",
}


def _options_doc():
    lines = []
    for name, text in _OPTION_HELP.items():
        lines.append(f"    {name} (default {DEFAULTS[name]!r}): {text}")
    return "\n".join(lines)


class FillResult:
    """What fill() returns.

    Attributes:
        points:   (M, 3) array, the N input rows unchanged (same dtype), then the filled points.
        normals:  (M, 3) array, the input normals (or the estimated ones), then the filled points'.
        filled:   (M,) bool, False for the N input rows, True for the filled points.
        reports:  list of dicts, one per hole: the fields of the command's JSON report
                  ("closed", "points_added", "first_output_index", "centre", "diameter", ...).
        extra:    (M, k) array when extra columns were given: the input's, then for each
                  filled point those of its nearest input row; None otherwise.
        normals_estimated: True when the normals were estimated (normals=None).
    """

    def __init__(self, points, normals, filled, reports, extra, normals_estimated):
        self.points = points
        self.normals = normals
        self.filled = filled
        self.reports = reports
        self.extra = extra
        self.normals_estimated = normals_estimated

    def __repr__(self):
        return (f"FillResult({len(self.points)} points, {int(self.filled.sum())} filled, "
                f"{len(self.reports)} holes)")


def _rows(name, array, allow_none=False):
    """(N, 3) float32 or float64, or a clear exception."""
    if array is None:
        if allow_none:
            return None
        raise TypeError(f"{name} is required")
    a = np.asarray(array)
    if a.dtype not in (np.float32, np.float64):
        raise TypeError(f"{name} must be a float32 or float64 array, not {a.dtype}")
    if a.ndim != 2 or a.shape[1] != 3:
        raise ValueError(f"{name} must have shape (N, 3), not {a.shape}")
    if a.shape[0] == 0:
        raise ValueError(f"{name} is empty")
    return a


def _words(options):
    """The command's words for the given options (unknown names are refused)."""
    words = []
    for name, value in options.items():
        if value is None:
            continue
        if name in _FLAGS:
            if not isinstance(value, (bool, np.bool_)):
                raise TypeError(f"{name} takes True or False, not {value!r}")
            if value:
                words.append("-q" if name == "quiet" else "-" + name)
        elif name == "sigma_n":
            if isinstance(value, str):
                words += ["-sigma_n", value]
            elif isinstance(value, (int, float, np.floating, np.integer)) and not isinstance(value, bool):
                words += ["-sigma_n", "sup" if np.isinf(value) and value > 0 else repr(float(value))]
            else:
                raise TypeError(f"sigma_n takes a number, 'auto' or 'sup', not {value!r}")
        elif name in _INTS:
            if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
                raise TypeError(f"{name} takes a whole number, not {value!r}")
            words += ["-" + name, str(int(value))]
        elif name == "min_hole_size" and isinstance(value, str):
            words += ["-min_hole_size", value]
        elif name in _FLOATS:
            if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
                raise TypeError(f"{name} takes a number, not {value!r}")
            words += ["-" + name, repr(float(value))]
        else:
            raise TypeError(f"unknown option {name!r}; the options are: " + ", ".join(sorted(_OPTION_HELP)))
    return words


def _call(function, *args):
    """Runs the extension; its messages name the command's -options: name them as keywords."""
    try:
        return function(*args)
    except ValueError as error:
        message = str(error)
        if message.startswith("-"):
            message = message[1:]
        raise ValueError(message) from None


def _frame(points):
    """float32 coordinates to compute on, and the shift back to the input's frame.

    float64 input is shifted to its mean first, so that georeferenced
    coordinates (x = 512345.678 m) keep their precision in the float32
    computation. float32 input is shifted as the command shifts a file: to
    the centre of its bounding box when it lies farther from the origin than
    its own size (its values are exact, but their differences would round),
    else not at all, so that module and command give the same points."""
    finite = np.isfinite(points).all(axis=1)
    if not finite.any():
        return np.ascontiguousarray(points, dtype=np.float32), np.zeros(3)
    kept = points[finite].astype(np.float64)
    if points.dtype == np.float64:
        centre = kept.mean(axis=0)
    else:
        low, high = kept.min(axis=0), kept.max(axis=0)
        centre = (low + high) / 2
        if np.linalg.norm(centre) <= np.linalg.norm(high - low):
            return np.ascontiguousarray(points, dtype=np.float32), np.zeros(3)
    return np.ascontiguousarray(points.astype(np.float64) - centre, dtype=np.float32), centre


def _checked_input(points, normals):
    points = _rows("points", points)
    normals = _rows("normals", normals, allow_none=True)
    if normals is not None and normals.shape != points.shape:
        raise ValueError(f"normals must have the shape of points {points.shape}, not {normals.shape}")
    if not np.isfinite(points).all(axis=1).any():
        raise ValueError("points has no finite row")
    return points, normals


def fill(points, normals=None, holes=None, extra=None, **options):
    pts, nrm = _checked_input(points, normals)
    if extra is not None:
        extra = np.asarray(extra)
        if extra.ndim == 1:
            extra = extra[:, None]
        if extra.ndim != 2 or extra.shape[0] != pts.shape[0]:
            raise ValueError(f"extra must have one row per point ({pts.shape[0]}), not shape {extra.shape}")
    loops = []
    for loop in holes or []:
        indices = np.asarray(loop)
        if indices.ndim != 1 or not np.issubdtype(indices.dtype, np.integer):
            raise TypeError("holes must be a list of 1-D integer arrays of point indices")
        loops.append([int(i) for i in indices])
    local, centre = _frame(pts)
    local_normals = None if nrm is None else np.ascontiguousarray(nrm, dtype=np.float32)
    out = _call(_ext.fill, local, local_normals, _words(options), loops)

    n = pts.shape[0]
    added = out["points"].shape[0] - n
    result_points = np.empty((n + added, 3), dtype=pts.dtype)
    result_points[:n] = pts
    result_points[n:] = (out["points"][n:].astype(np.float64) + centre).astype(pts.dtype)
    result_normals = np.empty((n + added, 3), dtype=pts.dtype)
    result_normals[:n] = nrm if nrm is not None else out["normals"][:n]
    result_normals[n:] = out["normals"][n:]
    filled = np.zeros(n + added, dtype=bool)
    filled[n:] = True
    reports = json.loads(out["report"])["holes"]
    for report in reports:
        report["centre"] = (np.asarray(report["centre"], dtype=np.float64) + centre).tolist()
    result_extra = None
    if extra is not None:
        result_extra = np.concatenate([extra, extra[np.maximum(out["nearest"], 0)]], axis=0)
    return FillResult(result_points, result_normals, filled, reports, result_extra, out["normals_estimated"])


fill.__doc__ = f"""Fills the holes of a point cloud.

Args:
    points:  (N, 3) float32 or float64 array. Rows with NaN are kept as they are and
             skipped. float64 rows are computed in a frame centred on the cloud, so
             large (georeferenced) coordinates keep their precision.
    normals: (N, 3) array of unit normals, or None to estimate them (PCA over 16
             neighbours, more on noisy clouds; consistently oriented), as the
             command does.
    holes:   None to detect the holes, or a list of integer arrays, each the input
             indices around one hole, in order (the command's -holes).
    extra:   optional (N, k) array of per-point columns (colour, intensity, ...): filled
             points take the row of their nearest input point.

Options (keywords; the command's options, same names and defaults):
{_options_doc()}

Returns:
    FillResult: points, normals, filled, reports, extra (see FillResult).

Raises:
    TypeError, ValueError: wrong shape, dtype or option, with the reason.
"""


def detect_holes(points, normals=None, **options):
    pts, nrm = _checked_input(points, normals)
    unknown = set(options) - {"min_hole_size", "max_hole_size", "threads", "quiet"}
    if unknown:
        raise TypeError(f"detect_holes takes min_hole_size, max_hole_size, threads and quiet, not "
                        f"{', '.join(sorted(unknown))}")
    local, _ = _frame(pts)
    local_normals = None if nrm is None else np.ascontiguousarray(nrm, dtype=np.float32)
    out = _call(_ext.detect_holes, local, local_normals, _words(options))
    return list(out["holes"])


detect_holes.__doc__ = f"""Finds the holes of a point cloud (outer borders of open surfaces are not holes).

Args:
    points:  (N, 3) float32 or float64 array (rows with NaN are skipped).
    normals: (N, 3) array, or None to estimate them as fill() does.

Options: min_hole_size (default {DEFAULTS['min_hole_size']!r} = 'auto', in sampling pitches;
    auto: 6 on uniformly random samples, 4 on even ones),
    max_hole_size (default {DEFAULTS['max_hole_size']!r}, cloud units, 0 = no limit),
    threads (default {DEFAULTS['threads']!r}), quiet.

Returns:
    list of int64 arrays: for each hole, the input indices around it in order (what
    fill(points, holes=...) takes).
"""
