"""A rigid body of a flexure mechanism: a union of axis-aligned boxes and simple polygons
(m), with the geometry its flexures' roots, the continuum and the beam model ask of it:
containment, the chord of a line through it, its faces, its area. A body of boxes only keeps
the boxes' exact axis-aligned arithmetic (the models of such a body are unchanged by the
polygons); its polygons go through shapely (geometry/polygon.py)."""
from dataclasses import dataclass
from functools import cached_property
import math

import numpy as np
from shapely import LineString, Point, Polygon

from .. import polygon as poly
from .plane import box_corners

#: The smallest side of a body's box (m), as a flexure's smallest thickness: below it the box
#: is a sliver (a corner mistyped by a rounding error) that gmsh cannot draw or mesh.
BOX_SIDE_MIN = 1e-6


@dataclass(frozen=True)
class Body:
    """A rigid body: ``name`` (its group in every model), ``boxes`` ((lower-left,
    upper-right) corner pairs, m) and ``polygons`` (simple polygons, each a tuple of (x, y)
    vertices, m, stored counter-clockwise); the body is their union. A body of boxes only
    keeps the boxes' own (exact, axis-aligned) geometry everywhere."""

    name: str
    boxes: tuple = ()
    source: str = ""
    polygons: tuple = ()

    def __post_init__(self):
        where = f"{self.source or 'body'}: body {self.name!r}"
        boxes = []
        for box in self.boxes:
            (x0, y0), (x1, y1) = box
            if not all(map(math.isfinite, (x0, y0, x1, y1))) or x0 == x1 or y0 == y1:
                raise ValueError(f"{where}: box {[list(box[0]), list(box[1])]} must be two "
                                 "opposite corners of a rectangle of non-zero area (m)")
            side = min(abs(x1 - x0), abs(y1 - y0))
            if side < BOX_SIDE_MIN:
                raise ValueError(f"{where}: box {[list(box[0]), list(box[1])]} is only "
                                 f"{side:.3g} m {'wide' if abs(x1 - x0) == side else 'tall'}: "
                                 f"a body's box needs at least {BOX_SIDE_MIN:g} m on each side "
                                 "(a sliver no mesh can resolve; lengths are in m)")
            boxes.append(((min(x0, x1), min(y0, y1)), (max(x0, x1), max(y0, y1))))
        polygons = []
        for k, vertices in enumerate(self.polygons):
            label = f"polygon {k + 1}" if len(self.polygons) > 1 else "polygon"
            try:
                polygons.append(poly.check_polygon(vertices, label))
            except ValueError as error:
                raise ValueError(f"{where}: {error}") from None
        if not boxes and not polygons:
            raise ValueError(f"{where} needs a box or a polygon")
        object.__setattr__(self, "boxes", tuple(boxes))
        object.__setattr__(self, "polygons", tuple(polygons))

    @property
    def blocks(self) -> tuple:
        """The body's parts as the beam model's blocks: its boxes (two corners), then its
        polygons (their vertices)."""
        return self.boxes + self.polygons

    @property
    def outlines(self) -> list:
        """Every part's vertices ((k, 2), m, counter-clockwise): boxes then polygons."""
        return [box_corners(b) for b in self.boxes] + [np.array(p) for p in self.polygons]

    @cached_property
    def _shapes(self) -> list:
        return [Polygon(p) for p in self.polygons]

    @cached_property
    def shape(self):
        """The union of the body's parts (shapely)."""
        return poly.union(self.blocks)

    def contains(self, point, tol: float) -> bool:
        """True where ``point`` (m) lies inside a part or on its outline (within ``tol``; a
        negative ``tol``: at least -tol inside)."""
        x, y = point
        if any(x0 - tol <= x <= x1 + tol and y0 - tol <= y <= y1 + tol
               for (x0, y0), (x1, y1) in self.boxes):
            return True
        here = Point(x, y)
        for shape in self._shapes:
            if tol >= 0 and shape.distance(here) <= tol:
                return True
            if tol < 0 and shape.contains(here) and shape.exterior.distance(here) >= -tol:
                return True
        return False

    def span_inside(self, a, b, tol: float) -> list:
        """The intervals [s0, s1] of s in [0, 1] where a + s (b - a) lies in the body (each
        part's outline moved out by ``tol``)."""
        out = []
        a, d = np.asarray(a, float), np.subtract(b, a)
        for (x0, y0), (x1, y1) in self.boxes:
            lo, hi = 0.0, 1.0
            for k, (low, high) in enumerate(((x0 - tol, x1 + tol), (y0 - tol, y1 + tol))):
                if abs(d[k]) < 1e-300:
                    if not low <= a[k] <= high:
                        lo, hi = 1.0, 0.0
                    continue
                s0, s1 = sorted(((low - a[k]) / d[k], (high - a[k]) / d[k]))
                lo, hi = max(lo, s0), min(hi, s1)
            if hi >= lo:
                out.append((lo, hi))
        length2 = float(d @ d)
        for shape in self._shapes:
            region = shape if tol == 0 else shape.buffer(tol, join_style="mitre")
            if length2 < 1e-300:
                if region.covers(Point(*a)):
                    out.append((0.0, 1.0))
                continue
            cut = LineString([a, a + d]).intersection(region)
            for piece in getattr(cut, "geoms", [cut]):
                if piece.is_empty or piece.geom_type not in ("Point", "LineString"):
                    continue
                s = [float((np.asarray(q) - a) @ d) / length2 for q in piece.coords]
                out.append((max(min(s), 0.0), min(max(s), 1.0)))
        return sorted(out)

    @property
    def area(self) -> float:
        """The area (m^2): the boxes' areas summed (a body's boxes should not overlap), or
        with polygons the area of the union."""
        if self.polygons:
            return float(self.shape.area)
        return sum((x1 - x0) * (y1 - y0) for (x0, y0), (x1, y1) in self.boxes)

    def face_at(self, point, tol: float):
        """Unit direction (2,) along the box edge or polygon edge ``point`` lies on (within
        ``tol``; a polygon's nearest), or None."""
        x, y = point
        for (x0, y0), (x1, y1) in self.boxes:
            if x0 - tol <= x <= x1 + tol and (abs(y - y0) <= tol or abs(y - y1) <= tol):
                return np.array([1.0, 0.0])
            if y0 - tol <= y <= y1 + tol and (abs(x - x0) <= tol or abs(x - x1) <= tol):
                return np.array([0.0, 1.0])
        for vertices in self.polygons:
            direction = poly.edge_at(vertices, point, tol)
            if direction is not None:
                return direction
        return None
