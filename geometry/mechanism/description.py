"""A flexure mechanism described once: rigid bodies joined by flexures (SI units, m).

:class:`Body` (body.py) is a union of axis-aligned boxes and simple polygons; :class:`Leaf`
a straight blade of constant thickness (with a fillet of radius ``fillet`` at both roots);
:class:`Notch` a circular or elliptical notch hinge (a blank cut by two circles or ellipses
that leave a neck of ``thickness``). A flexure runs along its centre line from ``start``
(inside or on the first body it joins) to ``end`` (inside or on the second); its free span
is the part between the bodies. :class:`Mechanism` holds them and :meth:`Mechanism.check` refuses what cannot be
built, naming the body or flexure. The continuum (draw.py) and the beam model (beams.py) are
both derived from this one description, with the bodies' names as their groups.
"""
from dataclasses import KW_ONLY, dataclass
import math

import numpy as np

from .body import Body
from .plane import along, box_corners, convex_overlap, cross2, inside_box, side_root, subtract

TOL = 1e-9  # relative to the mechanism's size: points closer than this coincide
REACH = 1.0 / math.tan(math.radians(10))  # an oblique root's side meets the face within
#                                          (width / 2) cot(10 deg) of the centre line


@dataclass(frozen=True)
class Flexure:
    """What every flexure has: the two bodies it joins ``between``, its centre line from
    ``start`` to ``end`` (m), its in-plane ``thickness`` (m); by keyword its ``name`` and
    ``source`` (where it was read)."""

    between: tuple
    start: tuple
    end: tuple
    thickness: float
    _: KW_ONLY
    name: str = ""
    source: str = ""


@dataclass(frozen=True)
class Leaf(Flexure):
    """A leaf spring (blade) of in-plane ``thickness`` (m) from ``start`` to ``end`` (m) on its
    centre line, joining the bodies ``between``; ``fillet``: root fillet radius (m, 0: square
    roots)."""

    fillet: float = 0.0
    kind = "leaf"

    @property
    def width(self) -> float:
        """The in-plane width of the flexure's outline at its roots (m)."""
        return self.thickness


@dataclass(frozen=True)
class Notch(Flexure):
    """A notch hinge: neck ``thickness`` (m) at the middle of its free span, on the centre
    line from ``start`` to ``end`` (m) joining ``between``; its two cut-outs are circles of
    ``radius`` (m), or ellipses of semi-axes ``radius`` along the centre line and ``across``
    (m) across it. The blank is ``thickness + 2 across`` wide and its free span 2 radius long
    (the bodies' faces must be that far apart along it; the cut-outs are tangent to them)."""

    radius: float
    across: float | None = None

    @property
    def kind(self) -> str:
        return "circular_notch" if self.across is None else "elliptical_notch"

    @property
    def semi_axes(self) -> tuple:
        """(along, across) the centre line (m)."""
        return self.radius, self.radius if self.across is None else self.across

    @property
    def width(self) -> float:
        return self.thickness + 2 * self.semi_axes[1]


@dataclass(frozen=True)
class Segment:
    """A straight piece from ``a`` to ``b`` (m): its ``length`` |b - a| (m) and unit
    direction ``d`` a -> b; in 2-D or 3-D."""

    a: np.ndarray
    b: np.ndarray

    @property
    def length(self) -> float:
        return float(np.linalg.norm(self.b - self.a))

    @property
    def d(self) -> np.ndarray:
        return (self.b - self.a) / self.length


@dataclass(frozen=True)
class Span(Segment):
    """Where a flexure is free: its root points ``a`` (leaving the first body) and ``b``
    (entering the second), m; ``d`` the unit direction a -> b, ``n`` its left normal;
    ``length`` |b - a| (m)."""

    @property
    def n(self) -> np.ndarray:
        return np.array([-self.d[1], self.d[0]])

    def corners(self, width: float) -> np.ndarray:
        """(4, 2) corners (m) of the rectangle ``width`` wide over the span."""
        h = width / 2 * self.n
        return np.array([self.a - h, self.b - h, self.b + h, self.a + h])


def flexure_label(flexure, index: int) -> str:
    name = f" {flexure.name!r}" if flexure.name else ""
    return f"flexure {index + 1}{name} ({flexure.kind} between {flexure.between[0]!r} and " \
           f"{flexure.between[1]!r})"


def _error(item, message: str) -> ValueError:
    return ValueError(f"{item.source + ': ' if item.source else ''}{message}")


@dataclass(frozen=True)
class Mechanism:
    """Rigid ``bodies`` joined by ``flexures``; ``depth``: out-of-plane thickness (m)."""

    bodies: tuple
    flexures: tuple
    depth: float
    source: str = ""

    def body(self, name: str) -> Body:
        for b in self.bodies:
            if b.name == name:
                return b
        raise KeyError(name)

    @property
    def size(self) -> float:
        """The diagonal of the bounding box of the bodies (m)."""
        corners = np.concatenate([xy for b in self.bodies for xy in b.outlines])
        return float(np.linalg.norm(corners.max(axis=0) - corners.min(axis=0)))

    @property
    def tol(self) -> float:
        return TOL * self.size

    def span(self, index: int) -> Span:
        """The free span of flexure ``index``: from where its centre line leaves its first body
        to where it enters the second."""
        f = self.flexures[index]
        first, second = (self.body(name) for name in f.between)
        step = TOL  # in fractions of the centre line; the boxes themselves clip exactly
        s_a = 0.0
        for lo, hi in first.span_inside(f.start, f.end, 0.0):
            if lo <= s_a + step:
                s_a = max(s_a, hi)
        s_b = 1.0
        for lo, hi in reversed(second.span_inside(f.start, f.end, 0.0)):
            if hi >= s_b - step:
                s_b = min(s_b, lo)
        start, end = np.asarray(f.start, float), np.asarray(f.end, float)
        return Span(start + s_a * (end - start), start + s_b * (end - start))

    def roots(self, index: int) -> list:
        """[(body name, corner (2,), inward (2,), face (2,), side)] of flexure ``index``: where
        each side of its outline (side -1 or +1 along the span's normal) meets the face of the
        body at each end, the direction into the free span and the face's direction away from
        the flexure (m, unit vectors)."""
        f, span, tol = self.flexures[index], self.span(index), self.tol
        out = []
        for name, root, inward in ((f.between[0], span.a, span.d),
                                   (f.between[1], span.b, -span.d)):
            body = self.body(name)
            for side in (-1.0, 1.0):
                offset = side * f.width / 2 * span.n
                corner = side_root(body, root + offset, inward, f.width * REACH, tol)
                if corner is None:
                    raise _error(f, f"{flexure_label(f, index)}: its side at "
                                 f"{(root + offset).tolist()} misses body {name!r}: the body's "
                                 f"face must be wider than the flexure ({f.width:.4g} m) where "
                                 "it starts")
                face = body.face_at(corner, 10 * tol)
                if face is None:
                    raise _error(f, f"{flexure_label(f, index)}: its side meets body {name!r} at "
                                 f"{corner.tolist()}, on no face of it")
                face = face if float(face @ offset) > 0 else -face
                out.append((name, corner, inward, face, side))
        return out

    def footprint(self, index: int) -> list:
        """[(body name, p0, p1)]: the segment of each body's face that flexure ``index``
        covers (between its sides' roots, and its fillets' tangent points), m."""
        f = self.flexures[index]
        r = f.fillet if isinstance(f, Leaf) else 0.0
        ends = {}
        for name, corner, inward, face, _ in self.roots(index):
            theta = math.acos(max(-1.0, min(1.0, float(face @ inward))))
            ends.setdefault(name, []).append(corner + face * r / math.tan(theta / 2))
        return [(name, p0, p1) for name, (p0, p1) in ends.items()]

    def outline_centre(self, name: str) -> np.ndarray:
        """Centroid (m) of body ``name``'s outline where no flexure meets it: the body's
        group in the continuum. A force on the group acts there and the group's mean
        displacement is that of this point when the body moves rigidly."""
        body, tol = self.body(name), self.tol
        covered = [(p0, p1) for i in range(len(self.flexures))
                   for n, p0, p1 in self.footprint(i) if n == name]
        if body.polygons:
            return self._union_outline_centre(body, covered)
        total, moment = 0.0, np.zeros(2)
        for box in body.boxes:
            corners = box_corners(box)
            for k in range(4):
                a, b = corners[k], corners[(k + 1) % 4]
                cuts = [(0.0, 1.0)]
                for other in body.boxes:
                    if other is not box:
                        cuts = subtract(cuts, inside_box(a, b, other, -tol))
                for p0, p1 in covered:
                    cuts = subtract(cuts, along(a, b, p0, p1, tol))
                for lo, hi in cuts:
                    length = (hi - lo) * float(np.linalg.norm(b - a))
                    total += length
                    moment += length * (a + (lo + hi) / 2 * (b - a))
        return moment / total

    def _union_outline_centre(self, body: Body, covered) -> np.ndarray:
        """outline_centre of a body with polygons: the outline of the union of its parts
        (its outer boundary and any holes), less the flexures' footprints."""
        total, moment = 0.0, np.zeros(2)
        for part in getattr(body.shape, "geoms", [body.shape]):
            for ring in (part.exterior, *part.interiors):
                xy = np.array(ring.coords)
                for a, b in zip(xy[:-1], xy[1:]):
                    cuts = [(0.0, 1.0)]
                    for p0, p1 in covered:
                        cuts = subtract(cuts, along(a, b, p0, p1, self.tol))
                    for lo, hi in cuts:
                        length = (hi - lo) * float(np.linalg.norm(b - a))
                        total += length
                        moment += length * (a + (lo + hi) / 2 * (b - a))
        return moment / total

    def _overlap(self, p: Body, q: Body) -> bool:
        """True where bodies p and q overlap by more than the tolerance: boxes by the
        separating-axis test, polygons (convex or not) by their unions shrunk by half of it."""
        if not (p.polygons or q.polygons):
            return any(convex_overlap(box_corners(u), box_corners(v), self.tol)
                       for u in p.boxes for v in q.boxes)
        return p.shape.buffer(-self.tol / 2, join_style="mitre").intersects(
            q.shape.buffer(-self.tol / 2, join_style="mitre"))

    def check(self, supported=None) -> None:
        """ValueError naming the body or flexure (and the model file's line where known) for
        unknown or repeated names, overlapping bodies, a flexure end outside the body it names,
        a leaf thicker than long, a fillet or notch that does not fit, overlapping flexures, a
        body joined to nothing, and (``supported``: the held group names) a mechanism with no
        support or a body not connected to a held one."""
        names = [b.name for b in self.bodies]
        if not 1e-6 <= self.size <= 10.0:
            raise ValueError(f"{self.source}: the mechanism is {self.size:.4g} m across; "
                             "lengths are in m (a flexure mechanism is 1 um to 10 m)")
        for b in self.bodies:
            if names.count(b.name) > 1:
                raise _error(b, f"body {b.name!r} is named twice; each body needs its own name")
        for i, p in enumerate(self.bodies):
            for q in self.bodies[i + 1:]:
                if self._overlap(p, q):
                    raise _error(q, f"bodies {p.name!r} and {q.name!r} overlap; a body is one "
                                 "name for all its boxes and polygons")
        spans = [self._check_flexure(i) for i in range(len(self.flexures))]
        self._check_overlaps(spans)
        joined = {name for f in self.flexures for name in f.between}
        for b in self.bodies:
            if b.name not in joined:
                raise _error(b, f"body {b.name!r} is joined to nothing: no [[flexure]] has it in "
                             "its between")
        held = [name for name in (supported or ()) if name in names]
        if supported is not None and not held:
            raise ValueError(f"{self.source}: the mechanism has no support: hold a body "
                             f"([[supports]] group = one of {names})")
        reached, todo = set(held), list(held)
        while todo:
            name = todo.pop()
            for f in self.flexures:
                if name in f.between:
                    other = f.between[1] if f.between[0] == name else f.between[0]
                    if other not in reached:
                        reached.add(other)
                        todo.append(other)
        for b in self.bodies:
            if held and b.name not in reached:
                raise _error(b, f"body {b.name!r} is not connected by flexures to a held body "
                             f"({', '.join(held)}): it would float free")

    def _check_flexure(self, i: int) -> Span:
        f = self.flexures[i]
        label = flexure_label(f, i)
        names = [b.name for b in self.bodies]
        if len(f.between) != 2 or f.between[0] == f.between[1]:
            raise _error(f, f"{label}: between must name two different bodies")
        for name in f.between:
            if name not in names:
                raise _error(f, f"{label}: no body is named {name!r}; bodies: {names}")
        if not f.thickness >= 1e-6:
            raise _error(f, f"{label}: thickness = {f.thickness!r} m must be at least 1 um "
                         "(lengths are in m)")
        for point, name, key in ((f.start, f.between[0], "from"), (f.end, f.between[1], "to")):
            if not self.body(name).contains(point, self.tol):
                raise _error(f, f"{label}: {key} = {list(point)} is not inside body {name!r}; "
                             "a flexure's ends lie inside (or on) the bodies it joins")
        if math.dist(f.start, f.end) <= self.tol:
            raise _error(f, f"{label}: from and to are the same point")
        span = self.span(i)
        if span.length <= self.tol:
            raise _error(f, f"{label}: no free length between {f.between[0]!r} and "
                         f"{f.between[1]!r}: the bodies touch along it")
        for point in (span.a, span.b):
            if sum(b.contains(point, self.tol) for b in self.bodies) > 1:
                raise _error(f, f"{label}: its root at {point.tolist()} touches two bodies")
        mid = (span.a + span.b) / 2
        for b in self.bodies:
            if b.contains(mid, -self.tol):
                raise _error(f, f"{label}: its free span runs through body {b.name!r}")
        if isinstance(f, Leaf):
            if f.thickness >= span.length:
                raise _error(f, f"{label}: a leaf thicker ({f.thickness:.4g} m) than long "
                             f"({span.length:.4g} m free) is a block, not a flexure; check the "
                             "units (lengths are in m)")
            if f.fillet < 0 or 2 * f.fillet >= span.length:
                raise _error(f, f"{label}: fillet = {f.fillet:.4g} m must be >= 0 and less than "
                             f"half the free length ({span.length:.4g} m)")
        else:
            if not (f.radius > 0 and f.semi_axes[1] > 0):
                raise _error(f, f"{label}: radius = {f.radius!r} and across = {f.across!r} "
                             "must be > 0 (m)")
            if abs(span.length - 2 * f.radius) > 1e-6 * span.length + self.tol:
                raise _error(f, f"{label}: its free span is {span.length:.6g} m but a notch of "
                             f"radius {f.radius:.6g} m (along the centre line) spans 2 radius = "
                             f"{2 * f.radius:.6g} m; place the bodies' faces 2 radius apart")
        return span

    def _check_overlaps(self, spans) -> None:
        """Overlapping or touching flexures are refused (the continuum would fuse them into
        one, the beam model keep two); two leaves that cross at an angle are a joint."""
        for i, (f, s) in enumerate(zip(self.flexures, spans)):
            for j in range(i + 1, len(spans)):
                g, t = self.flexures[j], spans[j]
                crossing = (isinstance(f, Leaf) and isinstance(g, Leaf)
                            and abs(cross2(s.d, t.d)) > math.sin(math.radians(10)))
                if not crossing and convex_overlap(s.corners(f.width), t.corners(g.width),
                                                    -self.tol):
                    touching = not convex_overlap(s.corners(f.width), t.corners(g.width),
                                                  self.tol)
                    raise _error(g, f"{flexure_label(g, j)} {'touches' if touching else 'overlaps'}"
                                    f" {flexure_label(f, i)}" + (
                                        " (no gap between them: the continuum would fuse them "
                                        "into one flexure)" if touching else ""))
