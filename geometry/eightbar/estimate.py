"""How big the eight-bar flexure mesh will be, before gmsh is asked for it.

``mesh_eightbar_flexure`` meshes each flexure structured (n elements across, element length
``aspect`` times the size across) and grades the links from the flexure size up to the
coarse size W / 2 * size_factor; counting two triangles per structured cell and the links'
area over the area of a triangle of the coarse size (bounded by the part's width), times
GRADING for the graded zones around each flexure, gives the triangle count: within a factor
~1.5 either way of gmsh's meshes (tests/studies/dbma/test_dbma_guards.py).

In 3-D (``dim=3``) the in-plane mesh of :func:`~.flexure.solid_mesh_options` is extruded in
L layers of tetrahedra (three a prism): a plane's N quadratic nodes give (2 L + 1) N nodes
(L + 1 planes of vertices and in-plane edges, and per layer the vertical edges and one
diagonal a side face), 3 DOFs each.
"""
import math

from .flexure import EightBarFlexureParams, check_mesh_options, eightbar_layout, solid_mesh_options

TRIANGLE_AREA = math.sqrt(3) / 4
NODES_PER_ELEMENT = 2.05  # quadratic triangles, large meshes
GRADING = 2.0  # elements of the graded zones, measured: 1.5x-3x the count without them


def _triangles(params: EightBarFlexureParams, n: int, aspect: float, coarse: float) -> float:
    """Expected triangle count of the in-plane mesh (n across a flexure, element length
    ``aspect`` times the size across, links graded to ``coarse`` m)."""
    count = 0.0
    for part in eightbar_layout(params).parts:
        length = math.dist(part.p0, part.p1)
        if part.kind == "flexure":
            cell = part.width / n
            count += 2 * n * math.ceil(length / (aspect * cell))
        else:
            size = min(coarse, part.width / 2)
            count += length * part.width / (TRIANGLE_AREA * size * size)
    return count * GRADING


def estimate_mesh(params: EightBarFlexureParams, n_across: int = 3, size_factor: float = 1.0,
                  aspect: float = 4.0, dim: int = 2, layers: int | None = None) -> dict:
    """{"elements", "nodes", "dofs"} expected of ``mesh_eightbar_flexure`` (quadratic) with the
    same arguments."""
    check_mesh_options(n_across, size_factor)
    if dim not in (2, 3):
        raise ValueError(f"dim = {dim!r} must be 2 or 3")
    if dim == 3:
        o = solid_mesh_options(params, n_across, size_factor, layers)
        count = _triangles(params, o["n_across"], o["aspect"], o["coarse"])
        nodes = NODES_PER_ELEMENT * count * (2 * o["layers"] + 1)
        return {"elements": int(3 * o["layers"] * count), "nodes": int(nodes),
                "dofs": int(3 * nodes)}
    n = max(int(n_across), int(math.ceil(3 / size_factor)))
    count = _triangles(params, n, min(20.0, max(0.5, aspect * size_factor)),
                       params.link_width / 2 * size_factor)
    nodes = NODES_PER_ELEMENT * count
    return {"elements": int(count), "nodes": int(nodes), "dofs": int(2 * nodes)}
