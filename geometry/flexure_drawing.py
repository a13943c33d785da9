"""A :class:`~flexfem.geometry.flexure_linkage.FlexureLayout` drawn and meshed in gmsh.

:func:`mesh_layout` draws the layout's rectangles in gmsh (OpenCASCADE), meshes each flexure
with a structured grid of ``n_across`` x (L / h_along) quadratic-ready triangles and grades the
links from the flexure size to a coarse size, and returns a :class:`~flexfem.fem.mesh.FEMesh`
with subdomains (each link, "flexure_<joint>", "links", "flexures", "body") and boundaries
("fixed" and the caller's named edges). ``root_fillet_radius`` (m, default 0: sharp corners)
adds quarter-circle root fillets (:mod:`flexfem.geometry.flexure_roots`). Lengths in m.
"""
import math

import numpy as np

from ..fem.gmsh_session import gmsh_session
from ..fem.mesh import mesh_from_gmsh
from .flexure_linkage import FlexureLayout
from .mesh_fields import threshold_field
from .flexure_roots import (
    check_root_fillet_radius,
    draw_filleted_flexure,
    root_zone_depth,
)


def draw_layout(gmsh, layout: FlexureLayout, n_across: int = 3, aspect: float = 4.0,
                coarse: float | None = None, root_fillet_radius: float = 0.0) -> dict:
    """Draw ``layout`` in the open gmsh session with its physical groups and mesh sizes:
    each flexure a structured n_across x n_along grid (element length aspect * w / n_across),
    the rest graded from the flexure size up to ``coarse`` (default W / 2). With
    ``root_fillet_radius`` r > 0 (m) each flexure gets four quarter-circle root fillets (see
    :mod:`flexfem.geometry.flexure_roots`): its root zones are meshed unstructured with size
    min(w / n_across, r / 3), the middle structured. Returns {"flexure_size", "coarse_size"}
    and, with fillets, "root_size" (m)."""
    r = check_root_fillet_radius(root_fillet_radius, layout.parts, layout.link_width)
    drawn = _draw_parts(gmsh.model.occ, layout, r)
    owner, role_of = _fragment(gmsh, drawn)
    groups = _subdomains(owner, layout)
    _add_subdomain_groups(gmsh, layout, groups, owner)
    ends = {t: _curve_ends(gmsh, t) for _, t in gmsh.model.getEntities(1)}
    _add_boundary_groups(gmsh, layout, ends)
    h_min, end_curves, root_tags, root_size = _structure_flexures(
        gmsh, layout, groups, role_of, ends, r, n_across, aspect)
    coarse = (layout.link_width / 2 if coarse is None else coarse)
    _set_size_fields(gmsh, layout.link_width, coarse, h_min, end_curves, root_tags, root_size)
    sizes = {"flexure_size": h_min, "coarse_size": coarse}
    if root_size is not None:
        sizes["root_size"] = root_size
    return sizes


def _draw_parts(occ, layout: FlexureLayout, r: float) -> list:
    """Each part as OCC surface(s): [(part, surface tag, role)], role "root" / "middle" for the
    pieces of a filleted flexure (root fillet radius ``r`` > 0, m), else None."""
    drawn = []
    for part in layout.parts:
        if r > 0 and part.kind == "flexure":
            drawn += [(part, tag, role) for tag, role in draw_filleted_flexure(occ, part, r)]
            continue
        c = part.corners()
        pts = [occ.addPoint(x, y, 0.0) for x, y in c]
        lines = [occ.addLine(pts[i], pts[(i + 1) % 4]) for i in range(4)]
        drawn.append((part, occ.addPlaneSurface([occ.addCurveLoop(lines)]), None))
    return drawn


def _fragment(gmsh, drawn: list) -> tuple:
    """Fragment the drawn surfaces into one conforming body: ({surface: {parts covering it}},
    {surface: role} for the pieces of filleted flexures)."""
    tags = [t for _, t, _ in drawn]
    _, out_map = gmsh.model.occ.fragment([(2, tags[0])], [(2, t) for t in tags[1:]])
    gmsh.model.occ.synchronize()
    owner, role_of = {}, {}
    for (part, _, role), pieces in zip(drawn, out_map):
        for dim, tag in pieces:
            owner.setdefault(tag, set()).add(part)
            if role is not None:
                role_of[tag] = role
    return owner, role_of


def _subdomains(owner: dict, layout: FlexureLayout) -> dict:
    """{subdomain: [surface tags]}: each link, and "flexure_<joint>" for each flexure. Raises
    ValueError where a flexure overlaps another part or parts of different links overlap."""
    groups = {}
    for tag, parts in owner.items():
        kinds = {p.kind for p in parts}
        if "flexure" in kinds and len(parts) > 1:
            names = sorted(p.name for p in parts)
            raise ValueError(f"flexure overlaps another part: {names}; the layout's flexures "
                             "must only touch the links at their ends")
        links = {("flexure_" + p.name.split("_", 1)[1]) if p.kind == "flexure" else p.link
                 for p in parts}
        if len(links) > 1:
            raise ValueError(f"parts of different links overlap: {sorted(p.name for p in parts)}")
        groups.setdefault(links.pop(), []).append(tag)
    return groups


def _add_subdomain_groups(gmsh, layout: FlexureLayout, groups: dict, owner: dict) -> None:
    """Physical surface groups: each subdomain, "flexures", "links", "anchors" (if any), "body"."""
    flexure_tags = []
    for name, surfaces in sorted(groups.items()):
        # a link named like a boundary edge (e.g. "end_effector") gets its subdomain "<name>_link"
        gmsh.model.addPhysicalGroup(2, surfaces, name=name + "_link" if name in layout.edges else name)
        if name.startswith("flexure_"):
            flexure_tags += surfaces
    link_tags = [t for n, s in groups.items() if not n.startswith("flexure_") and n != layout.ground
                 for t in s]
    ground_tags = groups.get(layout.ground, [])
    gmsh.model.addPhysicalGroup(2, flexure_tags, name="flexures")
    gmsh.model.addPhysicalGroup(2, link_tags, name="links")
    if ground_tags:
        gmsh.model.addPhysicalGroup(2, ground_tags, name="anchors")
    gmsh.model.addPhysicalGroup(2, sorted(owner), name="body")


def _add_boundary_groups(gmsh, layout: FlexureLayout, ends: dict) -> None:
    """Physical curve groups "fixed" and the layout's named edges: the curves (``ends``:
    {curve: (end, end)}, m) lying on their segments. Raises ValueError for an empty group."""
    scale = 1e-6 * max(np.ptp(np.array(layout.bounding_box()).reshape(2, 2), axis=0))
    for name, segments in [("fixed", layout.fixed)] + [(k, [v]) for k, v in layout.edges.items()]:
        found = [t for t, (a, b) in ends.items()
                 if any(_on_segment(a, s, scale) and _on_segment(b, s, scale) for s in segments)]
        if not found:
            raise ValueError(f"no boundary found for group {name!r}")
        gmsh.model.addPhysicalGroup(1, found, name=name)


def _structure_flexures(gmsh, layout, groups, role_of, ends, r, n_across, aspect) -> tuple:
    """Make every flexure (with fillets: its middle) a structured grid. Returns (smallest
    element size across a flexure (m), the flexures' end curves, the root-zone surfaces, the
    root-zone element size (m) or None without fillets)."""
    h_min, end_curves, root_tags, root_size = math.inf, [], [], None
    for part in (p for p in layout.parts if p.kind == "flexure"):
        tag = groups[f"flexure_{part.name.split('_', 1)[1]}"]
        h_across = part.width / n_across
        straight = part.length
        if r > 0:
            roots = [t for t in tag if role_of.get(t) == "root"]
            tag = [t for t in tag if role_of.get(t) == "middle"]
            if len(roots) != 2:
                raise ValueError(f"{part.name}'s root zones were split by the boolean union; "
                                 "check the layout")
            root_tags += roots
            straight = part.length - 2 * root_zone_depth(r, part.width)
            root_size = min(root_size or math.inf, h_across, r / 3)
        if len(tag) != 1:
            raise ValueError(f"{part.name} was split by the boolean union; check the layout")
        h_min = min(h_min, h_across)
        n_along = max(2, int(math.ceil(straight / (aspect * h_across))))
        end_curves += _set_transfinite(gmsh, part, tag[0], ends, straight, n_along, n_across)
    return h_min, end_curves, root_tags, root_size


def _set_transfinite(gmsh, part, surface, ends, straight, n_along, n_across) -> list:
    """Structured grid on one flexure's (middle) surface, its straight length ``straight`` (m):
    n_along x n_across elements. Returns its two end curves (across the flexure)."""
    boundary = [abs(t) for _, t in gmsh.model.getBoundary([(2, surface)], oriented=False)]
    if len(boundary) != 4:
        raise ValueError(f"{part.name} has {len(boundary)} edges after the union, not 4")
    end_curves = []
    for c in boundary:
        a, b = ends[c]
        along = abs(math.dist(a, b) - straight) < 1e-6 * part.length
        gmsh.model.mesh.setTransfiniteCurve(c, (n_along if along else n_across) + 1)
        if not along:
            end_curves.append(c)
    gmsh.model.mesh.setTransfiniteSurface(surface, "Alternate")
    return end_curves


def _set_size_fields(gmsh, W, coarse, h_min, end_curves, root_tags, root_size) -> None:
    """Background mesh size (m): 2 h_min at the flexures' ends growing to ``coarse`` over
    2 W (W the link width, m); with fillets, ``root_size`` in and graded from the root zones."""
    field_ = gmsh.model.mesh.field
    thr = threshold_field(gmsh, end_curves, 2, 2.0 * h_min, coarse, 0.0, 2.0 * W, sampling=20)
    if root_tags:
        # root zones: a constant size, also on their curves (the arcs, the link's face)
        zone_curves = sorted({abs(c) for t in root_tags
                              for _, c in gmsh.model.getBoundary([(2, t)], oriented=False)})
        const = field_.add("Constant")
        field_.setNumber(const, "VIn", root_size)
        field_.setNumber(const, "VOut", coarse)
        field_.setNumbers(const, "SurfacesList", root_tags)
        field_.setNumbers(const, "CurvesList", zone_curves)
        # grade the links from the root size: distance to the zones' curves
        thr_r = threshold_field(gmsh, zone_curves, 2, root_size, coarse, 0.0, 2.0 * W,
                                sampling=20)
        both = field_.add("Min")
        field_.setNumbers(both, "FieldsList", [thr, const, thr_r])
        thr = both
    field_.setAsBackgroundMesh(thr)
    for key in ("Mesh.MeshSizeExtendFromBoundary", "Mesh.MeshSizeFromPoints",
                "Mesh.MeshSizeFromCurvature"):
        gmsh.option.setNumber(key, 0)


def _curve_ends(gmsh, tag) -> tuple:
    pts = gmsh.model.getBoundary([(1, tag)], oriented=False)
    xy = [tuple(gmsh.model.getValue(0, abs(p), [])[:2]) for _, p in pts]
    return (xy[0], xy[-1])


def _on_segment(point, segment, tol) -> bool:
    a, b = np.asarray(segment[0]), np.asarray(segment[1])
    p = np.asarray(point)
    ab = b - a
    t = np.dot(p - a, ab) / np.dot(ab, ab)
    return -1e-9 <= t <= 1 + 1e-9 and np.linalg.norm(a + t * ab - p) <= tol


def mesh_layout(layout: FlexureLayout, n_across: int = 3, aspect: float = 4.0,
                coarse: float | None = None, name: str = "flexure_linkage",
                root_fillet_radius: float = 0.0) -> tuple:
    """Mesh ``layout`` (triangles; use order=2 in the Model for quadratic elements) with
    ``n_across`` (>= 3) elements across every flexure and, if ``root_fillet_radius`` r > 0
    (m), quarter-circle fillets at the flexure roots (element size <= r / 3 there; the
    fillets belong to the flexure's subdomain). Returns (FEMesh, {"flexure_size",
    "coarse_size"[, "root_size"]} in m). Coordinates in m."""
    if not (isinstance(n_across, (int, np.integer)) and n_across >= 3):
        raise ValueError(f"n_across = {n_across!r} must be an integer >= 3 (elements across a "
                         "flexure)")
    if not (math.isfinite(aspect) and 0.5 <= aspect <= 20):
        raise ValueError(f"aspect = {aspect!r} must be in [0.5, 20] (element length / width in "
                         "a flexure)")
    with gmsh_session(name) as gmsh:
        sizes = draw_layout(gmsh, layout, n_across, aspect, coarse, root_fillet_radius)
        gmsh.option.setNumber("Mesh.Algorithm", 6)
        gmsh.model.mesh.generate(2)
        return mesh_from_gmsh(gmsh), sizes
