"""The narrow necks (the flexure hinges) of an outline, measured on the outline itself.

A neck is a part of the solid thinner than a detection width ``detect`` (what a
morphological opening of that width removes) that joins thicker solid at two places or more:
a corner's sliver, removed by the opening too, touches the thick solid at one. Its width is
the least distance between its flanks (the stretches of the outline's boundary along it):
for a passage between two walls that is the diameter of the largest disc that passes
through it. Symmetry lines are mirrored first, so a hinge cut by one is measured whole."""
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Neck:
    """``width`` (m): the least distance across; ``where`` (x, y), m: the middle of that
    chord; ``region``: the thin part (shapely polygon, m)."""

    width: float
    where: tuple
    region: object


def _pieces(geom) -> list:
    """The parts of a shapely geometry, empty ones dropped."""
    if geom.is_empty:
        return []
    return [g for g in getattr(geom, "geoms", [geom]) if not g.is_empty]


def _flank_width(thin, thick, tol: float):
    """(width, where) across the thin part ``thin``: the least distance between two of its
    flanks (its boundary away from ``thick``), None where it has fewer than two."""
    from shapely.ops import linemerge, nearest_points

    free = thin.boundary.difference(thick.buffer(tol))
    flanks = [f for f in _pieces(linemerge(free) if free.geom_type == "MultiLineString"
                                   else free) if f.length > tol]
    best = None
    for i, a in enumerate(flanks):
        for b in flanks[i + 1:]:
            d = a.distance(b)
            if best is None or d < best[0]:
                pa, pb = nearest_points(a, b)
                best = (d, ((pa.x + pb.x) / 2, (pa.y + pb.y) / 2))
    return best


def find_necks(shape, detect: float, tol: float | None = None) -> list:
    """The necks of a shapely (Multi)Polygon thinner than ``detect`` (m), narrowest first;
    ``tol`` (m, default detect / 100): contacts and flanks shorter than it are ignored."""
    tol = detect / 100 if tol is None else tol
    thick = shape.buffer(-detect / 2, 16).buffer(detect / 2, 16)
    necks = []
    for thin in _pieces(shape.difference(thick).buffer(0)):
        if thin.geom_type != "Polygon" or thin.area <= tol * tol:
            continue
        contacts = _pieces(thin.buffer(tol).intersection(thick.buffer(tol)).buffer(0))
        if len([c for c in contacts if c.area > tol * tol]) < 2:
            continue
        across = _flank_width(thin, thick, 2 * tol)
        if across is not None:
            necks.append(Neck(float(across[0]), across[1], thin))
    return sorted(necks, key=lambda n: n.width)


def mirrored(shape, mirrors=()):
    """The shape with its mirror images about each symmetry line ((axis, value), m: 0 for
    x = value, 1 for y = value), joined."""
    from shapely.affinity import scale

    out = shape
    for axis, at in mirrors:
        origin = (at, 0.0) if axis == 0 else (0.0, at)
        image = scale(out, -1.0 if axis == 0 else 1.0, -1.0 if axis == 1 else 1.0,
                      origin=origin)
        out = out.union(image).buffer(0)
    return out


def outline_necks(outline, detect: float, mirrors=(), domain=None) -> list:
    """The necks of an :class:`~.outline.Outline` thinner than ``detect`` (m), measured on
    its shape mirrored about ``mirrors``, kept where their point lies in ``domain``
    ((x0, y0, x1, y1), m; default the outline's bounds)."""
    box = domain or outline.shape.bounds
    slack = 1e-9 * max(box[2] - box[0], box[3] - box[1])
    keep = []
    for neck in find_necks(mirrored(outline.shape, mirrors), detect):
        x, y = neck.where
        if box[0] - slack <= x <= box[2] + slack and box[1] - slack <= y <= box[3] + slack:
            keep.append(neck)
    return keep


def peak_in(points: np.ndarray, values: np.ndarray, region, reach: float) -> float:
    """The largest of ``values`` at ``points`` ((n, 2), m) within ``reach`` (m) of
    ``region`` (0 where none is)."""
    import shapely

    inside = shapely.contains_xy(region.buffer(reach), points[:, 0], points[:, 1])
    return float(values[inside].max()) if inside.any() else 0.0
