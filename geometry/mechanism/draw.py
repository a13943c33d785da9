"""The continuum of a :class:`~.description.Mechanism`: its outline drawn with gmsh's
OpenCASCADE kernel (boxes, polygons, flexures, root fillets, notches), fragmented into one
conforming model with a boundary group per body (its outline, where it meets no flexure),
meshed with local refinement in every flexure; 2-D, or extruded by the depth to a solid (the
group: the body's lateral faces). Lengths in m."""
from contextlib import contextmanager
import math
from typing import TYPE_CHECKING

import numpy as np

from ...fem import gmsh_session
from ...fem.budget import BOUNDARY_NODES, NODES_PER_ELEMENT, TETRAHEDRA_PER_CUBE, TRIANGLE, check_budget
from ..mesh_fields import size_by_fields, threshold_field
from ..polygon import inscribed_diameter
from .description import REACH, Leaf, Mechanism, flexure_label, cross2

if TYPE_CHECKING:  # the mesh (scikit-fem): imported by mesh_mechanism when it meshes
    from ...fem import FEMesh


def _polygon(occ, points) -> int:
    tags = [occ.addPoint(x, y, 0) for x, y in points]
    lines = [occ.addLine(tags[i], tags[(i + 1) % len(tags)]) for i in range(len(tags))]
    return occ.addPlaneSurface([occ.addCurveLoop(lines)])


def _central_piece(gmsh, pieces, point) -> list:
    """The piece of ``pieces`` (dimtags) nearest ``point``; the others are removed."""
    occ = gmsh.model.occ
    ranked = sorted(pieces, key=lambda dt: np.linalg.norm(
        np.asarray(occ.getCenterOfMass(*dt))[:2] - point))
    if ranked[1:]:
        occ.remove(ranked[1:], recursive=True)
    return ranked[:1]


def fillet_corners(mechanism: Mechanism, index: int) -> list:
    """[(C, T1, T2, centre)] (m) of the root fillets of leaf ``index``: the corner C where a
    side of the leaf meets a body's face, the tangent points on the side (T1) and on the face
    (T2) of the circle of radius ``fillet`` and its centre. ValueError where a fillet does not
    fit on the face or the leaf."""
    leaf = mechanism.flexures[index]
    if not isinstance(leaf, Leaf) or leaf.fillet <= 0:
        return []
    span, tol, r = mechanism.span(index), mechanism.tol, leaf.fillet
    out = []
    for name, corner, inward, face, _ in mechanism.roots(index):
        theta = math.acos(max(-1.0, min(1.0, float(face @ inward))))
        along = r / math.tan(theta / 2)
        t1, t2 = corner + along * inward, corner + along * face
        centre = corner + r / math.sin(theta / 2) * (inward + face) / np.linalg.norm(
            inward + face)
        if mechanism.body(name).face_at(t2, 10 * tol) is None or 2 * along >= span.length:
            raise ValueError(f"{leaf.source}: the fillet (radius {r:.4g} m) of flexure "
                             f"{index + 1} does not fit on the face of body {name!r} at "
                             f"{corner.tolist()} or on the leaf")
        out.append((corner, t1, t2, centre))
    return out


def _flexure_shapes(gmsh, mechanism: Mechanism, index: int, body_tags) -> list:
    """The surfaces (dimtags) of flexure ``index``: its outline over the free span, cut by the
    bodies, its notches or fillets."""
    occ = gmsh.model.occ
    f, span = mechanism.flexures[index], mechanism.span(index)
    reach = f.width / 2 * REACH
    ext = type(span)(span.a - reach * span.d, span.b + reach * span.d)
    blank = [(2, _polygon(occ, ext.corners(f.width)))]
    pieces, _ = occ.cut(blank, body_tags, removeObject=True, removeTool=False)
    mid = (span.a + span.b) / 2
    shape = _central_piece(gmsh, pieces, mid)
    if not isinstance(f, Leaf):
        along, across = f.semi_axes
        major = (along, across, span.d) if along >= across else (across, along, span.n)
        disks = [(2, occ.addDisk(*(mid + side * (f.thickness / 2 + across) * span.n), 0,
                                 major[0], major[1], xAxis=[*major[2], 0.0]))
                 for side in (-1, 1)]
        shape, _ = occ.cut(shape, disks)
        shape = _central_piece(gmsh, shape, mid)
    for corner, t1, t2, centre in fillet_corners(mechanism, index):
        ccw = cross2(t1 - corner, t2 - corner) > 0  # OCC fuses faces of one orientation
        triangle = [(2, _polygon(occ, [corner, t1, t2] if ccw else [corner, t2, t1]))]
        disk = [(2, occ.addDisk(centre[0], centre[1], 0, f.fillet, f.fillet))]
        cusp, _ = occ.cut(triangle, disk)
        shape += _central_piece(gmsh, cusp, corner + (t1 - corner + t2 - corner) / 6)
    return shape


@contextmanager
def _naming(source: str, what: str):
    """A gmsh (OpenCASCADE) failure while drawing ``what`` as one ValueError naming it: a
    degenerate or near-coincident shape (a sliver, an edge within round-off of another)."""
    try:
        yield
    except ValueError:
        raise
    except Exception as error:  # gmsh raises bare Exception with OCC's last error
        cause = str(error).strip() or "no reason given"
        raise ValueError(f"{source + ': ' if source else ''}{what}: gmsh cannot draw it "
                         f"({cause}); look for a degenerate shape: a side near zero or an edge "
                         "within round-off of another body's or flexure's") from None


def draw(gmsh, mechanism: Mechanism, dim: int = 2) -> dict:
    """Draw ``mechanism`` into the open gmsh session, fragmented into one conforming model with
    a physical group per body (its outline in 2-D, its lateral faces in 3-D: dimension
    dim - 1) and "solid" (everything). Returns {"bodies": {name: [entity tags of dim]},
    "flexures": [[entity tags of dim] per flexure]}."""
    occ = gmsh.model.occ
    body_tags = []
    for body in mechanism.bodies:
        with _naming(body.source or mechanism.source, f"body {body.name!r}"):
            boxes = [(2, occ.addRectangle(x0, y0, 0, x1 - x0, y1 - y0))
                     for (x0, y0), (x1, y1) in body.boxes]
            boxes += [(2, _polygon(occ, vertices)) for vertices in body.polygons]  # ccw
            if len(boxes) > 1:
                boxes, _ = occ.fuse(boxes[:1], boxes[1:])
        body_tags.append(boxes)
    every_body = [dt for tags in body_tags for dt in tags]
    flexure_tags = []
    for i, f in enumerate(mechanism.flexures):
        with _naming(f.source or mechanism.source, flexure_label(f, i)):
            flexure_tags.append(_flexure_shapes(gmsh, mechanism, i, every_body))
    inputs = body_tags + flexure_tags
    flat = [dt for tags in inputs for dt in tags]
    _, children = occ.fragment(flat, [])
    owner = [group for group, tags in enumerate(inputs) for _ in tags]
    parts = [set() for _ in inputs]
    for group, kids in zip(owner, children):
        parts[group].update(tag for _, tag in kids)
    if dim == 3:
        occ.synchronize()
        parts = _extrude(gmsh, parts, mechanism.depth)
    occ.synchronize()
    n_bodies = len(mechanism.bodies)
    shared = _shared_boundary(gmsh, dim)
    for body, tags in zip(mechanism.bodies, parts[:n_bodies]):
        outline = [c for c in _boundary(gmsh, dim, tags) if c not in shared
                   and (dim == 2 or _lateral(gmsh, c, mechanism.depth))]
        gmsh.model.addPhysicalGroup(dim - 1, outline, name=body.name)
    everything = sorted(set().union(*parts))
    gmsh.model.addPhysicalGroup(dim, everything, name="solid")
    return {"bodies": {b.name: sorted(t) for b, t in zip(mechanism.bodies, parts)},
            "flexures": [sorted(t) for t in parts[n_bodies:]]}


def _boundary(gmsh, dim: int, tags) -> list:
    return [abs(t) for _, t in gmsh.model.getBoundary([(dim, t) for t in sorted(tags)],
                                                      combined=False, oriented=False)]


def _shared_boundary(gmsh, dim: int) -> set:
    """Entities of dimension dim - 1 that bound two entities of dimension dim."""
    count = {}
    for _, tag in gmsh.model.getEntities(dim):
        for c in set(_boundary(gmsh, dim, [tag])):
            count[c] = count.get(c, 0) + 1
    return {c for c, n in count.items() if n > 1}


def _lateral(gmsh, face: int, depth: float) -> bool:
    """True for a face that spans the whole depth (not a top or bottom face)."""
    _, _, z0, _, _, z1 = gmsh.model.getBoundingBox(2, face)
    return z1 - z0 > 0.5 * depth


def _extrude(gmsh, parts, depth: float) -> list:
    """Each part's surfaces extruded by ``depth`` along z, the volumes fragmented into one
    conforming solid; returns the parts' volume tags."""
    occ = gmsh.model.occ
    volumes = []
    for tags in parts:
        out = occ.extrude([(2, t) for t in sorted(tags)], 0, 0, depth)
        volumes.append([tag for d, tag in out if d == 3])
    flat = [(3, t) for vs in volumes for t in vs]
    _, children = occ.fragment(flat, [])
    owner = [i for i, vs in enumerate(volumes) for _ in vs]
    new = [set() for _ in parts]
    for i, kids in zip(owner, children):
        new[i].update(tag for _, tag in kids)
    return new


#: A fillet's elements: its radius over this, near the arc (its peak stress converges there:
#: within 0.5 % of a mesh twice as fine on the examples' leaves, quadratic elements).
FILLET_DIVISIONS = 8


def element_sizes(mechanism: Mechanism, coarse: float | None = None) -> tuple:
    """(size in each flexure (m) list, coarse size in the bodies (m)): half a leaf's
    thickness, a quarter of a notch's neck; the bodies ``coarse`` or a twentieth of the
    mechanism's size, at most half the shortest box side or half the diameter of the
    largest circle inside a polygon (for a rectangle its shorter side; for an L-shape about
    its arms' width: two elements across a body's narrowest part, where a polygon's
    shortest edge could be a tiny chamfer and its minimum rotated rectangle is blind to
    thin arms). A leaf's fillets are meshed finer still (:data:`FILLET_DIVISIONS`)."""
    sizes = [f.thickness / 2 if isinstance(f, Leaf) else f.thickness / 4
             for f in mechanism.flexures]
    if coarse is None:
        shortest = min([min(x1 - x0, y1 - y0) for b in mechanism.bodies
                        for (x0, y0), (x1, y1) in b.boxes]
                       + [inscribed_diameter(p) for b in mechanism.bodies for p in b.polygons])
        coarse = min(mechanism.size / 20, shortest / 2)
        return sizes, max(coarse, max(sizes))
    check_body_size(mechanism, coarse, sizes)
    return sizes, coarse


def check_body_size(mechanism: Mechanism, coarse: float, sizes=None) -> None:
    """Refuse a requested element size in the bodies (``coarse``, m) that the mesh cannot
    honour: finer than the coarsest flexure's own size (half a leaf's thickness, a quarter
    of a notch's neck), from which every flexure's size grows to the bodies'; say which
    sizes are possible."""
    if sizes is None:
        sizes = [f.thickness / 2 if isinstance(f, Leaf) else f.thickness / 4
                 for f in mechanism.flexures]
    if not (math.isfinite(coarse) and coarse > 0):
        raise ValueError(f"{mechanism.source}: [mesh] size = {coarse!r} must be a finite "
                         "length > 0 (m)")
    k = max(range(len(sizes)), key=sizes.__getitem__)
    if coarse < sizes[k]:
        f = mechanism.flexures[k]
        what = (f"half the {f.thickness:g} m thickness of {flexure_label(f, k)}" if isinstance(f, Leaf)
                else f"a quarter of the {f.thickness:g} m neck of {flexure_label(f, k)}")
        raise ValueError(f"{mechanism.source}: [mesh] size = {coarse:g} m cannot be honoured: "
                         f"it sets the bodies' elements, which may not be finer than a "
                         f"flexure's own ({sizes[k]:g} m, {what}; each flexure is meshed at "
                         f"its size and grows to the bodies'); give size >= {sizes[k]:g} m; to "
                         "refine the flexures too, use flexfem converge (it divides every size "
                         "by the same factor)")


def _fillet_faces(gmsh, dim: int, tags) -> list:
    """The curved boundary entities (fillet arcs, or their extruded faces) of a flexure."""
    curved = []
    for c in sorted(set(_boundary(gmsh, dim, tags))):
        kind = gmsh.model.getType(dim - 1, c)
        if kind in ("Circle", "Ellipse") or (dim == 3 and kind != "Plane"):
            curved.append(c)
    return curved


def _refine(gmsh, mechanism: Mechanism, shapes: dict, size_factor: float, coarse, dim: int):
    sizes, coarse = element_sizes(mechanism, coarse)
    thresholds = []
    for f, tags, h in zip(mechanism.flexures, shapes["flexures"], sizes):
        curves = sorted(set(_boundary(gmsh, dim, tags)))
        thresholds.append(threshold_field(gmsh, curves, dim, h * size_factor,
                                          coarse * size_factor, f.thickness / 2, 2 * coarse))
        arcs = _fillet_faces(gmsh, dim, tags) if isinstance(f, Leaf) and f.fillet > 0 else []
        if arcs:
            fine = min(h, f.fillet / FILLET_DIVISIONS)
            thresholds.append(threshold_field(gmsh, arcs, dim, fine * size_factor,
                                              h * size_factor, f.fillet / 2, f.fillet))
    size_by_fields(gmsh, thresholds, coarse * size_factor)


def _graded_cells(cells, width: float, h: float, coarse: float, near: float, reach: float,
                  room: float) -> tuple:
    """(cells, area (m^2)) of a flexure's root in its body: the half-stadium of points within
    ``near + reach`` of the root's interface (``width`` long, m), where the size is ``h``
    within ``near`` and grows linearly to ``coarse`` at ``near + reach`` (the threshold field
    of :func:`_refine`), at most ``room`` (m^2, the body's area) of it. ``cells(area, size)``
    counts the elements of an area at a size."""
    d = np.linspace(0.0, near + reach, 201)
    size = np.clip(h + (coarse - h) * (d - near) / reach, h, coarse)
    strip = (width + math.pi * d)  # d(area)/d(distance) of the half-stadium
    area = np.trapezoid(strip, d)
    count = np.trapezoid(np.array([cells(a, s) for a, s in zip(strip, size)]), d)
    scale = min(1.0, room / area) if area > 0 else 0.0
    return count * scale, area * scale


def _element_count(mechanism: Mechanism, cells, sizes: list, coarse: float) -> tuple:
    """(elements, [(length (m), size (m))] of the outline) of the size field of :func:`_refine`
    integrated over the mechanism: each flexure's own area at its size, at each of its two
    roots the body's points within the field's reach at the graded size (:func:`_graded_cells`),
    the rest of the bodies at theirs. ``cells(area, size)`` counts an area's elements."""
    body_area = sum(b.area for b in mechanism.bodies)
    elements, graded = 0.0, 0.0
    outline = [(sum(b.shape.length for b in mechanism.bodies), coarse)]
    for i, (f, h) in enumerate(zip(mechanism.flexures, sizes)):
        if isinstance(f, Leaf):
            length = mechanism.span(i).length
            own = length * f.width
            if f.fillet > 0:  # four fillets, each fine within about its radius
                elements += cells(4 * (2 * f.fillet) ** 2, min(h, f.fillet / FILLET_DIVISIONS))
        else:  # fine within half the neck of the two cut-outs' half-ellipses
            own = math.pi * sum(f.semi_axes) * f.thickness
            length = math.pi * sum(f.semi_axes) / 2
        elements += cells(own, h)
        outline.append((2 * length, h))
        for _ in range(2):
            count, area = _graded_cells(cells, f.width, h, coarse, f.thickness / 2,
                                        2 * coarse, max(body_area - graded, 0.0))
            elements, graded = elements + count, graded + area
    return elements + cells(max(body_area - graded, 0.0), coarse), outline


def estimate_mesh(mechanism: Mechanism, dim: int = 2, size_factor: float = 1.0,
                  coarse: float | None = None, order: int = 2) -> dict:
    """{"elements", "nodes", "dofs"} expected of :func:`mesh_mechanism`: the elements of the
    size field integrated over the mechanism (:func:`_element_count`; in 3-D the areas through
    the depth in tetrahedra), the nodes NODES_PER_ELEMENT a cell plus BOUNDARY_NODES an element
    side on the boundary (2-D: its outline's edges; 3-D: the top and bottom faces' triangles
    and the lateral faces'): a thin flexure's mesh is mostly boundary."""
    sizes, coarse = element_sizes(mechanism, coarse)
    depth = mechanism.depth

    def triangles(area: float, h: float) -> float:
        h = min(h, coarse) * size_factor
        return area / (TRIANGLE * h * h)

    def tetrahedra(area: float, h: float) -> float:
        h = min(h, coarse) * size_factor
        return area * depth / (h ** 3 / TETRAHEDRA_PER_CUBE)

    planar, outline = _element_count(mechanism, triangles, sizes, coarse)
    if dim == 2:
        elements = planar
        boundary = sum(length / (h * size_factor) for length, h in outline)
    else:
        elements, _ = _element_count(mechanism, tetrahedra, sizes, coarse)
        boundary = 2 * planar + sum(triangles(length * depth, h) for length, h in outline)
    nodes = NODES_PER_ELEMENT[(dim, order)] * elements + BOUNDARY_NODES[(dim, order)] * boundary
    return {"elements": int(min(elements, 1e18)), "nodes": int(min(nodes, 1e18)),
            "dofs": int(min(dim * nodes, 1e18))}


def mesh_mechanism(mechanism: Mechanism, dim: int = 2, size_factor: float = 1.0,
                   coarse: float | None = None, order: int = 2,
                   max_dofs: int | None = None) -> "FEMesh":
    """The meshed continuum (linear cells; the Model raises the order) with a boundary group
    per body. ``size_factor`` scales every element size; ``coarse``: the bodies' size (m). A
    mesh whose estimate (of ``order`` elements) is above ``max_dofs`` (None: half the
    available memory) is refused first (BudgetError)."""
    if not (math.isfinite(size_factor) and size_factor > 0):
        raise ValueError(f"size_factor = {size_factor!r} must be a finite number > 0")
    check_budget(estimate_mesh(mechanism, dim, size_factor, coarse, order), dim, max_dofs,
                 what=f"the mechanism's mesh at size_factor {size_factor:g}")
    from ...fem import mesh_from_gmsh  # scikit-fem's mesh: imported where one is made

    with gmsh_session("mechanism") as gmsh:
        shapes = draw(gmsh, mechanism, dim)
        _refine(gmsh, mechanism, shapes, size_factor, coarse, dim)
        gmsh.option.setNumber("Mesh.ElementOrder", 1)
        try:
            gmsh.model.mesh.generate(dim)
        except Exception as error:  # gmsh raises plain Exception with its message
            raise ValueError(f"{mechanism.source}: gmsh could not mesh the mechanism: "
                             f"{error}") from None
        return mesh_from_gmsh(gmsh)
