"""Reduced beam models of flexure layouts: every flexure a (tapered) beam, every link rigid.

    model, nodes = layout_beam_model(layout, material, thickness, fillet_radius=r)

A flexure of length L and in-plane width w from its host end a to its other end b (a
:class:`~flexfem.geometry.flexure_linkage.FlexureJoint`) becomes a chain of co-rotational beam
elements whose section follows the drawn profile t(s) (root fillets included, via
:func:`flexfem.fem.beam.beam_from_profile`); every link is a rigid body (an exact
:class:`~flexfem.fem.beam.RigidLink`) whose master node is the link's centroid carrying the
link's mass and rotary inertia; a flexure ending on the ground is clamped.

Root extension (``root_extension``, default ROOT_EXTENSION = 0.38): a beam ends where it meets
a block, but the stress field spreads into the block over about the root thickness, which beam
theory does not have; the beam model is then too stiff by about b / l. Extending each flexure
by 0.38 times its root thickness into the block at both roots (at the root's thickness)
reproduces a 2-D plane-stress model of a sharp-cornered leaf within 0.15 % for l/b = 5-20
(docs/beam.md, "Joints and slenderness"). That is the bending side; the same spreading makes
a root axially compliant too, by about 0.38 t / H + 0.67 ln(H / t) - 0.45 (1 - t / H) over E w
per root (H the height of the block the root enters: 1.6 / (E w) for H = 20 t, as much as 1.6 t
of extra neck; 0.38 at H = t, where the extension only replaces the block it lies in), which
matters where flexures carry axial load (the DBMA with its input blocked, k_y of a guide): the
extension elements carry that axial compliance too (:func:`root_section`). Every generated
model here applies the same rule to every root, so the beam models of all mechanisms share one
calibration; ``root_extension=0`` turns both off.
All lengths in m.
"""
import math

import numpy as np

from ..fem.beam import BeamMesh, BeamModel, RigidLink, Section, beam_from_profile
from ..fem.beam.section import KAPPA

ROOT_EXTENSION = 0.38  # x root thickness, per root (docs/beam.md: l/b 5-20 within 0.15 %)
# axial compliance of a root, per root, in units of 1 / (E w): the load in a neck of thickness
# t spreads into a block of height H. A 2-D plane-stress fit (nu = 0.3, a sharp-cornered leaf,
# l/t = 10, blocks at least 2 H long, H/t = 1.1-40, within 0.03; docs/beam.md): ROOT_EXTENSION
# t / H + 0.67 ln(H / t) - 0.45 (1 - t / H); the log is a strip's spreading (about 2/pi ln H/t)
AXIAL_ROOT = (0.67, -0.45)


def axial_root_compliance(block_height: float, thickness: float) -> float:
    """Extra axial compliance of one root x E w (-): 0.38 t / H + 0.67 ln(H / t) - 0.45
    (1 - t / H), H at least t (a block no taller than the root: the extension's own)."""
    a, c = AXIAL_ROOT
    r = max(1.0, block_height / thickness)
    return ROOT_EXTENSION / r + a * math.log(r) + c * (1 - 1 / r)


def root_section(out_of_plane: float, thickness: float, length: float,
                 block_height: float | None) -> Section:
    """Section of a root-extension element of ``length`` (m): the root's area and bending
    stiffness; its axial stiffness factor such that the element's axial compliance is the
    root's (axial_root_compliance) when ``block_height`` (m) is given (else the root's own);
    no stress reported there (no depth: the root stress is the flexure's own end); no mass:
    it lies inside the body it enters, whose own model carries that material."""
    I = out_of_plane * thickness ** 3 / 12
    area = out_of_plane * thickness
    factor = 1.0
    if block_height is not None:  # length / (E A factor) = alpha / (E w)
        factor = length / (thickness * axial_root_compliance(block_height, thickness))
    return Section(A=area, Iz=I, Ay=KAPPA * area, factors=(1.0, 1.0, factor, 1.0),
                   mass_factor=0.0)


def check_root_extension(value) -> float:
    if not (isinstance(value, (int, float)) and not isinstance(value, bool)
            and math.isfinite(value) and 0 <= value <= 2):
        raise ValueError(f"root_extension = {value!r} must be a number in [0, 2] (x root "
                         "thickness)")
    return float(value)


def filleted_thickness(length: float, width: float, radius: float):
    """t(s) (m) of a flexure of ``length`` and ``width`` with quarter-circle root fillets of
    ``radius`` (m, 0: sharp) inside its length, s from its first end (m; a number or an
    array)."""
    def t(s):
        s = np.asarray(s, dtype=float)
        if radius <= 0:
            return np.full_like(s, width)
        u = np.maximum(np.maximum(radius - s, s - (length - radius)), 0.0)
        return width + 2 * (radius - np.sqrt(np.maximum(radius ** 2 - u ** 2, 0.0)))
    return t


def corrected_sections(sections, factors) -> list:
    """``sections`` with E I, kappa G A and E A multiplied by ``factors.bending``,
    ``.shear`` and ``.axial`` (a notch's 2-D correction: :mod:`.hinge_patch`)."""
    return [s.with_factors(factors.bending, factors.shear, factors.axial) for s in sections]


def profile_beam(a, b, thickness_fn, out_of_plane: float, breaks=(), n_total: int = 24,
                 root_extension: float = ROOT_EXTENSION, blocks=(None, None),
                 vectorized: bool = False, factors=None) -> BeamMesh:
    """A flexure from ``a`` to ``b`` (m) of in-plane thickness ``thickness_fn(s)`` (s from
    a, m) and out-of-plane width ``out_of_plane`` (m), as beam elements: pieces between the
    arc lengths ``breaks`` (e.g. the fillets' tangent points) meshed separately, about
    ``n_total`` elements in all (at least 4 per piece); extended by ``root_extension`` x the
    root thickness at both ends (those elements at the root's bending stiffness, and its
    axial compliance where the height of the block it enters, ``blocks`` = (H at a, H at b)
    m, is given: :func:`root_section`). point_nodes: [first node, last node] (the ends of the
    extended beam). ``vectorized``: thickness_fn takes arrays of s (beam_from_profile's)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    length = float(np.linalg.norm(b - a))
    d, tol = (b - a) / length, 1e-9 * length
    cuts = [0.0] + sorted(float(s) for s in breaks if 0 < s < length) + [length]
    t0, t1 = float(thickness_fn(0.0)), float(thickness_fn(length))
    e0, e1 = root_extension * t0, root_extension * t1
    pieces = [beam_from_profile(a + s0 * d, a + s1 * d, (lambda s, s0=s0: thickness_fn(s0 + s)),
                                out_of_plane, max(4, int(round(n_total * (s1 - s0) / length))),
                                vectorized) for s0, s1 in zip(cuts[:-1], cuts[1:])]
    if factors is not None:
        pieces = [BeamMesh(m.nodes, m.elements, corrected_sections(m.sections, factors),
                           m.point_nodes) for m in pieces]
    start, end, root, tip = a, b, None, None
    if e0 > 0:
        start = a - e0 * d
        root = _one_element(start, a, root_section(out_of_plane, t0, e0, blocks[0]))
    if e1 > 0:
        end = b + e1 * d
        tip = _one_element(b, end, root_section(out_of_plane, t1, e1, blocks[1]))
    mesh = _line_mesh([m for m in [root, *pieces, tip] if m is not None], tol)
    if mesh is not None:  # one chain from start to end, point_nodes [0, n - 1]
        return mesh
    mesh = pieces[0]  # a piece shorter than tol: BeamMesh.join's general merge decides
    for part in pieces[1:]:
        mesh = mesh.join(part, tol=tol)
    mesh = mesh if root is None else root.join(mesh, tol=tol)
    mesh = mesh if tip is None else mesh.join(tip, tol=tol)
    first, last = mesh.node_at(start, tol=tol), mesh.node_at(end, tol=tol)
    return BeamMesh(mesh.nodes, mesh.elements, mesh.sections, [first, last])


def _one_element(a, b, section) -> BeamMesh:
    """beam_chain([a, b], section, 1) (the same nodes: a, b) without its checks."""
    return BeamMesh(np.array([a, b], dtype=float), np.array([[0, 1]]), [section], [0, 1])


def _line_mesh(parts, tol: float) -> BeamMesh | None:
    """Chains ``parts`` (BeamMesh, each a chain of consecutive nodes) along one straight line,
    each starting where the previous one ends, joined as successive BeamMesh.join calls
    would (the shared end node kept from the earlier part), without their all-pairs node
    search; None where two nodes are within ``tol`` (m) of each other other than at a joint
    (then the general join decides which merge)."""
    for prev, part in zip(parts, parts[1:]):
        if math.dist(prev.nodes[-1], part.nodes[0]) > tol:
            return None
    nodes = np.vstack([parts[0].nodes] + [part.nodes[1:] for part in parts[1:]])
    step = np.diff(nodes, axis=0)
    if np.hypot(step[:, 0], step[:, 1]).min() <= tol:
        return None
    n = len(nodes)
    return BeamMesh(nodes, np.column_stack([np.arange(n - 1), np.arange(1, n)]),
                    [sec for part in parts for sec in part.sections], [0, n - 1])


def clip_convex(poly, clipper) -> list:
    """Sutherland-Hodgman: the part of convex polygon ``poly`` inside convex counter-
    clockwise ``clipper`` (lists of (x, y))."""
    out = list(poly)
    for (ax, ay), (bx, by) in zip(clipper, clipper[1:] + clipper[:1]):
        inside = lambda p: (bx - ax) * (p[1] - ay) - (by - ay) * (p[0] - ax) >= 0
        points, out = out, []
        for p, q in zip(points, points[1:] + points[:1]):
            if inside(q):
                if not inside(p):
                    out.append(_cross(p, q, (ax, ay), (bx, by)))
                out.append(q)
            elif inside(p):
                out.append(_cross(p, q, (ax, ay), (bx, by)))
        if not out:
            return []
    return out


def _cross(p, q, a, b) -> tuple:
    """Intersection of segment p-q with the line a-b."""
    d1 = (q[0] - p[0], q[1] - p[1])
    d2 = (b[0] - a[0], b[1] - a[1])
    t = ((a[0] - p[0]) * d2[1] - (a[1] - p[1]) * d2[0]) / (d1[0] * d2[1] - d1[1] * d2[0])
    return (p[0] + t * d1[0], p[1] + t * d1[1])


def _moments(poly) -> np.ndarray:
    """(area, S_x = int x, S_y = int y, int x^2, int y^2) of a polygon about the origin."""
    a = sx = sy = ixx = iyy = 0.0  # float sums, in the order of the former array sums
    for (x0, y0), (x1, y1) in zip(poly, poly[1:] + poly[:1]):
        c = x0 * y1 - x1 * y0
        a += c / 2
        sx += (x0 + x1) * c / 6
        sy += (y0 + y1) * c / 6
        ixx += (x0 * x0 + x0 * x1 + x1 * x1) * c / 12
        iyy += (y0 * y0 + y0 * y1 + y1 * y1) * c / 12
    return np.array([a, sx, sy, ixx, iyy])


def link_moments(parts, link: str) -> np.ndarray | None:
    """:func:`_moments` of the union of the rectangles of ``link`` (bars and hubs, which
    overlap at the bars' corners and ends): inclusion-exclusion over the rectangles' overlaps
    up to three at a time (bars meeting at a point with a hub; exact unless four overlap);
    None for a link without rectangles."""
    rects = [[tuple(c) for c in p.corners()] for p in parts
             if p.link == link and p.kind != "flexure"]
    if not rects:
        return None
    total, n = sum(_moments(r) for r in rects), len(rects)
    for i in range(n):
        for j in range(i + 1, n):
            pair = clip_convex(rects[i], rects[j])
            if len(pair) < 3:
                continue
            total = total - _moments(pair)
            for k in range(j + 1, n):
                triple = clip_convex(pair, rects[k])
                if len(triple) >= 3:
                    total = total + _moments(triple)
    return total


def link_inertia(parts, link: str, out_of_plane: float, rho: float) -> tuple:
    """(mass kg, centroid (2,) m, rotary inertia about it kg m^2) of the union of the
    rectangles of ``link`` (:func:`link_moments`)."""
    total = link_moments(parts, link)
    if total is None:
        return 0.0, None, 0.0
    A, Sx, Sy, Ixx, Iyy = total
    J = Ixx + Iyy
    centroid = np.array([Sx / A, Sy / A])
    m = rho * out_of_plane * A
    return float(m), centroid, float(rho * out_of_plane * (J - A * float(centroid @ centroid)))


def layout_beam_model(layout, material, out_of_plane: float, fillet_radius: float = 0.0,
                      n_per_flexure: int = 24, root_extension: float = ROOT_EXTENSION,
                      anchors: dict | None = None, shear: bool = True) -> tuple:
    """(BeamModel, info) of a :class:`~flexfem.geometry.flexure_linkage.FlexureLayout`:
    flexures as beams (fillets of ``fillet_radius`` m in their profile), links rigid with
    their masses (``material.rho``, thickness ``out_of_plane``) at master nodes on their
    centroids, or at ``anchors`` {link: point (m)} where given (the node a load or support
    is applied to). info: {"masters": {link: node}, "ground": [clamped nodes],
    "flexures": {joint: (first element, last element)}}."""
    root_extension = check_root_extension(root_extension)
    mesh, ends, spans = None, {}, {}
    for fj in layout.joints:
        a, b = fj.ends()
        r = min(fillet_radius, 0.49 * fj.length)
        fn = filleted_thickness(fj.length, fj.width, r)
        breaks = (r, fj.length - r) if r > 0 else ()
        part = profile_beam(a, b, fn, out_of_plane, breaks, n_per_flexure, root_extension,
                            blocks=(layout.link_width, layout.link_width), vectorized=True)
        offset_e = 0 if mesh is None else len(mesh.elements)
        if mesh is None:
            mesh, index = part, np.arange(len(part.nodes))
        else:
            n0 = len(mesh.nodes)
            mesh = BeamMesh(np.vstack([mesh.nodes, part.nodes]),
                            np.vstack([mesh.elements, part.elements + n0]),
                            list(mesh.sections) + list(part.sections), [])
            index = np.arange(len(part.nodes)) + n0
        ends[fj.name] = (int(index[part.point_nodes[0]]), int(index[part.point_nodes[1]]))
        spans[fj.name] = (offset_e, offset_e + len(part.elements))
    nodes = [mesh.nodes]
    masters, masses, slaves, n = {}, {}, {}, len(mesh.nodes)
    for link in layout.links:
        m, centroid, J = link_inertia(layout.parts, link, out_of_plane, material.density_or_nan)
        anchored = link in (anchors or {}) and centroid is not None
        point = np.asarray(anchors[link] if anchored else centroid, float)
        masters[link], slaves[link] = n, []
        nodes.append(point[None, :])
        n += 1
        if anchored:  # a slave node on the centroid carries the mass
            nodes.append(centroid[None, :])
            slaves[link].append(n)
            n += 1
        masses[n - 1] = (m, J)
    ground = []
    for fj in layout.joints:
        first, last = ends[fj.name]
        slaves[fj.host].append(first)
        (ground if fj.other == layout.ground else slaves[fj.other]).append(last)
    links = [RigidLink(masters[k], tuple(v)) for k, v in slaves.items() if v]
    model = BeamModel(np.vstack(nodes), mesh.elements, mesh.sections, material, shear=shear,
                      rigid_links=links, point_masses=masses)
    return model, {"masters": masters, "ground": ground, "flexures": spans, "ends": ends}
