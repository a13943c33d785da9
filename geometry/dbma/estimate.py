"""How big a DBMA mesh will be, before gmsh is asked for it: seconds, not minutes.

The size field of :func:`drawing.set_mesh_sizes` is known in closed form (b / hinge_elements
in each hinge box, growing linearly to the coarse size over the box's transition thickness),
so the number of triangles is the integral over the part of 1 / (area of a triangle of that
size), summed on a sampling grid of every rectangle of the part (4096 points each). In 3-D
each triangle becomes three quadrilaterals (gmsh's subdivision), extruded in layers through
the thickness. Against the meshes gmsh makes, the estimate is low by at most ~2.5x at the
coarsest sizes (where a minimum number of elements per feature dominates) and by 1.1-1.4x
at the sizes that matter for a budget (tests/studies/dbma/test_dbma_guards.py).
"""
import math

import numpy as np

from .drawing import (
    DBMALayout,
    check_mesh_options,
    dbma_rects,
    hinge_boxes,
    layers_through_thickness,
)
from .params import DBMAParams

SAMPLES = 64  # per side of each rectangle
TRIANGLE_AREA = math.sqrt(3) / 4  # of an equilateral triangle of unit edge
# nodes per element of the quadratic meshes (large-mesh ratios: P2 triangles ~2, Q2
# hexahedra of an extruded quad mesh ~4 at 20 nodes, counting shared nodes once)
NODES_PER_ELEMENT = {2: 2.05, 3: 2.2}


def _size(x, y, boxes, fine, coarse, thickness):
    size = np.full(x.shape, coarse)
    for r in boxes:
        dx = np.maximum(np.maximum(r.x0 - x, x - r.x1), 0.0)
        dy = np.maximum(np.maximum(r.y0 - y, y - r.y1), 0.0)
        distance = np.hypot(dx, dy)
        ramp = fine + (coarse - fine) * np.clip(distance / thickness, 0.0, 1.0)
        size = np.minimum(size, ramp)
    return size


def estimate_mesh(p: DBMAParams, layout: DBMALayout | None = None, dim: int = 2,
                  hinge_elements: int | None = None, size_factor: float = 1.0) -> dict:
    """{"elements", "nodes", "dofs"} expected of ``mesh_dbma`` with these arguments (dofs of
    a quadratic displacement model: dim per node)."""
    if hinge_elements is None:
        hinge_elements = 4 if dim == 2 else 2
    check_mesh_options(dim, hinge_elements, size_factor)
    fine = p.b / hinge_elements * size_factor
    coarse = (p.c / 2 if dim == 2 else p.c) * size_factor
    boxes, thickness = hinge_boxes(p, layout), 2 * p.b + p.l
    count = 0.0
    for r in dbma_rects(p, layout):
        u = (np.arange(SAMPLES) + 0.5) / SAMPLES
        x, y = np.meshgrid(r.x0 + (r.x1 - r.x0) * u, r.y0 + (r.y1 - r.y0) * u)
        h = _size(x, y, boxes, fine, coarse, thickness)
        cell = (r.x1 - r.x0) * (r.y1 - r.y0) / SAMPLES**2
        # at least one element across a rectangle's short side, as gmsh meshes it
        short = min(r.x1 - r.x0, r.y1 - r.y0)
        h = np.minimum(h, short)
        count += float(np.sum(cell / (TRIANGLE_AREA * h * h)))
    if dim == 3:  # three quadrilaterals per triangle, in layers through d
        count = 3 * count * layers_through_thickness(p, size_factor)
    nodes = NODES_PER_ELEMENT[dim] * count
    return {"elements": int(count), "nodes": int(nodes), "dofs": int(dim * nodes)}
