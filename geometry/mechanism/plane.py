"""Plane geometry for bodies and flexures: cross products, segment clipping, convex
overlap (m)."""
import math

import numpy as np


def cross2(a, b) -> float:
    """The z component of a x b for plane vectors a, b (2,)."""
    return float(a[0] * b[1] - a[1] * b[0])


def convex_overlap(p: np.ndarray, q: np.ndarray, tol: float) -> bool:
    """True where the convex polygons p and q ((k, 2), m) overlap by more than ``tol``
    (separating-axis test)."""
    for poly in (p, q):
        for i in range(len(poly)):
            edge = poly[(i + 1) % len(poly)] - poly[i]
            axis = np.array([-edge[1], edge[0]]) / np.linalg.norm(edge)
            pa, qa = p @ axis, q @ axis
            if pa.max() <= qa.min() + tol or qa.max() <= pa.min() + tol:
                return False
    return True


def side_root(body, point, direction, reach: float, tol: float) -> np.ndarray | None:
    """Where the line through ``point`` along ``direction`` (unit) leaves ``body`` nearest
    ``point``, looking ``reach`` (m) either side (m); None where that line misses the body."""
    start, end = point - reach * direction, point + reach * direction
    exits = [hi for _, hi in body.span_inside(start, end, tol)]
    if not exits:
        return None
    s = min(exits, key=lambda v: abs(v - 0.5))
    return start + s * (end - start)


def subtract(intervals, cut) -> list:
    """[lo, hi] intervals of [0, 1] less the interval ``cut`` (or None)."""
    if cut is None:
        return intervals
    c0, c1 = cut
    out = []
    for lo, hi in intervals:
        if c1 <= lo or c0 >= hi:
            out.append((lo, hi))
            continue
        if c0 > lo:
            out.append((lo, c0))
        if c1 < hi:
            out.append((c1, hi))
    return out


def inside_box(a, b, box, tol):
    """The interval of s where a + s (b - a) lies strictly inside ``box``, or None."""
    (x0, y0), (x1, y1) = box
    lo, hi = 0.0, 1.0
    d = b - a
    for k, (low, high) in enumerate(((x0 - tol, x1 + tol), (y0 - tol, y1 + tol))):
        if abs(d[k]) < 1e-300:
            if not low < a[k] < high:
                return None
            continue
        s0, s1 = sorted(((low - a[k]) / d[k], (high - a[k]) / d[k]))
        lo, hi = max(lo, s0), min(hi, s1)
    return (lo, hi) if hi > lo else None


def along(a, b, p0, p1, tol):
    """The interval of s on a -> b covered by the segment p0 p1 lying on the same line."""
    d = b - a
    length2 = float(d @ d)
    n = np.array([-d[1], d[0]]) / math.sqrt(length2)
    if abs(float((p0 - a) @ n)) > 10 * tol or abs(float((p1 - a) @ n)) > 10 * tol:
        return None
    s0, s1 = sorted((float((p0 - a) @ d) / length2, float((p1 - a) @ d) / length2))
    return (max(s0, 0.0), min(s1, 1.0)) if min(s1, 1.0) > max(s0, 0.0) else None


def box_corners(box) -> np.ndarray:
    (x0, y0), (x1, y1) = box
    return np.array([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], float)
