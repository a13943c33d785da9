"""A link plate as spatial beams: the skeleton of its union of rectangles (bars and hubs).

    skeleton = link_skeleton(layout.parts, "coupler_L")
    skeleton.pieces   # [(a, b)]: beam centre-lines, m; skeleton.offsets: [(end, junction)]

Every rectangle of the link (a :class:`~flexfem.geometry.flexure_linkage.Part`, W wide)
becomes a beam along its centre-line with the W x thickness section. Where rectangles
overlap (a bar ending on a hub, two bars meeting at a corner or a T) the material is
counted once: the rectangles are taken in turn (hubs and anchors first, then bars, longest
first) and the part of a centre-line inside an earlier rectangle is dropped; the beam then
ends at that rectangle's edge, and a rigid offset along its own centre-line joins it to the
earlier beam where the two centre-lines cross (a rigid joint zone, as in frame analysis).
The beams and joint zones then partition the plate exactly where parts meet at right angles,
and to a sliver (a bar entering a hub obliquely) otherwise. Generic over a FlexureLayout;
all lengths in m.
"""
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Skeleton:
    """pieces: [(a, b)] beam centre-lines (2,) m; offsets: [(end, junction)] rigid offsets
    from a trimmed beam end to the earlier beam it enters."""

    pieces: list
    offsets: list


def _inside_interval(p0, p1, corners, tol: float):
    """(s0, s1) in [0, 1] of the segment p0-p1 inside the counter-clockwise convex polygon
    ``corners`` (Cyrus-Beck), or None where that is shorter than ``tol`` (m)."""
    d, lo, hi = p1 - p0, 0.0, 1.0
    for a, b in zip(corners, np.roll(corners, -1, axis=0)):
        e = b - a
        f0 = e[0] * (p0[1] - a[1]) - e[1] * (p0[0] - a[0])  # >= 0 inside
        df = e[0] * d[1] - e[1] * d[0]
        if abs(df) < 1e-15 * np.linalg.norm(e) * max(np.linalg.norm(d), 1e-300):
            if f0 < 0:
                return None
            continue
        s = -f0 / df
        lo, hi = (max(lo, s), hi) if df > 0 else (lo, min(hi, s))
    length = np.linalg.norm(d)
    return (lo, hi) if (hi - lo) * length > tol else None


def _merge(intervals) -> list:
    out = []
    for s0, s1 in sorted(intervals):
        if out and s0 <= out[-1][1]:
            out[-1] = (out[-1][0], max(out[-1][1], s1))
        else:
            out.append((s0, s1))
    return out


def _crossing(p, q, pieces, tol: float):
    """The point of ``pieces`` nearest ``p`` on the segment p-q (an intersection or, for a
    collinear piece, its nearest point on p-q), or None."""
    best, d = None, q - p
    for a, b in pieces:
        e = b - a
        den = d[0] * e[1] - d[1] * e[0]
        w = a - p
        if abs(den) > 1e-12 * np.linalg.norm(d) * np.linalg.norm(e):
            s, t = (w[0] * e[1] - w[1] * e[0]) / den, (w[0] * d[1] - w[1] * d[0]) / den
            hits = [s] if -1e-9 <= s <= 1 + 1e-9 and -1e-9 <= t <= 1 + 1e-9 else []
        elif abs(w[0] * d[1] - w[1] * d[0]) <= tol * np.linalg.norm(d):  # collinear
            ends = [float((x - p) @ d / (d @ d)) for x in (a, b)]
            lo, hi = max(min(ends), 0.0), min(max(ends), 1.0)
            hits = [lo] if lo <= hi else []
        else:
            hits = []
        for s in hits:
            if best is None or s < best:
                best = s
    return None if best is None else p + min(max(best, 0.0), 1.0) * d


def nearest_on(pieces, point) -> tuple:
    """(point on ``pieces`` nearest ``point``, its distance) (m)."""
    best = (None, np.inf)
    for a, b in pieces:
        e = b - a
        s = min(max(float((point - a) @ e / (e @ e)), 0.0), 1.0)
        x = a + s * e
        dist = float(np.linalg.norm(point - x))
        if dist < best[1]:
            best = (x, dist)
    return best


def _order(parts) -> list:
    """Hubs and anchors first, then bars, longest first (ties by name)."""
    return sorted(parts, key=lambda p: (p.kind == "bar", -round(p.length, 12), p.name))


def link_skeleton(parts, link: str, tol: float = 1e-9) -> Skeleton:
    """The beams and rigid joint zones of ``link``'s plate (module docstring). ValueError
    for a link without rectangles."""
    rects = _order([p for p in parts if p.link == link and p.kind != "flexure"])
    if not rects:
        raise ValueError(f"link {link!r} has no bars or hubs to model as beams")
    pieces, offsets, placed = [], [], []
    for part in rects:
        p0, p1 = np.asarray(part.p0, float), np.asarray(part.p1, float)
        covered = _merge([iv for c in placed if (iv := _inside_interval(p0, p1, c, tol))])
        edges = [0.0] + [s for iv in covered for s in iv] + [1.0]
        earlier = list(pieces)
        for k in range(0, len(edges), 2):
            s0, s1 = edges[k], edges[k + 1]
            if (s1 - s0) * part.length <= tol:
                continue
            a, b = p0 + s0 * (p1 - p0), p0 + s1 * (p1 - p0)
            pieces.append((a, b))
            for end, s_end, s_far in ((a, s0, edges[k - 1] if k > 0 else None),
                                      (b, s1, edges[k + 2] if k + 2 < len(edges) else None)):
                if s_far is None:
                    continue
                far = p0 + s_far * (p1 - p0)
                junction = _crossing(end, far, earlier, tol)
                if junction is None:
                    junction = nearest_on(earlier, end)[0]
                offsets.append((end, junction))
        placed.append(part.corners())
    return Skeleton(pieces, offsets)


class _MergedPoints:
    """Points (m) merged within ``tol``."""

    def __init__(self, tol: float):
        self.points, self.tol = [], tol

    def at(self, p) -> int:
        p = np.asarray(p, float)
        for k, q in enumerate(self.points):
            if np.linalg.norm(p - q) <= self.tol:
                return k
        self.points.append(p)
        return len(self.points) - 1


def mesh_skeleton(skeleton: Skeleton, stations, size: float, tol: float = 1e-9) -> tuple:
    """(nodes (n, 2) m, elements (n_e, 2), pairs [(junction node, offset node)], station
    nodes): every piece split at the junctions and at the stations' nearest points on it, and
    into elements no longer than ``size`` (m); a station off the pieces (more than ``tol``
    away) gets its own node, rigidly offset from its nearest point (a pair)."""
    if not size > 0:
        raise ValueError(f"size = {size!r} m must be > 0 (the link elements' length)")
    stations = [np.asarray(s, float) for s in stations]
    feet = [nearest_on(skeleton.pieces, s)[0] for s in stations]
    cuts = [j for _, j in skeleton.offsets] + feet
    nodes, elements = _MergedPoints(tol), []
    for a, b in skeleton.pieces:
        e = b - a
        length = float(np.linalg.norm(e))
        s = sorted({0.0, 1.0} | {float((c - a) @ e) / length**2 for c in cuts
                                 if abs(e[0] * (c - a)[1] - e[1] * (c - a)[0]) <= tol * length
                                 and -tol <= (c - a) @ e <= length**2 + tol})
        for s0, s1 in zip(s[:-1], s[1:]):
            if (s1 - s0) * length <= tol:
                continue
            n = max(1, int(np.ceil((s1 - s0) * length / size - 1e-9)))
            ids = [nodes.at(a + x * e) for x in np.linspace(s0, s1, n + 1)]
            elements += list(zip(ids[:-1], ids[1:]))
    pairs = [(nodes.at(j), nodes.at(end)) for end, j in skeleton.offsets]
    station_nodes = []
    for s, foot in zip(stations, feet):
        k = nodes.at(s)
        if np.linalg.norm(s - foot) > tol:
            pairs.append((nodes.at(foot), k))
        station_nodes.append(k)
    pairs = [(m, s) for m, s in pairs if m != s]
    return np.array(nodes.points), np.array(elements, dtype=int), pairs, station_nodes
