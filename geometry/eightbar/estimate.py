"""How big the eight-bar flexure mesh will be, before gmsh is asked for it.

``mesh_eightbar_flexure`` meshes each flexure structured (n elements across, element length
``aspect`` times the size across) and grades the links from the flexure size up to the
coarse size W / 2 * size_factor; counting two triangles per structured cell and the links'
area over the area of a triangle of the coarse size (bounded by the part's width), times
GRADING for the graded zones around each flexure, gives the triangle count: within a factor
~1.5 either way of gmsh's meshes (tests/studies/dbma/test_dbma_guards.py).
"""
import math

from .flexure import EightBarFlexureParams, check_mesh_options, eightbar_layout

TRIANGLE_AREA = math.sqrt(3) / 4
NODES_PER_ELEMENT = 2.05  # quadratic triangles, large meshes
GRADING = 2.0  # elements of the graded zones, measured: 1.5x-3x the count without them


def estimate_mesh(params: EightBarFlexureParams, n_across: int = 3, size_factor: float = 1.0,
                  aspect: float = 4.0) -> dict:
    """{"elements", "nodes", "dofs"} expected of ``mesh_eightbar_flexure`` (2-D, quadratic)."""
    check_mesh_options(n_across, size_factor)
    n = max(int(n_across), int(math.ceil(3 / size_factor)))
    aspect = min(20.0, max(0.5, aspect * size_factor))
    coarse = params.link_width / 2 * size_factor
    count = 0.0
    for part in eightbar_layout(params).parts:
        length = math.dist(part.p0, part.p1)
        if part.kind == "flexure":
            cell = part.width / n
            count += 2 * n * math.ceil(length / (aspect * cell))
        else:
            size = min(coarse, part.width / 2)
            count += length * part.width / (TRIANGLE_AREA * size * size)
    count *= GRADING
    nodes = NODES_PER_ELEMENT * count
    return {"elements": int(count), "nodes": int(nodes), "dofs": int(2 * nodes)}
