"""The continuum of a :class:`~.description.SpatialMechanism`: its bodies (boxes, cylinders,
prisms) and flexures (wires as cylinders, leaves as plates) drawn with gmsh's OpenCASCADE
kernel from the description's numbers alone (no user text reaches gmsh), fragmented into
one conforming solid with a boundary group per body (its faces where no flexure meets it)
and "solid"; meshed in tetrahedra refined in every flexure (at least two elements through a
wire's diameter or a leaf's thickness, and AROUND elements round a wire's circumference). The model raises the order (P2 by default).
Lengths in m."""
import math

import numpy as np

from ...fem import FEMesh, gmsh_session, mesh_from_gmsh
from ...fem.curved import curved_onto_cylinders
from ...fem.budget import NODES_PER_ELEMENT, TETRAHEDRA_PER_CUBE, check_budget
from ..mechanism.draw import size_by_fields, threshold_field
from .description import AXES, SpatialMechanism, Wire, flexure_label
from .mass import mass_properties

#: Elements through a wire's diameter or a leaf's thickness, by default.
THROUGH = 2
#: Elements round a curved surface's full circle (a wire's circumference, a cylinder
#: body's), by default: gmsh's curvature-based size (Mesh.MeshSizeFromCurvature). Two
#: elements through a wire alone would make its section a polygon of about six sides,
#: 0.69 of the circle's I; sixteen round it, with the cells curved onto the cylinder
#: (fem/curved.py), give the circle's to O(h^4) (docs/spatial.md).
AROUND = 16


def around_size(diameter: float, size_factor: float = 1.0) -> float:
    """The curvature-based element size (m) on a round surface of ``diameter`` (m): its
    circumference over :data:`AROUND` elements, times ``size_factor``."""
    return math.pi * diameter / AROUND * size_factor


def flexure_size(flexure) -> float:
    """The element size (m) in a flexure: its diameter or thickness over :data:`THROUGH`."""
    return (flexure.diameter if isinstance(flexure, Wire) else flexure.thickness) / THROUGH


def body_size(mechanism: SpatialMechanism, coarse: float | None = None) -> float:
    """The element size (m) in the bodies: ``coarse`` or a twentieth of the mechanism, at
    most half the shortest box side, never finer than the coarsest flexure's size."""
    if coarse is None:
        sides = [abs(hi[k] - lo[k]) for b in mechanism.bodies for lo, hi in b.boxes
                 for k in range(3)]
        sides += [c.diameter for b in mechanism.bodies for c in b.cylinders]
        coarse = min([mechanism.size / 20] + [s / 2 for s in sides])
    return max(coarse, max(flexure_size(f) for f in mechanism.flexures))


def estimate_mesh(mechanism: SpatialMechanism, size_factor: float = 1.0,
                  coarse: float | None = None, order: int = 2) -> dict:
    """{"elements", "nodes", "dofs"} expected of :func:`mesh_spatial`: the bodies at their
    size, each flexure's volume with a band of one element round it at its own size (the
    planar path's rule, fem/budget.py's tetrahedra per cube)."""
    h_body = body_size(mechanism, coarse) * size_factor
    elements = sum(mass_properties(b).volume for b in mechanism.bodies) / (h_body ** 3 / TETRAHEDRA_PER_CUBE)
    for i, f in enumerate(mechanism.flexures):
        h = flexure_size(f) * size_factor
        length = mechanism.span(i).length
        if isinstance(f, Wire):
            band = math.pi * (f.diameter / 2 + h) ** 2 * length
            rim = around_size(f.diameter, size_factor)  # a layer of that size under its surface
            if rim < h:
                elements += math.pi * f.diameter * length * rim / (rim ** 3 / TETRAHEDRA_PER_CUBE)
        else:
            band = (f.width + 2 * h) * (f.thickness + 2 * h) * length
        elements += band / (h ** 3 / TETRAHEDRA_PER_CUBE)
    nodes = NODES_PER_ELEMENT[(3, order)] * elements
    return {"elements": int(min(elements, 1e18)), "nodes": int(min(nodes, 1e18)),
            "dofs": int(min(3 * nodes, 1e18))}


def _prism(occ, prism) -> list:
    k = AXES[prism.axis]
    points = []
    for u, v in prism.polygon:
        q = [0.0, 0.0, 0.0]
        q[(k + 1) % 3], q[(k + 2) % 3], q[k] = u, v, prism.span[0]
        points.append(occ.addPoint(*q))
    lines = [occ.addLine(points[i], points[(i + 1) % len(points)]) for i in range(len(points))]
    face = occ.addPlaneSurface([occ.addCurveLoop(lines)])
    shift = [0.0, 0.0, 0.0]
    shift[k] = prism.span[1] - prism.span[0]
    return [(d, t) for d, t in occ.extrude([(2, face)], *shift) if d == 3]


def body_shapes(occ, body) -> list:
    """[(3, tag)]: a body's boxes, cylinders and prisms drawn, fused into one shape and
    turned by its pose."""
    shapes = [(3, occ.addBox(*lo, *np.subtract(hi, lo))) for lo, hi in body.boxes]
    shapes += [(3, occ.addCylinder(*c.start, *np.subtract(c.end, c.start), c.diameter / 2))
               for c in body.cylinders]
    for p in body.prisms:
        shapes += _prism(occ, p)
    if len(shapes) > 1:
        shapes, _ = occ.fuse(shapes[:1], shapes[1:])
    if body.pose is not None:
        occ.rotate(shapes, *body.pose.about, *body.pose.axis, body.pose.angle)
    return shapes


def _rim(f, centre, e) -> list:
    """Points (m) round the section of flexure ``f`` about ``centre`` on the plane across the
    unit axis ``e``: a leaf's four corners, eight points on a wire's circle."""
    if isinstance(f, Wire):
        u = np.cross(e, np.eye(3)[int(np.argmin(np.abs(e)))])
        u /= np.linalg.norm(u)
        v = np.cross(e, u)
        r = f.diameter / 2
        return [centre + r * (math.cos(a) * u + math.sin(a) * v)
                for a in np.linspace(0, 2 * math.pi, 8, endpoint=False)]
    w = np.asarray(f.width_along, float)
    w, n = w / np.linalg.norm(w) * f.width / 2, f.normal * f.thickness / 2
    return [centre - w - n, centre + w - n, centre + w + n, centre - w + n]


def root_extensions(mechanism: SpatialMechanism, index: int) -> tuple:
    """(at from, at to) (m): how far flexure ``index``'s solid is drawn on beyond its ends
    into their bodies. An end whose section lies wholly inside or on its body needs none (a
    flexure standing square on a body's face); one that leaves part of its section outside
    (an oblique leaf ending on a face: a wedge-shaped notch half its thickness deep) is
    drawn on by its half-section, where that lies inside the body: the part inside is the
    body's, so the root is solid, as the description means."""
    f = mechanism.flexures[index]
    a, b = np.asarray(f.start, float), np.asarray(f.end, float)
    e = (b - a) / np.linalg.norm(b - a)
    tol, out = mechanism.tol, []
    for point, sign, name in ((a, -1.0, f.between[0]), (b, 1.0, f.between[1])):
        body = mechanism.body(name)
        if all(body.contains(p, tol) for p in _rim(f, point, e)):
            out.append(0.0)
            continue
        reach = f.radius
        deeper = point + sign * reach * e
        inside = all(body.contains(p, tol) for p in _rim(f, deeper, e))
        out.append(reach if inside else 0.0)
    return tuple(out)


def _flexure_shape(occ, f, extensions=(0.0, 0.0)) -> list:
    """The flexure's solid over its whole axis (from -> to, inside the bodies at its ends,
    drawn on by ``extensions`` (m) at each: :func:`root_extensions`; the fragment keeps the
    part outside them as the flexure)."""
    start, end = np.asarray(f.start, float), np.asarray(f.end, float)
    e = (end - start) / np.linalg.norm(end - start)
    start, end = start - extensions[0] * e, end + extensions[1] * e
    axis = end - start
    if isinstance(f, Wire):
        return [(3, occ.addCylinder(*start, *axis, f.diameter / 2))]
    points = [occ.addPoint(*c) for c in _rim(f, start, e)]
    lines = [occ.addLine(points[i], points[(i + 1) % 4]) for i in range(4)]
    face = occ.addPlaneSurface([occ.addCurveLoop(lines)])
    return [(d, t) for d, t in occ.extrude([(2, face)], *axis) if d == 3]


def flexure_shapes(occ, mechanism: SpatialMechanism) -> list:
    """[[(3, tag)] per flexure]: each flexure's solid (:func:`_flexure_shape`) with its
    :func:`root_extensions`."""
    return [_flexure_shape(occ, f, root_extensions(mechanism, i))
            for i, f in enumerate(mechanism.flexures)]


def draw(gmsh, mechanism: SpatialMechanism) -> dict:
    """Draw ``mechanism`` into the open gmsh session as one conforming solid, a boundary
    group per body and "solid"; {"bodies": {name: [volume tags]}, "flexures": [[volume
    tags] per flexure]}. A part that lies inside a body counts as that body."""
    occ = gmsh.model.occ
    body_tags = [body_shapes(occ, b) for b in mechanism.bodies]
    flexure_tags = flexure_shapes(occ, mechanism)
    inputs = body_tags + flexure_tags
    flat = [dt for tags in inputs for dt in tags]
    _, children = occ.fragment(flat, [])
    occ.synchronize()
    n_bodies = len(mechanism.bodies)
    owner = {}
    for group, kids in zip([g for g, tags in enumerate(inputs) for _ in tags], children):
        for _, tag in kids:
            owner.setdefault(tag, group)  # a body first: what lies in a body is the body
            owner[tag] = min(owner[tag], group)
    parts = [sorted(t for t, g in owner.items() if g == k) for k in range(len(inputs))]
    count = {}
    for _, tag in gmsh.model.getEntities(3):
        for _, face in gmsh.model.getBoundary([(3, tag)], combined=False, oriented=False):
            count[abs(face)] = count.get(abs(face), 0) + 1
    for body, tags in zip(mechanism.bodies, parts[:n_bodies]):
        faces = {abs(f) for _, f in gmsh.model.getBoundary([(3, t) for t in tags],
                                                          combined=False, oriented=False)}
        gmsh.model.addPhysicalGroup(2, sorted(f for f in faces if count[f] == 1),
                                    name=body.name)
    gmsh.model.addPhysicalGroup(3, sorted(owner), name="solid")
    return {"bodies": {b.name: parts[k] for k, b in enumerate(mechanism.bodies)},
            "flexures": parts[n_bodies:]}


def _refine(gmsh, mechanism, shapes, size_factor, coarse) -> None:
    thresholds = []
    for f, tags in zip(mechanism.flexures, shapes["flexures"]):
        faces = sorted({abs(s) for _, s in gmsh.model.getBoundary(
            [(3, t) for t in tags], combined=False, oriented=False)})
        near = 2 * flexure_size(f)
        thresholds.append(threshold_field(gmsh, faces, 3, flexure_size(f) * size_factor,
                                          coarse * size_factor, near, 2 * coarse))
    size_by_fields(gmsh, thresholds, coarse * size_factor)
    if any(isinstance(f, Wire) for f in mechanism.flexures) or any(
            b.cylinders for b in mechanism.bodies):  # the min of this and the fields
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature",
                              math.ceil(AROUND / size_factor))


def mesh_spatial(mechanism: SpatialMechanism, size_factor: float = 1.0,
                 coarse: float | None = None, order: int = 2,
                 max_dofs: int | None = None) -> FEMesh:
    """The meshed continuum (linear tetrahedra; the Model raises the order, and at order 2
    the cells on the wires' and cylinders' surfaces are curved onto them: fem/curved.py)
    with a boundary group per body and "solid". ``size_factor`` scales every element size, ``coarse`` the
    bodies' size (m); a mesh whose estimate is above ``max_dofs`` (None: half the available
    memory) is refused first (BudgetError, fem/budget.py), and so is one whose nodes pass it
    once meshed."""
    if not (math.isfinite(size_factor) and size_factor > 0):
        raise ValueError(f"size_factor = {size_factor!r} must be a finite number > 0")
    for body, vector, source in mechanism.moments:
        if any(vector):
            raise ValueError(f"{source}: [[loads]] moment on {body!r}: the continuum takes "
                             "forces on faces; a moment on a body is the beam model's "
                             "(--model beam)")
    what = f"the spatial mechanism's mesh at size_factor {size_factor:g}"
    check_budget(estimate_mesh(mechanism, size_factor, coarse, order), 3, max_dofs, what=what)
    coarse = body_size(mechanism, coarse)
    with gmsh_session("spatial mechanism") as gmsh:
        try:
            shapes = draw(gmsh, mechanism)
        except Exception as error:  # gmsh raises plain Exception with OCC's message
            raise ValueError(f"{mechanism.source}: gmsh cannot fuse the bodies and flexures "
                             f"({error}); look for a degenerate shape") from None
        for k, tags in enumerate(shapes["flexures"]):
            if not tags:
                raise ValueError(f"{mechanism.source}: "
                                 f"{flexure_label(mechanism.flexures[k], k)} lies inside a "
                                 "body: it has no free span")
        _refine(gmsh, mechanism, shapes, size_factor, coarse)
        gmsh.option.setNumber("Mesh.ElementOrder", 1)
        try:
            gmsh.model.mesh.generate(3)
        except Exception as error:
            raise ValueError(f"{mechanism.source}: gmsh could not mesh the mechanism: "
                             f"{error}") from None
        nodes = len(gmsh.model.mesh.getNodes()[0])
        ratio = NODES_PER_ELEMENT[(3, order)] / NODES_PER_ELEMENT[(3, 1)]
        check_budget({"elements": 0, "nodes": int(nodes * ratio),
                      "dofs": int(3 * nodes * ratio)}, 3, max_dofs, what=what)
        mesh = mesh_from_gmsh(gmsh)
    return curved_onto_cylinders(mesh, round_surfaces(mechanism)) if order == 2 else mesh


def round_surfaces(mechanism: SpatialMechanism) -> list:
    """[(start, end, radius)] (m) of every wire and cylinder body: the surfaces the quadratic
    cells are curved onto (fem/curved.py)."""
    out = [(f.start, f.end, f.diameter / 2) for f in mechanism.flexures if isinstance(f, Wire)]
    for b in mechanism.bodies:
        turn = (lambda p: p) if b.pose is None else b.pose.to_world
        out += [(turn(c.start), turn(c.end), c.diameter / 2) for c in b.cylinders]
    return out
