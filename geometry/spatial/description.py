"""A spatial flexure mechanism described once: rigid 3-D bodies joined by wire and leaf
flexures (SI units, m).

:class:`SolidBody` is a union of axis-aligned boxes, cylinders and prisms (a polygon extruded
along x, y or z); :class:`Wire` a rod of circular section (``diameter``) on its axis from
``start`` to ``end``; :class:`Plate` a leaf spring (``thickness``, ``width`` along
``width_along``, perpendicular to its axis). A flexure's ends lie inside or on the bodies it
joins (``between``); its free span is the part of its axis outside both.
:meth:`SpatialMechanism.check` refuses what cannot be built, naming the body or flexure.
"""
from dataclasses import dataclass, field
import math

import numpy as np

from shapely.geometry import Point, Polygon

from ..mechanism.description import Segment

TOL = 1e-9  # relative to the mechanism's size: points closer than this coincide
AXES = {"x": 0, "y": 1, "z": 2}


@dataclass(frozen=True)
class Cylinder:
    """A solid cylinder of ``diameter`` (m) on its axis from ``start`` to ``end`` (m)."""

    start: tuple
    end: tuple
    diameter: float

    def contains(self, p, tol: float) -> bool:
        a, b = np.asarray(self.start, float), np.asarray(self.end, float)
        d = b - a
        s = float((np.asarray(p) - a) @ d / (d @ d))
        radial = np.linalg.norm(np.asarray(p) - a - s * d)
        length = math.sqrt(d @ d)
        return -tol / length <= s <= 1 + tol / length and radial <= self.diameter / 2 + tol


@dataclass(frozen=True)
class Prism:
    """A polygon (vertices (m) in the plane across ``axis``: (y, z) for x, (z, x) for y,
    (x, y) for z) extruded along ``axis`` over ``span`` = (from, to) (m)."""

    polygon: tuple
    axis: str
    span: tuple

    def plane(self, p) -> tuple:
        k = AXES[self.axis]
        return (p[(k + 1) % 3], p[(k + 2) % 3]), p[k]

    def contains(self, p, tol: float) -> bool:
        (u, v), w = self.plane(p)
        lo, hi = sorted(self.span)
        return lo - tol <= w <= hi + tol and Polygon(self.polygon).buffer(tol).covers(Point(u, v))


@dataclass(frozen=True)
class Pose:
    """A body's rotation by ``angle`` (rad, right-handed) about the direction ``axis``
    through the point ``about`` (m): its parts are written unrotated and turned so."""

    axis: tuple
    angle: float
    about: tuple

    @property
    def matrix(self) -> np.ndarray:
        """The rotation matrix (3, 3) (Rodrigues' formula)."""
        k = np.asarray(self.axis, float) / np.linalg.norm(self.axis)
        K = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
        return np.eye(3) + math.sin(self.angle) * K + (1 - math.cos(self.angle)) * K @ K

    def to_world(self, p) -> np.ndarray:
        """Points ``p`` ((3,) or (n, 3), m) of the unrotated parts where the body puts them."""
        c = np.asarray(self.about, float)
        return c + (np.asarray(p, float) - c) @ self.matrix.T

    def to_parts(self, p) -> np.ndarray:
        """The inverse of :meth:`to_world`."""
        c = np.asarray(self.about, float)
        return c + (np.asarray(p, float) - c) @ self.matrix


@dataclass(frozen=True)
class SolidBody:
    """A rigid body: the union of ``boxes`` (((x0, y0, z0), (x1, y1, z1)), m), ``cylinders``
    and ``prisms``, turned by its ``pose`` (a :class:`Pose`; None: as written); its
    ``name`` is its group (its free faces) in every model."""

    name: str
    boxes: tuple = ()
    cylinders: tuple = ()
    prisms: tuple = ()
    source: str = ""
    pose: Pose | None = None

    def contains(self, p, tol: float) -> bool:
        """Whether point ``p`` (m) lies inside or on the body (within ``tol``, m)."""
        p = np.asarray(p, float) if self.pose is None else self.pose.to_parts(p)
        for lo, hi in self.boxes:
            lo, hi = np.minimum(lo, hi), np.maximum(lo, hi)
            if np.all(p >= lo - tol) and np.all(p <= hi + tol):
                return True
        return any(c.contains(p, tol) for c in self.cylinders + self.prisms)

    def extent(self) -> tuple:
        """(lower, upper) corners (m) of the body's bounding box (of a posed body, a box
        round its parts' turned bounding box)."""
        points = [np.asarray(c) for box in self.boxes for c in box]
        for c in self.cylinders:
            r = c.diameter / 2
            points += [np.asarray(c.start) - r, np.asarray(c.start) + r,
                       np.asarray(c.end) - r, np.asarray(c.end) + r]
        for pr in self.prisms:
            k = AXES[pr.axis]
            for u, v in pr.polygon:
                for w in pr.span:
                    q = np.zeros(3)
                    q[(k + 1) % 3], q[(k + 2) % 3], q[k] = u, v, w
                    points.append(q)
        stack = np.array(points, float)
        lo, hi = stack.min(axis=0), stack.max(axis=0)
        if self.pose is None:
            return lo, hi
        corners = self.pose.to_world([[(lo, hi)[i >> k & 1][k] for k in range(3)]
                                      for i in range(8)])
        return corners.min(axis=0), corners.max(axis=0)


@dataclass(frozen=True)
class SpatialFlexure:
    """What every spatial flexure has: the bodies ``between`` it joins, its axis from
    ``start`` to ``end`` (m), and by keyword its root ``fillet`` radius (m, 0: square
    roots), ``name``, ``crosses`` (names of flexures it may pass through: declared
    crossings) and ``source`` (file and line, for messages)."""

    between: tuple
    start: tuple
    end: tuple
    fillet: float = field(default=0.0, kw_only=True)
    name: str = field(default="", kw_only=True)
    crosses: tuple = field(default=(), kw_only=True)
    source: str = field(default="", kw_only=True)


@dataclass(frozen=True)
class Wire(SpatialFlexure):
    """A wire flexure: a rod of ``diameter`` (m) on its axis."""

    diameter: float
    kind = "wire"

    @property
    def radius(self) -> float:
        """Half the widest section across the axis (m): how near another flexure may come."""
        return self.diameter / 2


@dataclass(frozen=True)
class Plate(SpatialFlexure):
    """A leaf spring in 3-D on its centre line: ``thickness`` (m) along its normal,
    ``width`` (m) along the unit direction ``width_along`` (perpendicular to the axis)."""

    thickness: float
    width: float
    width_along: tuple
    kind = "leaf"

    @property
    def radius(self) -> float:
        return math.hypot(self.width, self.thickness) / 2

    @property
    def normal(self) -> np.ndarray:
        """The unit normal of the leaf's plane (thickness direction)."""
        d = np.subtract(self.end, self.start)
        n = np.cross(d, self.width_along)
        return n / np.linalg.norm(n)


def flexure_label(flexure, index: int) -> str:
    name = f" {flexure.name!r}" if flexure.name else ""
    return (f"flexure {index + 1}{name} ({flexure.kind} between {flexure.between[0]!r} and "
            f"{flexure.between[1]!r})")


def _segment_distance(p0, p1, q0, q1) -> float:
    """The shortest distance (m) between segments p0-p1 and q0-q1."""
    u, v, w = p1 - p0, q1 - q0, p0 - q0
    a, b, c, d, e = u @ u, u @ v, v @ v, u @ w, v @ w
    den = a * c - b * b
    candidates = []
    if den > 1e-30 * a * c:
        s, t = (b * e - c * d) / den, (a * e - b * d) / den
        if 0 <= s <= 1 and 0 <= t <= 1:
            candidates.append(np.linalg.norm(w + s * u - t * v))
    for s in (0.0, 1.0):
        t = np.clip((e + s * b) / c, 0, 1)
        candidates.append(np.linalg.norm(w + s * u - t * v))
    for t in (0.0, 1.0):
        s = np.clip((t * b - d) / a, 0, 1)
        candidates.append(np.linalg.norm(w + s * u - t * v))
    return float(min(candidates))


@dataclass(frozen=True)
class FreeSpan(Segment):
    """Where a flexure is free: its axis from ``a`` (leaving the first body) to ``b``
    (entering the second), m."""

    @property
    def centre(self) -> np.ndarray:
        return (self.a + self.b) / 2


@dataclass(frozen=True)
class SpatialMechanism:
    """Rigid ``bodies`` (SolidBody) joined by ``flexures`` (Wire, Plate); ``source``: the
    model file, for messages; ``moments``: the file's [[loads]] moments on bodies ((body,
    (M_x, M_y, M_z) N m, source), ...: the beam model's; the continuum refuses them)."""

    bodies: tuple
    flexures: tuple
    source: str = ""
    moments: tuple = ()

    @property
    def size(self) -> float:
        """The diagonal of the mechanism's bounding box (m)."""
        lows, highs = zip(*(b.extent() for b in self.bodies))
        return float(np.linalg.norm(np.max(highs, axis=0) - np.min(lows, axis=0)))

    @property
    def tol(self) -> float:
        return TOL * self.size

    def body(self, name: str) -> SolidBody:
        for b in self.bodies:
            if b.name == name:
                return b
        raise KeyError(name)

    def span(self, index: int) -> FreeSpan:
        """The free span of flexure ``index``: its axis between the last point inside its
        first body and the first point inside its second (bisection, to 1e-12 of its
        length)."""
        f = self.flexures[index]
        a, b = np.asarray(f.start, float), np.asarray(f.end, float)
        first, second = self.body(f.between[0]), self.body(f.between[1])

        def edge(inside, lo, hi):  # inside(lo), not inside(hi)
            for _ in range(60):
                mid = (lo + hi) / 2
                lo, hi = (mid, hi) if inside(mid) else (lo, mid)
            return lo

        tol = self.tol
        s0 = edge(lambda s: first.contains(a + s * (b - a), tol), 0.0, 1.0)
        s1 = 1.0 - edge(lambda s: second.contains(b + s * (a - b), tol), 0.0, 1.0)
        return FreeSpan(a + s0 * (b - a), a + s1 * (b - a))

    def check(self, supported=None) -> None:
        """ValueError naming the file, the line and the body or flexure for what cannot be
        built: a name used twice, a flexure joining an unknown body or one body to itself,
        an end outside its body, a leaf's width_along not perpendicular to it, flexures
        that meet (unless either declares ``crosses``), a body joined to nothing, and (when
        ``supported`` is given: the held group names) a mechanism with no held body; and a
        root fillet, which neither model draws yet."""
        names = [b.name for b in self.bodies]
        for b in self.bodies:
            if names.count(b.name) > 1:
                raise ValueError(f"{b.source}: body {b.name!r} is named twice")
        for i, f in enumerate(self.flexures):
            label = flexure_label(f, i)
            for name in f.between:
                if name not in names:
                    raise ValueError(f"{f.source}: {label}: {name!r} is no body; bodies: "
                                     f"{', '.join(names)}")
            if f.between[0] == f.between[1]:
                raise ValueError(f"{f.source}: {label} joins body {f.between[0]!r} to itself")
            if f.fillet:
                raise ValueError(f"{f.source}: {label}: fillet = {f.fillet!r} m: root fillets "
                                 "of spatial flexures are not modelled yet (both models "
                                 "would draw square roots); leave fillet out or write 0")
            axis = np.subtract(f.end, f.start)
            length = float(np.linalg.norm(axis))
            if not length > self.tol:
                raise ValueError(f"{f.source}: {label}: from and to coincide")
            for key, point, body in (("from", f.start, f.between[0]),
                                     ("to", f.end, f.between[1])):
                if not self.body(body).contains(point, self.tol):
                    raise ValueError(f"{f.source}: {label}: its end {key} = "
                                     f"{list(map(float, point))} is outside body {body!r} "
                                     "(each end lies inside or on the body it joins)")
            if isinstance(f, Plate):
                w = np.asarray(f.width_along, float)
                cosine = abs(float(w @ axis)) / (np.linalg.norm(w) * length)
                if cosine > 1e-6:
                    raise ValueError(f"{f.source}: {label}: width_along = "
                                     f"{list(map(float, w))} is not perpendicular to the leaf "
                                     f"(from -> to): it makes {math.degrees(math.acos(cosine)):.4g}"
                                     " deg with it")
            span = self.span(i)
            if not span.length > self.tol:
                raise ValueError(f"{f.source}: {label}: no free span: both ends' bodies "
                                 "meet along its axis")
        self._check_crossings()
        joined = {n for f in self.flexures for n in f.between}
        for b in self.bodies:
            if b.name not in joined:
                raise ValueError(f"{b.source}: body {b.name!r} is joined to nothing: no "
                                 "flexure names it in between")
        if supported is not None and not set(supported) & set(names):
            raise ValueError(f"{self.source}: the mechanism has no support: hold a body "
                             "with [[supports]] group = 'NAME'")

    def _check_crossings(self) -> None:
        spans = [self.span(i) for i in range(len(self.flexures))]
        for i, f in enumerate(self.flexures):
            for j in range(i + 1, len(self.flexures)):
                g = self.flexures[j]
                if (g.name and g.name in f.crosses) or (f.name and f.name in g.crosses):
                    continue
                gap = _segment_distance(spans[i].a, spans[i].b, spans[j].a, spans[j].b)
                if gap < f.radius + g.radius - self.tol:
                    raise ValueError(
                        f"{g.source}: {flexure_label(g, j)} intersects "
                        f"{flexure_label(f, i)}: their axes pass {gap:.4g} m apart, nearer "
                        f"than their half-sections ({f.radius + g.radius:.4g} m); move one, "
                        "or declare crosses = [\"NAME\"] to fuse them where they cross")
