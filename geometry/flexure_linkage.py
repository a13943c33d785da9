"""A planar linkage with its revolute joints replaced by beam flexures, laid out as rectangles.

Each joint J joins a *host* link and an *other* link (or the ground). The flexure is a thin
rectangle of length L and width w centred on J and lying along the host's centre-line at J
(direction d, pointing from the host's neighbouring point to J): it spans J - L/2 d to
J + L/2 d, so its middle -- the point about which a beam bent by end moments alone rotates
(M = E I theta / L, no shear) -- is the rigid-body pivot. The host's bar is shortened to end at
J - L/2 d; the other link gets a *hub* (W wide, 2 W long, W the link width) beyond J + L/2 d
and its bar is redirected to the hub's centre, W from the flexure. For a joint to the ground
the hub is the *anchor*, whose far face is the "fixed" boundary. Rigid links are bars of
width W along their centre-lines.

Everything here is plain geometry in m (:class:`FlexureLayout`, a list of rectangles);
:func:`flexfem.geometry.flexure_drawing.mesh_layout` draws and meshes it in gmsh.
"""
import math
from dataclasses import dataclass, field

import numpy as np

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


def _close(a, b, atol: float = 1e-8) -> bool:
    """``np.allclose(a, b, atol=atol)`` (rtol 1e-5) of two finite points, without its ~30 us
    of overhead (the layout makes thousands of these comparisons)."""
    return all(abs(x - y) <= atol + 1e-5 * abs(y) for x, y in zip(map(float, a), map(float, b)))


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
    neighbour = _host_neighbours(polylines, joints, hosts, position, W)
    flex, attach = _place_flexures(joints, hosts, sizes, position, neighbour, W)
    parts, fixed = _flexures_and_hubs(flex, W, ground)
    for link, lines in polylines.items():
        parts += _bars(link, lines, position, attach, W)
    named = {}
    for name, edge in (edges or {}).items():
        named[name] = edge(parts) if callable(edge) else edge
    return FlexureLayout(tuple(parts), tuple(flex.values()), tuple(fixed), named, W, ground)


def _host_neighbours(polylines, joints, hosts, position, W) -> dict:
    """{joint: the host's neighbouring point (m)}: the other end of the host's first centre-line
    segment ending at the joint. Raises ValueError for a joint off its host's centre-line."""
    neighbour = {}
    for j in joints:
        host = hosts[j["name"]]
        for line in polylines[host]:
            pts = [np.asarray(p, float) for p in line]
            for k, p in enumerate(pts):
                if _close(p, position[j["name"]], atol=1e-12 * (1 + W)) and j["name"] not in neighbour:
                    neighbour[j["name"]] = pts[k - 1] if k > 0 else pts[k + 1]
        if j["name"] not in neighbour:
            raise ValueError(f"joint {j['name']!r} is not on a centre-line of its host {host!r}")
    return neighbour


def _place_flexures(joints, hosts, sizes, position, neighbour, W) -> tuple:
    """({joint: FlexureJoint}, {(link, joint): attachment point (m)}). A flexure lies along its
    host towards the joint from the neighbouring point, or from that point's attachment where
    it is itself a joint (a hub of another link); the hubs are placed after the host
    directions, so this iterates to a fixed point (at most 4 passes)."""
    attach = {}
    for _ in range(4):
        flex = _flexure_joints(joints, hosts, sizes, position, neighbour, attach)
        new = {}
        for fj in flex.values():
            c, d = np.asarray(fj.position), np.asarray(fj.direction)
            new[(fj.host, fj.name)] = c - fj.length / 2 * d
            new[(fj.other, fj.name)] = c + (fj.length / 2 + W) * d
        if attach and all(_close(new[k], attach[k], atol=1e-15) for k in new):
            break
        attach = new
    return flex, attach


def _flexure_joints(joints, hosts, sizes, position, neighbour, attach) -> dict:
    """One pass of :func:`_place_flexures`: {joint: FlexureJoint} given the attachments so far."""
    flex = {}
    for j in joints:
        name, host = j["name"], hosts[j["name"]]
        other = next(link for link in j["links"] if link != host)
        L, w = sizes[name]
        nb = neighbour[name]
        for (lk, jn), pt in attach.items():
            if lk == host and _close(position[jn], nb):
                nb = pt
        d = _unit(position[name] - nb)
        flex[name] = FlexureJoint(name, host, other, tuple(position[name]), tuple(d), L, w)
    return flex


def _flexures_and_hubs(flex: dict, W: float, ground: str) -> tuple:
    """([flexure, hub or anchor parts], [fixed segments (m)]): a hub W wide and 2 W long beyond
    each flexure's other end; for a joint to the ground an anchor, whose far face is fixed."""
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
    return parts, fixed


def _bars(link, lines, position, attach, W) -> list:
    """The bar parts (W wide, m) of one link: each centre-line segment with its joint points
    replaced by attachment points. A bar ending at a flexure is flush with it, one ending at a
    hub ends at the hub's centre (W from the flexure), one ending elsewhere runs W/2 past its
    end point (square corners). Raises ValueError where flexures leave a bar shorter than W."""
    parts = []
    for line in lines:
        pts = [np.asarray(p, float) for p in line]
        for p, q in zip(pts[:-1], pts[1:]):
            ends, flush = [], []
            for pt in (p, q):
                jn = next((n for n, x in position.items() if (link, n) in attach
                           and _close(x, pt)), None)
                ends.append(pt if jn is None else attach[(link, jn)])
                flush.append(jn is not None)
            e0, e1 = ends
            seg_len = float(np.linalg.norm(e1 - e0))
            if any(flush) and seg_len < W:
                jn = [n for n, x in position.items() if (_close(x, p) or _close(x, q))
                      and (link, n) in attach]
                raise ValueError(
                    f"flexure(s) {['flexure_' + n for n in jn]} too long for link {link!r}: the "
                    f"bar left between them is {seg_len:.4g} m, must be >= link width {W:.4g} "
                    "m (shorten the flexures)")
            d = _unit(e1 - e0)
            e0 = e0 if flush[0] else e0 - W / 2 * d
            e1 = e1 if flush[1] else e1 + W / 2 * d
            parts.append(Part(f"{link}:bar{len(parts)}", link, "bar", tuple(e0), tuple(e1), W))
    return parts


# -- convex polygon distances (rectangles), for clearance checks ------------------------------

def inside_convex(point, poly) -> bool:
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
    if inside_convex(P[0], Q) or inside_convex(Q[0], P):
        return 0.0, tuple(P[0] if inside_convex(P[0], Q) else Q[0])
    return best, where


def _closest_midpoint(a0, a1, b0, b1) -> tuple:
    """Midpoint (m) between the closest points of two segments (sampled, for reporting)."""
    s = np.linspace(0.0, 1.0, 41)
    A = a0 + s[:, None] * (a1 - a0)
    B = b0 + s[:, None] * (b1 - b0)
    d = np.linalg.norm(A[:, None] - B[None], axis=2)
    i, k = np.unravel_index(np.argmin(d), d.shape)
    return tuple((A[i] + B[k]) / 2)
