"""The reduced beam model of a model file that declares its beams (``[[beam]]``,
``[[rigid]]``): ``beam_model(spec) -> (BeamModel, info)``.

Each [[beam]] is a chain of straight segments through its points, each segment n tapered
elements (:func:`flexfem.fem.beam.beam_from_profile` through the thickness profile t(s));
beams that share a point are joined there (welded). Each [[rigid]] is a rigid body
(:class:`flexfem.fem.beam.RigidLink`) carrying the beam points it joins, one node per group it
names (where the continuum's supports and loads act) and the mass of its blocks (on a node at
their centroid). A beam end joined to a rigid body is extended into it by root_extension x its
thickness (:func:`flexfem.reduced.layout.root_section`: the root's compliance, which
beam theory has not; docs/beam.md, "Joints and slenderness"), axially too where the body
declares the block it enters (its chord across the beam is the block height H). A beam
leaving a declared block's face at an angle begins where its whole section has left the block,
(t/2) cot(phi) along it (:mod:`.roots`), and is extended from there. Where two beams cross
they are joined by a rigid joint (:mod:`.crossings`). A straight beam whose profile is a notch
or a filleted leaf (:func:`flexfem.reduced.hinge_patch.has_notch`) is corrected by its own
2-D model (:func:`flexfem.reduced.hinge_patch.profile_factors`: its stiffness in rotation,
shear and extension), unless ``[beam_model] notch_correction = false``. Lengths in m.
"""
import math

import numpy as np

from ..fem.beam import BeamMesh, BeamModel, RigidLink, beam_from_profile, profile_chain
from ..fem.beam.mesh import point_distances
from ..geometry.polygon import chord as polygon_chord, moments as polygon_moments
from .layout import corrected_sections, root_section
from .hinge_patch import has_notch, profile_factors
from .crossings import crossings
from .roots import root_offset


def _error(where: str, message: str) -> ValueError:
    return ValueError(f"{where}: {message}")


def _notch_factors(line, nu: float):
    """The 2-D correction (NotchFactors) of a [[beam]] whose profile is a notch or a filleted
    leaf, None for any other: a beam of one straight segment (collinear points) whose
    thickness is least inside it and at least 1.5 times that at both ends
    (:func:`..hinge_patch.has_notch`)."""
    profile = line.thickness
    if profile.expression is None and min(profile.values) == max(profile.values):
        return None  # a uniform leaf: nothing to correct
    points = np.asarray(line.points, float)
    chord = points[-1] - points[0]
    length = float(np.linalg.norm(chord))
    d = chord / length
    offsets = d[0] * (points[:, 1] - points[0, 1]) - d[1] * (points[:, 0] - points[0, 0])
    if np.abs(offsets).max() > 1e-9 * length:
        return None
    if not has_notch(line.thickness, line.thickness.length):
        return None
    return profile_factors(line.thickness, line.thickness.length, nu)


#: the least elements on a piece of a flexure between its profile's breaks (a fillet)
PROFILE_PIECE_ELEMENTS = 4


def _line_mesh(line, tol, cuts=None, trim=(0.0, 0.0), factors=None) -> BeamMesh:
    """Each segment ``line.elements`` quadratically tapered elements through t(s); a segment
    split at ``cuts`` {segment: [arc lengths from its first point, m]} (a crossing's rigid
    stubs) shares them among its pieces by length, at least one each; ``trim`` (m): the
    lengths left out at the first and last point (an oblique root's, :mod:`.roots`);
    ``factors``: a notch's correction on every element. The profile's breaks (a root
    fillet's end) split a segment too, and its pieces then get at least
    :data:`PROFILE_PIECE_ELEMENTS` each (an element across a fillet's end, quadratic through
    a thick root and the thin blade, would dip below the blade), as the layouts'
    profile_beam does."""
    cuts, pieces = cuts or {}, []  # pieces: (start, end, arc length at its start, elements)
    last, before = len(line.points) - 2, 0.0  # before: arc length to the segment's start, m
    for k in range(last + 1):
        a, b = np.asarray(line.points[k], float), np.asarray(line.points[k + 1], float)
        length = float(np.linalg.norm(b - a))
        start, stop = (trim[0] if k == 0 else 0.0), length - (trim[1] if k == last else 0.0)
        marks = [start] + sorted(cuts.get(k, [])) + [stop]
        if any(s1 - s0 <= tol for s0, s1 in zip(marks[:-1], marks[1:])):
            raise ValueError(f"{line.source}: [[beam]] its oblique roots (the section leaves "
                             f"the block {trim[0]:.3g} m, {trim[1]:.3g} m along it) or a "
                             "crossing's joint leave no length of its segment "
                             f"{list(line.points[k])} - {list(line.points[k + 1])}")
        breaks = [x - before for x in line.thickness.breaks
                  if all(abs(x - before - m) > tol for m in marks) and start < x - before < stop]
        least = PROFILE_PIECE_ELEMENTS if breaks else 1
        marks = sorted(marks + breaks)
        for s0, s1 in zip(marks[:-1], marks[1:]):
            pieces.append((a + s0 / length * (b - a), a + s1 / length * (b - a), before + s0,
                           max(least, round(line.elements * (s1 - s0) / length))))
        before += length
    mesh = _pieces_mesh(pieces, line, tol)
    if factors is not None:
        mesh = BeamMesh(mesh.nodes, mesh.elements, corrected_sections(mesh.sections, factors),
                        mesh.point_nodes)
    return mesh


def _pieces_mesh(pieces, line, tol) -> BeamMesh:
    """The line's pieces (start, end, arc length at the start, elements) as one chain
    (:func:`flexfem.fem.beam.profile_chain`): the pieces joined one by one (each node of a
    piece welded to one of the pieces before it within ``tol``) give the same mesh unless a
    piece comes back to one before it, where they are joined so."""
    starts, ends, arcs, counts = zip(*pieces)
    chain = profile_chain(starts, ends, arcs, counts, line.thickness.at, line.depth)
    piece = np.repeat(np.arange(len(counts)), counts)  # of each node but the first
    piece = np.concatenate([[0], piece])
    near = point_distances(chain.nodes, chain.nodes) <= tol
    if not (near & (piece[:, None] != piece[None, :])).any():
        return chain
    mesh = None
    for a, b, arc, n in pieces:
        part = beam_from_profile(a, b, lambda s, arc=arc: line.thickness.at(arc + s),
                                 line.depth, n, vectorized=True)
        mesh = part if mesh is None else mesh.join(part, tol)
    return mesh


def _end(line, end: int) -> tuple:
    """(end point, unit direction (2,) from the beam into the block beyond it, thickness m)."""
    a, b = (line.points[0], line.points[1]) if end == 0 else (line.points[-1], line.points[-2])
    t = line.thickness(0.0 if end == 0 else line.thickness.length)
    return a, np.subtract(a, b) / math.dist(a, b), t


def _extension(line, end: int, factor: float, bodies=(), offset: float = 0.0):
    """(root point, its root-extension element or None): the root point is ``offset`` (m)
    inside the beam from its first (end 0) or last (end -1) point, where its whole section has
    left the block (:func:`.roots.root_offset`); the element reaches factor x t beyond it, with
    the root's axial compliance where a block of ``bodies`` (the [[rigid]] bodies joining that
    point) declares the height it enters (:func:`_block_height`)."""
    a, d, t = _end(line, end)
    root = tuple(np.subtract(a, offset * d))
    length = factor * t
    if length <= 0:
        return root, None
    height = _block_height(a, d, [r for body in bodies for r in body.blocks])
    section = root_section(line.depth, t, length, height)
    # one element: beam_chain([root, tip], section, 1)'s mesh, without its checks
    return root, BeamMesh(np.array([root, np.add(root, length * d)]), np.array([[0, 1]]),
                          [section], [0, 1])


def _block_height(point, direction, blocks) -> float | None:
    """The height H (m) of the block a beam end at ``point`` (m) enters along ``direction``:
    the longest chord, across the beam through the point, of the rectangles ``blocks`` ((2, 2)
    opposite corners, m) or polygons ((k, 2) vertices: the piece of the line across it that
    holds the point); None where none reaches the point."""
    n = np.array([-direction[1], direction[0]])
    best = None
    for block in blocks:
        if len(block) > 2:
            length = polygon_chord(block, point, n, 1e-9 * float(np.ptp(block, axis=0).max()))
            best = max(best or 0.0, length) if length else best
            continue
        (x0, y0), (x1, y1) = block
        lo, hi = -np.inf, np.inf
        for k, (low, high) in enumerate(((min(x0, x1), max(x0, x1)),
                                         (min(y0, y1), max(y0, y1)))):
            if abs(n[k]) < 1e-12:
                if not low - 1e-12 <= point[k] <= high + 1e-12:
                    lo, hi = 0.0, -1.0
                continue
            s0, s1 = sorted(((low - point[k]) / n[k], (high - point[k]) / n[k]))
            lo, hi = max(lo, s0), min(hi, s1)
        if hi > lo and lo <= 1e-12 and hi >= -1e-12:
            best = max(best or 0.0, hi - lo)
    return best


def _root_offsets(line, bodies_at, factor: float, tol: float) -> list:
    """[s_root at the first point, at the last] (m): the oblique roots' offsets where the end
    is joined to a block (0 elsewhere, for the bare beams, root extension 0, and for roots at
    the centre line, ``factor`` 0)."""
    out = []
    for end in (0, -1):
        blocks = [r for body in bodies_at[end] for r in body.blocks]
        a, d, t = _end(line, end)
        out.append(root_offset(a, -d, t, blocks, tol, line.source) if factor > 0 else 0.0)
    return out


def _mesh(beams, tol, nu: float) -> tuple:
    """(BeamMesh of all beams, {joined beam end point: [the ends of its root extensions, or
    its root node]}, [(crossing node, its rigid stubs' nodes)]); ``nu``: Poisson's ratio (a
    notch's correction)."""
    found = crossings(beams.beams, tol, beams.root_extension) if beams.crossings == "rigid" else []
    cuts = [{} for _ in beams.beams]
    for crossing in found:
        for i, seg, s in crossing.cuts:
            cuts[i].setdefault(seg, []).append(s)
    mesh, roots = None, []
    for line, line_cuts in zip(beams.beams, cuts):
        bodies_at = [[body for body in beams.rigid
                      if any(math.dist(line.points[end], q) <= tol for q in body.joins)]
                     for end in (0, -1)]
        oblique = beams.root_extension if beams.roots == "acute_edge" else 0.0
        offsets = _root_offsets(line, bodies_at, oblique, tol)
        factors = _notch_factors(line, nu) if beams.notch_correction else None
        part = _line_mesh(line, tol, line_cuts, offsets, factors)
        mesh = part if mesh is None else mesh.join(part, tol)
        for end, bodies, offset in zip((0, -1), bodies_at, offsets):
            if bodies and (offset > 0 or beams.root_extension > 0):
                roots.append((line.points[end], *_extension(
                    line, end, beams.root_extension, bodies, offset)))
    ends = {}
    for point, root, ext in roots:  # after all beams: node numbers of the joined mesh are final
        if ext is not None:
            mesh = mesh.join(ext, tol)
            far = mesh.point_nodes[-1]  # the extension's far end, renumbered by the join
        else:
            far = mesh.node_at(root, tol)
        ends.setdefault(tuple(point), []).append(far)
    joints = []
    for crossing in found:
        stubs = []
        for i, seg, s in crossing.cuts:
            a, b = np.asarray(beams.beams[i].points[seg], float), beams.beams[i].points[seg + 1]
            stubs.append(mesh.node_at(a + s * (np.asarray(b) - a) / math.dist(a, b), tol))
        joints.append((mesh.node_at(crossing.point, tol), tuple(stubs)))
    return mesh, ends, joints


def _rect_inertia(block, rho_t) -> tuple:
    """(mass kg, centroid (2,) m, rotary inertia about the centroid kg m^2) of a rectangle."""
    (x0, y0), (x1, y1) = block
    w, h = abs(x1 - x0), abs(y1 - y0)
    m = rho_t * w * h
    return m, np.array([(x0 + x1) / 2, (y0 + y1) / 2]), m * (w * w + h * h) / 12


def _body_mass(body, rho_t) -> tuple:
    """(mass, centroid, rotary inertia about it) of the union of a body's (disjoint) blocks;
    with polygons among them, of the blocks' union (its area moments, geometry/polygon.py)."""
    if any(len(block) > 2 for block in body.blocks):
        area, c, (xx, yy, _) = polygon_moments(body.blocks)
        return rho_t * area, c, rho_t * (xx + yy)
    parts = [_rect_inertia(b, rho_t) for b in body.blocks]
    m = sum(p[0] for p in parts)
    c = sum(p[0] * p[1] for p in parts) / m
    J = sum(p[2] + p[0] * float((p[1] - c) @ (p[1] - c)) for p in parts)
    return m, c, J


class _BodyNodes:
    """The beam mesh's nodes plus the points the rigid bodies add (reusing a node there)."""

    def __init__(self, nodes, tol):
        self.xy, self.tol = [tuple(p) for p in nodes], tol

    def at(self, point, add: bool = True, among=None):
        """The node at ``point`` (m) (one of ``among`` only, if given), else a new one (or
        None if not ``add``)."""
        d = np.linalg.norm(np.asarray(self.xy) - np.asarray(point), axis=1)
        if among is not None:
            d[[k for k in range(len(d)) if k not in among]] = np.inf
        if d.min() <= self.tol:
            return int(d.argmin())
        if not add:
            return None
        self.xy.append(tuple(point))
        return len(self.xy) - 1


def _master_group(body, supported: set) -> str | None:
    held = [g for g in body.groups if g in supported]
    return held[0] if held else next(iter(body.groups), None)


def beam_model(spec) -> tuple:
    """(BeamModel, info) of ``spec`` (a ModelSpec with beams), with the file's support, load
    and [[rigid]] groups as the model's groups (:mod:`flexfem.fem.beam.face`). info: "groups" {group: node},
    "masters" [node per rigid body], "bodies" {group: index of its rigid body}. ValueError
    naming the model file where a rigid body joins no beam point, a point is joined twice, or
    a support or load group has no point."""
    beams = spec.beams
    if beams is None:
        raise ValueError(f"{spec.source}: the model file declares no beams ([[beam]], "
                         "docs/model_files.md, 'The beam model'); use the continuum model")
    if spec.section.kind != "plane_stress":
        raise ValueError(f"{spec.source}: [section] kind = {spec.section.kind!r}: the beam "
                         "model is plane stress (its beams' depth free to contract across "
                         "it); analyse plane strain with the continuum (--model continuum)")
    scale = max(math.dist(a, b) for line in beams.beams for a, b in zip(line.points,
                                                                      line.points[1:]))
    tol = 1e-9 * scale
    mesh, ends, joints = _mesh(beams, tol, spec.material.nu)
    nodes = _BodyNodes(mesh.nodes, tol)
    supported = {s.group for s in spec.supports}
    groups, links, masses, owner, masters = {}, [], {}, {}, []
    for i, body in enumerate(beams.rigid):
        slaves = []
        for p in body.joins:
            rooted = [n for q, ns in ends.items() if math.dist(p, q) <= tol for n in ns]
            node = nodes.at(p, add=False) if not rooted else None
            if node is None and not rooted:
                raise _error(body.source, f"[[rigid]] joins {list(p)}, which is no point of "
                             "a [[beam]]")
            slaves += rooted or [node]
        # a group's point or the mass centre reuses only this body's nodes: never welds
        # another beam's node to the block
        named = {g: nodes.at(p, among=set(slaves)) for g, p in body.groups.items()}
        first = _master_group(body, supported)
        master = named[first] if first is not None else slaves[0]
        if body.blocks:
            m, c, J = _body_mass(body, 1.0)  # per kg/m^2: its centroid needs no density
            rho_t = spec.material.density_or_nan * spec.thickness
            m, J = rho_t * m, rho_t * J
            centre = nodes.at(c, among=set(slaves) | set(named.values()))
            masses[centre] = (masses.get(centre, (0, 0))[0] + m,
                              masses.get(centre, (0, 0))[1] + J)
            slaves.append(centre)
        groups.update(named)
        slaves = list(dict.fromkeys(n for n in slaves + list(named.values()) if n != master))
        for n in slaves + [master]:
            if owner.setdefault(n, i) != i:
                raise _error(body.source, f"[[rigid]] point {list(nodes.xy[n])} belongs to "
                             f"rigid body {owner[n] + 1} too; join it once")
        masters.append(master)
        if slaves:
            links.append(RigidLink(master, tuple(slaves)))
    for master, stubs in joints:
        for n in (master,) + stubs:
            if n in owner:
                raise _error(beams.beams[0].source, f"a [[rigid]] body joins the crossing at "
                             f"{list(nodes.xy[master])}; join the crossing or its beams' ends")
        links.append(RigidLink(master, stubs))
    _check_groups(spec, groups)
    model = BeamModel(np.asarray(nodes.xy), mesh.elements, mesh.sections, spec.material,
                      shear=beams.shear, rigid_links=links, point_masses=masses)
    for name, node in groups.items():
        model.add_group(name, [node], _span(spec, beams.rigid[beams.groups[name]], name))
    return model, {"groups": groups, "masters": masters, "bodies": dict(beams.groups)}


def _span(spec, body, name: str = "") -> tuple:
    """The extent (m) of the face a group stands for: a body of a mechanism description is
    its group whole (its blocks' bounding box), a face of it (``stage.top``) that face's
    extent; a [[rigid]] group's point stands for a face of unknown extent (zero: a component
    held there leaves the rotation free)."""
    if spec.mechanism is None or not body.blocks:
        return (0.0, 0.0)
    from ..geometry.mechanism.faces import face_point, parse_face

    face = parse_face(name, [b.name for b in spec.mechanism.bodies], spec.dim)
    if face is not None:
        return face_point(spec.mechanism, name, *face)[1]
    corners = np.array([p for block in body.blocks for p in block], dtype=float)
    return tuple(corners.max(axis=0) - corners.min(axis=0))


def _check_groups(spec, groups: dict) -> None:
    """Every support, load and compliance group must have a point in a [[rigid]] body."""
    needed = [(s.group, s.source) for s in spec.supports]
    needed += [(load.group, load.source) for load in spec.loads]
    if spec.analysis.compliance:
        needed.append((spec.analysis.compliance, spec.source))
    points = getattr(spec, "points", {})  # [points] ride on their bodies (observe.py)
    needed += [(g, o.source) for o in getattr(spec, "outputs", ()) for g in o.groups
               if g not in points]
    for group, where in needed:
        if group not in groups:
            raise _error(where or spec.source, f"group {group!r} has no point in the beam "
                         "model: name it in a [[rigid]] body's groups = { "
                         f"{group} = [x, y] }} (known: {', '.join(groups) or 'none'})")
