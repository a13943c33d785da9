"""Spatial (6-DOF) beam model of the eight-bar flexure suspension, for out-of-plane modes.

    model, info = eightbar_beam3d_model(EightBarFlexureParams())            # flexible links
    model, info = eightbar_beam3d_model(EightBarFlexureParams(), links="rigid")

Built from the planar beam model of the same parameters
(:func:`flexfem.reduced.eightbar.eightbar_beam_model`): the same flexure nodes (in the
plane z = 0), elements and clamps, with the out-of-plane properties added: every section
becomes the t x w rectangle of its in-plane depth t (tapered as the planar element's through
the root fillets) and the out-of-plane width w = ``thickness``, with I_y = t w^3 / 12 and the
Saint-Venant J. Links "flexible" (default; more accurate, docs/beam.md): every link plate and
anchor as beams of its W x w section along its skeleton (:mod:`.link_beams`), the flexures
rigidly offset to their real ends on it. Links "rigid": the planar model's rigid links, mass
and polar inertia J_z, and J_x, J_y of the link's plate (union of its bars and hubs,
thickness w) about its centroid.
"""
import numpy as np

from ..fem.beam.spatial import Beam3DModel, RigidLink, Section
from .layout import ROOT_EXTENSION, link_moments
from .spatial import lifted_model, spatial_sections
from .eightbar import EE_LINK, eightbar_beam_model
from ..geometry.eightbar.flexure import EightBarFlexureParams, eightbar_layout
from ..geometry.eightbar.link_beams import link_skeleton, mesh_skeleton

LINKS = ("flexible", "rigid")


def link_plate_inertia(parts, link: str, out_of_plane: float, rho: float) -> tuple:
    """(mass kg, centroid (2,) m, J_x, J_y kg m^2) of ``link``'s plate (the union of its
    rectangles, :func:`..beam_layout.link_moments`) about in-plane axes through its
    centroid."""
    A, Sx, Sy, Ixx, Iyy = link_moments(parts, link)
    c = np.array([Sx / A, Sy / A])
    m = rho * out_of_plane * A
    thick = m * out_of_plane**2 / 12.0
    jx = rho * out_of_plane * (Iyy - A * c[1] ** 2) + thick  # about x: y^2 and z^2
    jy = rho * out_of_plane * (Ixx - A * c[0] ** 2) + thick
    return float(m), c, float(jx), float(jy)


def eightbar_beam3d_model(params: EightBarFlexureParams, n_per_flexure: int = 24,
                          root_extension: float = ROOT_EXTENSION, shear: bool = True,
                          links: str = "flexible", link_element: float | None = None) -> tuple:
    """(Beam3DModel, info) of the suspension in its drawn pose; info as the planar model's
    (eightbar_beam_model): "end_effector" (a node on its bottom face's centre), "ground"
    (clamped nodes), "flexures". ``links``: "flexible" (every link plate and anchor as beams,
    :func:`flexible_links`; info "links" {link: (first, last element)}) or "rigid" (rigid
    bodies with the plates' masses; info "masters"); ``link_element``: the link elements'
    length (m, default the link width)."""
    if links not in LINKS:
        raise ValueError(f"links = {links!r} must be one of {LINKS}")
    if link_element is not None and not (isinstance(link_element, (int, float))
                                         and 0 < link_element < float("inf")):
        raise ValueError(f"link_element = {link_element!r} m must be a number > 0 (or None: "
                         "the link width)")
    planar, info = eightbar_beam_model(params, n_per_flexure, root_extension, shear)
    if links == "flexible":
        return flexible_links(planar, info, params, link_element, shear)
    w = params.thickness
    layout = eightbar_layout(params)
    rho = planar.material.rho
    masses = {}
    for link in layout.links:
        m, c, jx, jy = link_plate_inertia(layout.parts, link, w, rho)
        at = [k for k in planar.point_masses if np.allclose(planar.nodes[k], c, atol=1e-12)]
        if len(at) != 1:
            raise ValueError(f"link {link!r}: no single mass node at its centroid {c}")
        m_planar, jz = planar.point_masses[at[0]]
        masses[at[0]] = (m_planar, jx, jy, jz)
    return lifted_model(planar, w, masses), info


def _stations(layout, link: str) -> tuple:
    """([points (m) on ``link`` where something attaches], [(joint, end 0 host / 1 other)]):
    the flexures' real ends, the end-effector's face centre, the anchors' fixed faces."""
    points, ends = [], []
    for fj in layout.joints:
        for side, owner in enumerate((fj.host, fj.other)):
            if owner == link:
                points.append(fj.ends()[side])
                ends.append((fj.name, side))
    if link == EE_LINK:
        points.append(np.mean(layout.edges[EE_LINK], axis=0))
    if link == layout.ground:
        points += [np.mean(edge, axis=0) for edge in layout.fixed]
    return points, ends


def _groups(pairs, preferred) -> list:
    """RigidLinks joining the rigidly connected nodes of ``pairs`` (node, node); the master of
    each group the node of ``preferred`` in it, else the first pair's first node."""
    group = {}
    for a, b in pairs:
        ga, gb = group.get(a, [a]), group.get(b, [b])
        if ga is not gb:
            ga += gb
            for n in ga:
                group[n] = ga
    out, seen = [], set()
    for a, _ in pairs:
        g = group[a]
        if id(g) in seen:
            continue
        seen.add(id(g))
        master = next((n for n in g if n in preferred), a)
        out.append(RigidLink(master, tuple(sorted(set(g) - {master}))))
    return out


def flexible_links(planar, info: dict, params: EightBarFlexureParams,
                   link_element: float | None = None, shear: bool = True) -> tuple:
    """(Beam3DModel, info) with the planar model's flexures and every link plate and anchor
    as spatial beams of the link's W x thickness section along its skeleton
    (:mod:`.link_beams`), each flexure's (extended) end rigidly offset to its real end on
    the link; the anchors clamped at their fixed faces. No point masses: the beams carry the
    plates' mass and inertia."""
    layout, w = eightbar_layout(params), params.thickness
    size = layout.link_width if link_element is None else float(link_element)
    n_flex = min(info["masters"].values())
    if planar.elements.max() >= n_flex:
        raise ValueError("the planar model's flexure nodes are not its first nodes")
    nodes, elements = [planar.nodes[:n_flex]], [planar.elements]
    sections = spatial_sections(planar, w)
    plate = Section.rect(w, layout.link_width)
    pairs, spans, n, ground, face = [], {}, n_flex, [], None
    for link in layout.links + [layout.ground]:
        points, ends = _stations(layout, link)
        xy, el, offsets, at = mesh_skeleton(link_skeleton(layout.parts, link), points, size)
        spans[link] = (len(sections), len(sections) + len(el))
        nodes.append(xy)
        elements.append(el + n)
        sections += [plate] * len(el)
        pairs += [(a + n, b + n) for a, b in offsets]
        pairs += [(at[k] + n, info["ends"][joint][side]) for k, (joint, side) in enumerate(ends)]
        if link == EE_LINK:
            face = at[len(ends)] + n
        if link == layout.ground:
            ground = [k + n for k in at[len(ends):]]
        n += len(xy)
    xyz = np.vstack(nodes)
    model = Beam3DModel(np.column_stack([xyz, np.zeros(len(xyz))]), np.vstack(elements),
                        sections, planar.material, rigid_links=_groups(pairs, {face, *ground}),
                        shear=shear)
    return model, {"end_effector": face, "ground": ground, "flexures": info["flexures"],
                   "links": {k: v for k, v in spans.items() if k != layout.ground},
                   "anchors": spans[layout.ground]}
