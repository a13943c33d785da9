"""Simple polygons in the plane (m): the checks of a body's polygon, its area moments (mass,
centroid and rotary inertia of a plate), the chord through a point and the edge a point lies
on. A rectangle given by two opposite corners is the polygon of its four corners
(:func:`block_vertices`). Light on imports (numpy, shapely): the beam model's builder
(reduced/) uses it as well as the bodies and flexures (geometry/mechanism/)."""
import math

import numpy as np
from shapely import LineString, Point, Polygon
from shapely.geometry.polygon import orient
from shapely.ops import polylabel, unary_union
from shapely.validation import explain_validity


def block_vertices(block) -> np.ndarray:
    """(k, 2) vertices (m) of a block: a rectangle's two opposite corners -> its four corners
    counter-clockwise from the lower left; a polygon's vertices as they are."""
    if len(block) == 2:
        (x0, y0), (x1, y1) = block
        (x0, x1), (y0, y1) = sorted((x0, x1)), sorted((y0, y1))
        return np.array([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], float)
    return np.asarray(block, float)


def check_polygon(vertices, label: str = "polygon") -> tuple:
    """The vertices ((x, y) tuple, m) of a simple polygon of non-zero area, counter-clockwise;
    a closing vertex equal to the first and repeated consecutive vertices are dropped.
    ValueError, its message beginning with ``label`` and the vertices, for fewer than 3
    vertices, non-finite coordinates, zero area or an outline that crosses itself."""
    points = [tuple(float(v) for v in p) for p in vertices]
    shown = f"{label} {[list(p) for p in points]}"
    if not all(math.isfinite(v) for p in points for v in p):
        raise ValueError(f"{shown} has a coordinate that is not a finite number (m)")
    kept = [p for i, p in enumerate(points) if i == 0 or p != points[i - 1]]
    if len(kept) > 1 and kept[-1] == kept[0]:
        kept.pop()
    if len(kept) < 3:
        raise ValueError(f"{shown} has {len(kept)} distinct vertices; a polygon needs at least "
                         "3 [x, y] (m)")
    xy = np.array(kept)
    rel = xy - xy[0]
    extent = float(np.abs(rel).max())
    if np.abs(rel[:, 0, None] * rel[None, :, 1] - rel[:, 1, None] * rel[None, :, 0]).max() \
            <= 1e-12 * extent * extent:
        raise ValueError(f"{shown} has zero area: its vertices lie on one line")
    shape = Polygon(kept)
    if not shape.is_valid:
        raise ValueError(f"{shown} crosses itself ({explain_validity(shape)}): its edges may "
                         "meet only at their shared vertices; list the vertices in order around "
                         "the outline")
    x, y = xy.T
    signed = float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))
    return tuple(kept if signed > 0 else kept[:1] + kept[:0:-1])  # the first vertex kept


def union(blocks):
    """The shapely union of ``blocks`` (rectangles by two corners, or polygons)."""
    shapes = [Polygon(block_vertices(b)) for b in blocks]
    return shapes[0] if len(shapes) == 1 else unary_union(shapes)


def _ring(xy: np.ndarray, ref: np.ndarray) -> np.ndarray:
    """[A, Sx, Sy, Ixx, Iyy, Ixy] of a closed ring's vertices (k, 2) about ``ref``, signed
    (> 0 counter-clockwise): area, first moments (int x, int y dA) and second moments
    (int x^2, int y^2, int x y dA), by Green's theorem over the edges."""
    x, y = (xy - ref).T
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    c = x * yn - xn * y
    return np.array([c.sum() / 2, ((x + xn) * c).sum() / 6, ((y + yn) * c).sum() / 6,
                     ((x * x + x * xn + xn * xn) * c).sum() / 12,
                     ((y * y + y * yn + yn * yn) * c).sum() / 12,
                     ((x * yn + 2 * x * y + 2 * xn * yn + xn * y) * c).sum() / 24])


def moments(blocks) -> tuple:
    """(area m^2, centroid (2,) m, (int (x - cx)^2, int (y - cy)^2, int (x - cx)(y - cy)) dA
    m^4) of the union of ``blocks`` (rectangles by two corners, or polygons); overlaps count
    once, holes the union encloses not at all."""
    shape = union(blocks)
    ref = np.array(shape.centroid.coords[0])  # about it: no cancellation in the sums
    total = np.zeros(6)
    for poly in getattr(shape, "geoms", [shape]):
        poly = orient(poly, 1.0)  # exterior counter-clockwise, holes clockwise
        for ring in (poly.exterior, *poly.interiors):
            total += _ring(np.array(ring.coords)[:-1], ref)
    area, sx, sy, ixx, iyy, ixy = total
    cx, cy = sx / area, sy / area
    return (float(area), ref + np.array([cx, cy]),
            (float(ixx - area * cx * cx), float(iyy - area * cy * cy),
             float(ixy - area * cx * cy)))


def inscribed_diameter(vertices) -> float:
    """The diameter (m) of the largest circle inside the polygon: a rectangle's shorter side,
    an L-shape's arm thickness (to ~1.2 x), by GEOS's maximum inscribed circle to 1e-6 of the
    perimeter."""
    shape = Polygon(vertices)
    centre = polylabel(shape, tolerance=1e-6 * shape.length)
    return 2 * float(shape.exterior.distance(centre))


def chord(vertices, point, direction, tol: float) -> float | None:
    """The length (m) of the chord of the polygon (outline within ``tol``) on the line through
    ``point`` along ``direction`` (unit), the piece of it that holds the point; None where the
    point is farther than ``tol`` from the polygon."""
    shape = Polygon(vertices)
    here = Point(point)
    if shape.distance(here) > tol:
        return None
    region = shape.buffer(tol, join_style="mitre") if tol > 0 else shape
    x0, y0, x1, y1 = region.bounds
    reach = math.hypot(x1 - x0, y1 - y0) + tol
    p, d = np.asarray(point, float), np.asarray(direction, float)
    cut = LineString([p - reach * d, p + reach * d]).intersection(region)
    pieces = [g for g in getattr(cut, "geoms", [cut]) if g.geom_type == "LineString"]
    near = [g.length for g in pieces if g.distance(here) <= 2 * tol]
    return max(near) if near else 0.0


def edge_at(vertices, point, tol: float, corners: bool = True):
    """The unit direction (2,) of the polygon's edge nearest ``point`` (m) within ``tol`` (m),
    counter-clockwise along a counter-clockwise polygon; None where no edge is that near, or
    (``corners`` False) where the point lies within ``tol`` of the edge's ends."""
    xy = np.asarray(vertices, float)
    p = np.asarray(point, float)
    best, found = tol, None
    for a, b in zip(xy, np.roll(xy, -1, axis=0)):
        length = float(np.linalg.norm(b - a))
        u = (b - a) / length
        s = float((p - a) @ u)
        if corners:
            gap = float(np.linalg.norm(p - (a + min(max(s, 0.0), length) * u)))
        elif tol < s < length - tol:
            gap = abs(float(u[0] * (p - a)[1] - u[1] * (p - a)[0]))
        else:
            continue
        if gap <= best:
            best, found = gap, u
    return found
