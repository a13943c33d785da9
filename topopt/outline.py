"""From densities to a shape: the thresholded design's outline (scikit-image's marching
squares), cleaned and simplified with shapely, checked for members thinner than a minimum
size and for islands, and written as DXF (geometry/outline_files.py, mm) for manufacture or
re-meshing."""
from dataclasses import dataclass
from functools import reduce

import numpy as np

from ..geometry.outline_files import loop_of, write_dxf as _write_dxf
from .grid import Grid


@dataclass(frozen=True)
class Outline:
    """``shape``: the kept solid (shapely Polygon or MultiPolygon, m); ``islands``: parts
    dropped for touching none of the anchors (m^2 each); ``thin_area``: area of the kept
    solid thinner than the minimum member size (m^2)."""

    shape: object
    islands: tuple
    thin_area: float

    @property
    def parts(self) -> list:
        return list(getattr(self.shape, "geoms", [self.shape]))

    @property
    def faces(self) -> list:
        """[[outer loop, hole loop, ...]] a part, each loop [(x, y, 0.0)] (m, straight)."""
        return [[loop_of(p.exterior.coords), *(loop_of(r.coords) for r in p.interiors)]
                for p in self.parts]


def problem_anchors(problem) -> list:
    """The node coordinates (m) of a problem's supports, loads and springs."""
    regions = [s.where for s in (*problem.supports, *problem.loads, *problem.springs)]
    return [tuple(problem.grid.nodes[n]) for r in regions for n in r.nodes(problem.grid)]


def _rings(density: np.ndarray, grid: Grid, threshold: float, mirrors=()) -> list:
    from skimage.measure import find_contours

    field = np.pad(density.reshape(grid.nelx, grid.nely), 2)  # [ix, iy], void around
    for axis, at in mirrors:    # a symmetry line: its mirror image beyond it, then void
        side = 1 if at == 0.0 else -2
        index, inner = [slice(1, -1), slice(1, -1)], [slice(1, -1), slice(1, -1)]
        index[axis], inner[axis] = side, side + (1 if side == 1 else -1)
        field[tuple(index)] = field[tuple(inner)]
    rings = []
    for c in find_contours(field, threshold):
        xy = np.column_stack([(c[:, 0] - 1.5) * grid.dx, (c[:, 1] - 1.5) * grid.dy])
        if len(xy) >= 4:
            rings.append(xy)
    return rings


def extract_outline(density, grid: Grid, anchors=(), threshold: float = 0.5,
                    min_member: float = 0.0, simplify: float | None = None,
                    close: float = 0.0, mirrors=()) -> Outline:
    """The outline of ``density > threshold``. ``anchors``: points (m) the mechanism must
    reach (supports, loads, springs): a part touching none is an island, dropped;
    ``mirrors``: symmetry lines at the grid's edges ((axis, value), m, as
    topopt.verify.mirror_lines gives them), across which the solid continues straight
    instead of being rounded off as at a free edge;
    ``min_member`` (m): members thinner than this are measured as ``thin_area``;
    ``simplify`` (m, default a quarter element): the outline's tolerance; ``close`` (m): a
    morphological closing of that radius (grown, then shrunk), which joins elements that
    touch at a corner (one-node hinges) by a neck and rounds concave corners."""
    import shapely
    from shapely.geometry import MultiPolygon, Point, Polygon, box

    polys = [Polygon(r).buffer(0) for r in _rings(np.asarray(density), grid, threshold,
                                                  mirrors)]
    solid = reduce(lambda a, b: a.symmetric_difference(b), polys, Polygon())
    if close > 0:
        solid = solid.buffer(close, 16).buffer(-close, 16)
    solid = solid.intersection(box(0.0, 0.0, grid.lx, grid.ly))
    tol = 0.25 * min(grid.dx, grid.dy) if simplify is None else simplify
    solid = shapely.make_valid(solid.simplify(tol)).buffer(0)
    parts = [g for g in getattr(solid, "geoms", [solid]) if g.area > 0]
    reach = [Point(a).buffer(0.75 * max(grid.dx, grid.dy)) for a in anchors]
    kept = [g for g in parts if not reach or any(g.intersects(r) for r in reach)]
    islands = tuple(float(g.area) for g in parts if g not in kept)
    shape = kept[0] if len(kept) == 1 else MultiPolygon(kept)
    thin = 0.0
    if min_member > 0:
        opened = shape.buffer(-min_member / 2).buffer(min_member / 2)
        thin = float(shape.difference(opened).area)
    return Outline(shape, islands, thin)


def write_dxf(outline: Outline, path) -> int:
    """Each ring of the outline as a closed polyline, in millimetres; returns the number of
    polylines."""
    return _write_dxf([loop for face in outline.faces for loop in face], path)
