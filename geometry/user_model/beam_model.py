"""The reduced beam model of a model file that declares its beams (``[[beam]]``,
``[[rigid]]``): ``beam_model(spec) -> (BeamModel, info)``.

Each [[beam]] is a chain of straight segments through its points, each segment n tapered
elements (:func:`flexfem.fem.beam.beam_from_profile` through the thickness profile t(s));
beams that share a point are joined there (welded). Each [[rigid]] is a rigid body
(:class:`flexfem.fem.beam.RigidLink`) carrying the beam points it joins, one node per group it
names (where the continuum's supports and loads act) and the mass of its blocks (on a node at
their centroid). A beam end joined to a rigid body is extended into it by root_extension x its
thickness (:func:`flexfem.geometry.beam_layout.root_section`: the root's compliance, which
beam theory has not; docs/beam.md, "Joints and slenderness"). Lengths in m.
"""
import math

import numpy as np

from ...fem.beam import BeamMesh, BeamModel, RigidLink, beam_chain, beam_from_profile
from ..beam_layout import root_section


def _error(where: str, message: str) -> ValueError:
    return ValueError(f"{where}: {message}")


def _line_mesh(line, tol) -> BeamMesh:
    """Each segment ``line.elements`` quadratically tapered elements through t(s)."""
    mesh, profile = None, line.thickness
    for k in range(len(line.points) - 1):
        part = beam_from_profile(line.points[k], line.points[k + 1],
                                 lambda s, s0=profile.arc[k]: profile(s0 + s), line.depth,
                                 line.elements)
        mesh = part if mesh is None else mesh.join(part, tol)
    return mesh


def _extension(line, end: int, factor: float) -> BeamMesh | None:
    """The root-extension element beyond the beam's first (end 0) or last (end -1) point."""
    a, b = (line.points[0], line.points[1]) if end == 0 else (line.points[-1], line.points[-2])
    t = line.thickness(0.0 if end == 0 else line.thickness.length)
    length = factor * t
    if length <= 0:
        return None
    d = np.subtract(a, b) / math.dist(a, b)
    return beam_chain([a, tuple(np.add(a, length * d))],
                      root_section(line.depth, t, length, None), 1)


def _mesh(beams, tol) -> tuple:
    """(BeamMesh of all beams, {node of a joined beam end: [the ends of its root
    extensions]})."""
    mesh, extensions = None, []
    joined = [p for body in beams.rigid for p in body.joins]
    for line in beams.beams:
        part = _line_mesh(line, tol)
        mesh = part if mesh is None else mesh.join(part, tol)
        for end in (0, -1):
            p = line.points[end]
            if any(math.dist(p, q) <= tol for q in joined):
                ext = _extension(line, end, beams.root_extension)
                if ext is not None:
                    extensions.append(ext)
    ends = {}
    for ext in extensions:  # after all beams: node numbers of the joined mesh are final
        mesh = mesh.join(ext, tol)
        ends.setdefault(mesh.node_at(ext.nodes[0], tol), []).append(
            mesh.node_at(ext.nodes[1], tol))
    return mesh, ends


def _rect_inertia(block, rho_t) -> tuple:
    """(mass kg, centroid (2,) m, rotary inertia about the centroid kg m^2) of a rectangle."""
    (x0, y0), (x1, y1) = block
    w, h = abs(x1 - x0), abs(y1 - y0)
    m = rho_t * w * h
    return m, np.array([(x0 + x1) / 2, (y0 + y1) / 2]), m * (w * w + h * h) / 12


def _body_mass(body, rho_t) -> tuple:
    """(mass, centroid, rotary inertia about it) of the union of a body's (disjoint) blocks."""
    parts = [_rect_inertia(b, rho_t) for b in body.blocks]
    m = sum(p[0] for p in parts)
    c = sum(p[0] * p[1] for p in parts) / m
    J = sum(p[2] + p[0] * float((p[1] - c) @ (p[1] - c)) for p in parts)
    return m, c, J


class _Nodes:
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
    """(BeamModel, info) of ``spec`` (a ModelSpec with beams). info: "groups" {group: node},
    "masters" [node per rigid body], "bodies" {group: index of its rigid body}. ValueError
    naming the model file where a rigid body joins no beam point, a point is joined twice, or
    a support or load group has no point."""
    beams = spec.beams
    if beams is None:
        raise ValueError(f"{spec.source}: the model file declares no beams ([[beam]], "
                         "docs/model_files.md, 'The beam model'); use the continuum model")
    scale = max(math.dist(a, b) for line in beams.beams for a, b in zip(line.points,
                                                                      line.points[1:]))
    tol = 1e-9 * scale
    mesh, ends = _mesh(beams, tol)
    nodes = _Nodes(mesh.nodes, tol)
    supported = {s.group for s in spec.supports}
    groups, links, masses, owner, masters = {}, [], {}, {}, []
    for i, body in enumerate(beams.rigid):
        slaves = []
        for p in body.joins:
            node = nodes.at(p, add=False)
            if node is None:
                raise _error(body.source, f"[[rigid]] joins {list(p)}, which is no point of "
                             "a [[beam]]")
            slaves += ends.get(node, [node])
        # a group's point or the mass centre reuses only this body's nodes: never welds
        # another beam's node to the block
        named = {g: nodes.at(p, among=set(slaves)) for g, p in body.groups.items()}
        first = _master_group(body, supported)
        master = named[first] if first is not None else slaves[0]
        if body.blocks:
            m, c, J = _body_mass(body, spec.material.rho * spec.thickness)
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
    _check_groups(spec, groups)
    model = BeamModel(np.asarray(nodes.xy), mesh.elements, mesh.sections, spec.material,
                      shear=beams.shear, rigid_links=links, point_masses=masses)
    return model, {"groups": groups, "masters": masters, "bodies": dict(beams.groups)}


def _check_groups(spec, groups: dict) -> None:
    """Every support, load and compliance group must have a point in a [[rigid]] body."""
    needed = [(s.group, s.source) for s in spec.supports]
    needed += [(load.group, load.source) for load in spec.loads]
    if spec.analysis.compliance:
        needed.append((spec.analysis.compliance, spec.source))
    for group, where in needed:
        if group not in groups:
            raise _error(where or spec.source, f"group {group!r} has no point in the beam "
                         "model: name it in a [[rigid]] body's groups = { "
                         f"{group} = [x, y] }} (known: {', '.join(groups) or 'none'})")
