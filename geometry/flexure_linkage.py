"""A planar linkage with its revolute joints replaced by beam flexures, as a 2-D gmsh part.

Each joint J joins a *host* link and an *other* link (or the ground). The flexure is a thin
rectangle of length L and width w centred on J and lying along the host's centre-line at J
(direction d, pointing from the host's neighbouring point to J): it spans J - L/2 d to
J + L/2 d, so its middle -- the point about which a beam bent by end moments alone rotates
(M = E I theta / L, no shear) -- is the rigid-body pivot. The host's bar is shortened to end at
J - L/2 d; the other link gets a *hub* (W wide, 2 W long, W the link width) beyond J + L/2 d
and its bar is redirected to the hub's centre, W from the flexure. For a joint to the ground
the hub is the *anchor*, whose far face is the "fixed" boundary. Rigid links are bars of
width W along their centre-lines.

Everything here is plain geometry in m (:class:`FlexureLayout`, a list of rectangles) until
:func:`mesh_layout`, which draws it in gmsh (OpenCASCADE), meshes each flexure with a
structured grid of ``n_across`` x (L / h_along) quadratic-ready triangles and grades the links
from the flexure size to a coarse size, and returns a :class:`~flexfem.fem.mesh.FEMesh` with
subdomains (each link, "flexure_<joint>", "links", "flexures", "body") and boundaries
("fixed" and the caller's named edges). ``root_fillet_radius`` (default 0: sharp corners) adds
quarter-circle root fillets (:mod:`flexfem.geometry.flexure_roots`).
"""
import math
from dataclasses import dataclass, field

import numpy as np

from ..fem.gmsh_session import gmsh_session
from ..fem.mesh import mesh_from_gmsh
from .flexure_roots import (
    check_root_fillet_radius,
    draw_filleted_flexure,
    root_zone_depth,
)
from .linkage_clearance import segment_distance


@dataclass(frozen=True)
class Part:
    """A rectangle of width ``width`` (m) around the centre-line ``p0``-``p1`` (m).

    name : e.g. "crank_L:bar0", "flexure_A_L", "anchor_O_L"; link : the link it belongs to
    (for a flexure: its host); kind : "bar", "hub", "anchor" or "flexure"."""

    name: str
    link: str
    kind: str
    p0: tuple
    p1: tuple
    width: float

    @property
    def length(self) -> float:
        return float(math.dist(self.p0, self.p1))

    def corners(self, transform=None) -> np.ndarray:
        """(4, 2) corners (m), counter-clockwise; ``transform`` a 3x3 homogeneous map."""
        p0, p1 = np.asarray(self.p0, float), np.asarray(self.p1, float)
        if transform is not None:
            p0, p1 = (transform @ np.r_[p0, 1.0])[:2], (transform @ np.r_[p1, 1.0])[:2]
        d = (p1 - p0) / max(np.linalg.norm(p1 - p0), 1e-300)
        n = np.array([-d[1], d[0]]) * self.width / 2
        return np.array([p0 - n, p1 - n, p1 + n, p0 + n])


@dataclass(frozen=True)
class FlexureJoint:
    """A joint replaced by a flexure: ``host`` link carries it, ``other`` is the other link
    (or the ground); centre ``position`` (m), unit ``direction`` along the host, ``length``
    and ``width`` (m)."""

    name: str
    host: str
    other: str
    position: tuple
    direction: tuple
    length: float
    width: float

    def ends(self) -> tuple:
        """(host end, other end) of the flexure, m."""
        c, d = np.asarray(self.position), np.asarray(self.direction)
        return tuple(c - self.length / 2 * d), tuple(c + self.length / 2 * d)


@dataclass(frozen=True, eq=False)
class FlexureLayout:
    """The flexure part as rectangles (m): ``parts``, ``joints`` (FlexureJoint), the ``fixed``
    edges (segments, m) and named ``edges`` {name: segment}; ``link_width`` W (m)."""

    parts: tuple
    joints: tuple
    fixed: tuple
    edges: dict = field(default_factory=dict)
    link_width: float = 0.0
    ground: str = "ground"

    @property
    def links(self) -> list:
        return sorted({p.link for p in self.parts if p.kind != "flexure" and p.link != self.ground})

    def flexure(self, joint: str) -> Part:
        return next(p for p in self.parts if p.name == f"flexure_{joint}")

    def bounding_box(self) -> tuple:
        """(x_min, y_min, x_max, y_max), m."""
        xy = np.vstack([p.corners() for p in self.parts])
        return (*xy.min(axis=0), *xy.max(axis=0))


def _unit(v) -> np.ndarray:
    v = np.asarray(v, float)
    n = np.linalg.norm(v)
    if not n > 0:
        raise ValueError("a link centre-line segment has zero length")
    return v / n


def flexure_layout(polylines: dict, joints: list, hosts: dict, sizes: dict, link_width: float,
                   edges: dict | None = None, ground: str = "ground") -> FlexureLayout:
    """Replace each joint of a posed linkage by a flexure.

    polylines : {link: [[(x, y), ...], ...]} centre-lines of the moving links (m), passing
        through their joints' positions; joints : [{"name", "position", "links"}] (as
        :func:`flexfem.geometry.eightbar.rigid.eightbar_joints` gives them); hosts : {joint:
        host link}; sizes : {joint: (length, width)} of its flexure (m); link_width : W (m);
        edges : {name: callable(layout parts) -> segment} or {name: segment}, extra boundary
        groups. Raises ValueError if a flexure's host segment is too short to carry it.
    """
    W = float(link_width)
    position = {j["name"]: np.asarray(j["position"], float) for j in joints}
    for j in joints:
        if hosts[j["name"]] not in j["links"]:
            raise ValueError(f"host of joint {j['name']!r} = {hosts[j['name']]!r} is not one of "
                             f"its links {j['links']}")
    # the host's neighbouring point at each joint: the other end of its segment ending there
    neighbour = {}
    for j in joints:
        host = hosts[j["name"]]
        for line in polylines[host]:
            pts = [np.asarray(p, float) for p in line]
            for k, p in enumerate(pts):
                if np.allclose(p, position[j["name"]], atol=1e-12 * (1 + W)) and j["name"] not in neighbour:
                    neighbour[j["name"]] = pts[k - 1] if k > 0 else pts[k + 1]
        if j["name"] not in neighbour:
            raise ValueError(f"joint {j['name']!r} is not on a centre-line of its host {host!r}")
    # effective attachment point of each link at each joint (m); hubs of the other links are
    # placed after the host directions, which may depend on other hubs: iterate to a fixed point
    attach = {}
    for _ in range(4):
        flex = {}
        for j in joints:
            name, host = j["name"], hosts[j["name"]]
            other = next(link for link in j["links"] if link != host)
            L, w = sizes[name]
            nb = neighbour[name]
            for (lk, jn), pt in attach.items():
                if lk == host and np.allclose(position[jn], nb):
                    nb = pt
            d = _unit(position[name] - nb)
            flex[name] = FlexureJoint(name, host, other, tuple(position[name]), tuple(d), L, w)
        new = {}
        for fj in flex.values():
            c, d = np.asarray(fj.position), np.asarray(fj.direction)
            new[(fj.host, fj.name)] = c - fj.length / 2 * d
            new[(fj.other, fj.name)] = c + (fj.length / 2 + W) * d
        if attach and all(np.allclose(new[k], attach[k], atol=1e-15) for k in new):
            break
        attach = new
    parts, fixed = [], []
    for fj in flex.values():
        a, b = fj.ends()
        parts.append(Part(f"flexure_{fj.name}", fj.host, "flexure", a, b, fj.width))
        d = np.asarray(fj.direction)
        hub0 = np.asarray(b)
        hub1 = hub0 + 2 * W * d
        kind = "anchor" if fj.other == ground else "hub"
        parts.append(Part(f"{kind}_{fj.name}", fj.other, kind, tuple(hub0), tuple(hub1), W))
        if fj.other == ground:
            n = np.array([-d[1], d[0]]) * W / 2
            fixed.append((tuple(hub1 - n), tuple(hub1 + n)))
    # bars: each centre-line segment with joint points replaced by attachment points; a bar
    # ending at a flexure is flush with it, one ending at a hub ends at the hub's centre (W
    # from the flexure), one ending elsewhere runs W/2 past its end point (square corners)
    for link, lines in polylines.items():
        count = 0
        for line in lines:
            pts = [np.asarray(p, float) for p in line]
            for p, q in zip(pts[:-1], pts[1:]):
                ends, flush = [], []
                for pt in (p, q):
                    jn = next((n for n, x in position.items() if np.allclose(x, pt)
                               and (link, n) in attach), None)
                    if jn is None:
                        ends.append(pt)
                        flush.append(False)
                    else:
                        ends.append(attach[(link, jn)])
                        flush.append(True)
                e0, e1 = ends
                seg_len = float(np.linalg.norm(e1 - e0))
                if any(flush) and seg_len < W:
                    jn = [n for n, x in position.items() if (np.allclose(x, p) or np.allclose(x, q))
                          and (link, n) in attach]
                    raise ValueError(
                        f"flexure(s) {['flexure_' + n for n in jn]} too long for link {link!r}: the "
                        f"bar left between them is {seg_len:.4g} m, must be >= link width {W:.4g} "
                        "m (shorten the flexures)")
                d = _unit(e1 - e0)
                e0 = e0 if flush[0] else e0 - W / 2 * d
                e1 = e1 if flush[1] else e1 + W / 2 * d
                parts.append(Part(f"{link}:bar{count}", link, "bar", tuple(e0), tuple(e1), W))
                count += 1
    named = {}
    for name, edge in (edges or {}).items():
        named[name] = edge(parts) if callable(edge) else edge
    return FlexureLayout(tuple(parts), tuple(flex.values()), tuple(fixed), named, W, ground)


# -- convex polygon distances (rectangles), for clearance checks ------------------------------

def _inside(point, poly) -> bool:
    """Point inside (or on) a counter-clockwise convex polygon."""
    for a, b in zip(poly, np.roll(poly, -1, axis=0)):
        if (b[0] - a[0]) * (point[1] - a[1]) - (b[1] - a[1]) * (point[0] - a[0]) < 0:
            return False
    return True


def polygon_distance(P: np.ndarray, Q: np.ndarray) -> tuple:
    """(distance (m), midpoint of the closest approach (x, y) m) of two convex polygons
    ((n, 2) counter-clockwise); distance 0 where they touch or overlap."""
    best, where = math.inf, None
    for a0, a1 in zip(P, np.roll(P, -1, axis=0)):
        for b0, b1 in zip(Q, np.roll(Q, -1, axis=0)):
            d = segment_distance(a0, a1, b0, b1)
            if d < best:
                best, where = d, _closest_midpoint(a0, a1, b0, b1)
    if _inside(P[0], Q) or _inside(Q[0], P):
        return 0.0, tuple(P[0] if _inside(P[0], Q) else Q[0])
    return best, where


def _closest_midpoint(a0, a1, b0, b1) -> tuple:
    """Midpoint (m) between the closest points of two segments (sampled, for reporting)."""
    s = np.linspace(0.0, 1.0, 41)
    A = a0 + s[:, None] * (a1 - a0)
    B = b0 + s[:, None] * (b1 - b0)
    d = np.linalg.norm(A[:, None] - B[None], axis=2)
    i, k = np.unravel_index(np.argmin(d), d.shape)
    return tuple((A[i] + B[k]) / 2)


# -- gmsh -------------------------------------------------------------------------------------

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
    occ = gmsh.model.occ
    drawn = []  # (part, input surface tag, role): role "root" / "middle" for filleted flexures
    for part in layout.parts:
        if r > 0 and part.kind == "flexure":
            drawn += [(part, tag, role) for tag, role in draw_filleted_flexure(occ, part, r)]
            continue
        c = part.corners()
        pts = [occ.addPoint(x, y, 0.0) for x, y in c]
        lines = [occ.addLine(pts[i], pts[(i + 1) % 4]) for i in range(4)]
        drawn.append((part, occ.addPlaneSurface([occ.addCurveLoop(lines)]), None))
    tags = [t for _, t, _ in drawn]
    out, out_map = occ.fragment([(2, tags[0])], [(2, t) for t in tags[1:]])
    occ.synchronize()
    owner, role_of = {}, {}
    for (part, _, role), pieces in zip(drawn, out_map):
        for dim, tag in pieces:
            owner.setdefault(tag, set()).add(part)
            if role is not None:
                role_of[tag] = role
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

    W = layout.link_width
    curves = gmsh.model.getEntities(1)
    ends = {t: _curve_ends(gmsh, t) for _, t in curves}
    scale = 1e-6 * max(np.ptp(np.array(layout.bounding_box()).reshape(2, 2), axis=0))
    for name, segments in [("fixed", layout.fixed)] + [(k, [v]) for k, v in layout.edges.items()]:
        found = [t for t, (a, b) in ends.items()
                 if any(_on_segment(a, s, scale) and _on_segment(b, s, scale) for s in segments)]
        if not found:
            raise ValueError(f"no boundary found for group {name!r}")
        gmsh.model.addPhysicalGroup(1, found, name=name)

    # structured flexures (with fillets: their middles; the root zones are sized below)
    h_min = math.inf
    end_curves = []
    root_tags, root_size = [], None
    for part in layout.parts:
        if part.kind != "flexure":
            continue
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
        n_along = max(2, int(math.ceil(straight / (aspect * h_across))))
        h_min = min(h_min, h_across)
        boundary = [abs(t) for _, t in gmsh.model.getBoundary([(2, tag[0])], oriented=False)]
        if len(boundary) != 4:
            raise ValueError(f"{part.name} has {len(boundary)} edges after the union, not 4")
        for c in boundary:
            a, b = ends[c]
            along = abs(math.dist(a, b) - straight) < 1e-6 * part.length
            gmsh.model.mesh.setTransfiniteCurve(c, (n_along if along else n_across) + 1)
            if not along:
                end_curves.append(c)
        gmsh.model.mesh.setTransfiniteSurface(tag[0], "Alternate")
    coarse = (W / 2 if coarse is None else coarse)
    field_ = gmsh.model.mesh.field
    dist = field_.add("Distance")
    field_.setNumbers(dist, "CurvesList", end_curves)
    field_.setNumber(dist, "Sampling", 20)
    thr = field_.add("Threshold")
    field_.setNumber(thr, "InField", dist)
    field_.setNumber(thr, "SizeMin", 2.0 * h_min)
    field_.setNumber(thr, "SizeMax", coarse)
    field_.setNumber(thr, "DistMin", 0.0)
    field_.setNumber(thr, "DistMax", 2.0 * W)
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
        dist_r = field_.add("Distance")
        field_.setNumbers(dist_r, "CurvesList", zone_curves)
        field_.setNumber(dist_r, "Sampling", 20)
        thr_r = field_.add("Threshold")
        field_.setNumber(thr_r, "InField", dist_r)
        field_.setNumber(thr_r, "SizeMin", root_size)
        field_.setNumber(thr_r, "SizeMax", coarse)
        field_.setNumber(thr_r, "DistMin", 0.0)
        field_.setNumber(thr_r, "DistMax", 2.0 * W)
        both = field_.add("Min")
        field_.setNumbers(both, "FieldsList", [thr, const, thr_r])
        thr = both
    field_.setAsBackgroundMesh(thr)
    for key in ("Mesh.MeshSizeExtendFromBoundary", "Mesh.MeshSizeFromPoints",
                "Mesh.MeshSizeFromCurvature"):
        gmsh.option.setNumber(key, 0)
    sizes = {"flexure_size": h_min, "coarse_size": coarse}
    if root_size is not None:
        sizes["root_size"] = root_size
    return sizes


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
