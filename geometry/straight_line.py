"""The classic straight-line linkages of the eight-bar thesis, Chapter 2, and the straightness of a
traced path.

Each builder draws its linkage in the middle of its straight stretch (the reference pose) and
returns a :class:`StraightLineMechanism`: the linkage, its tracing point, and the input range
over which the path is used (crank rotation from the reference pose, rad, or for Chebyshev's
linkage the tracing point's x, m). Lengths in m.
"""
from dataclasses import dataclass

import numpy as np

from ..fem import checks

from .linkage import (
    CrankAngle,
    Joint,
    Link,
    Linkage,
    PointCoordinate,
    trace_from_reference,
)


@dataclass(frozen=True)
class LineDeviation:
    """Straightness of a path against its total-least-squares line.

    max_deviation_m: largest distance of a point from the line; band_m: width of the band the
    path fills across the line (max minus min signed distance, the thesis' "max minus min Y");
    travel_m: extent of the path along the line; deviation_pct = 100 max_deviation / travel.
    """

    max_deviation_m: float
    band_m: float
    travel_m: float
    deviation_pct: float
    direction: tuple
    centroid: tuple


def straight_line_deviation(points) -> LineDeviation:
    """Deviation of points (n, 2), m, from their total-least-squares (orthogonal) line."""
    points = np.asarray(points, float)
    if points.ndim != 2 or points.shape[1] != 2 or len(points) < 2:
        raise ValueError(f"points: shape {points.shape}, must be (n >= 2, 2)")
    centroid = points.mean(axis=0)
    centred = points - centroid
    _, _, vt = np.linalg.svd(centred, full_matrices=False)
    direction, normal = vt[0], vt[1]
    along, across = centred @ direction, centred @ normal
    travel = float(np.ptp(along))
    if travel == 0:
        raise ValueError("points: all coincide, the path has no travel")
    max_dev = float(np.max(np.abs(across)))
    return LineDeviation(max_dev, float(np.ptp(across)), travel, 100.0 * max_dev / travel,
                         tuple(direction), tuple(centroid))


@dataclass(frozen=True)
class StraightLineMechanism:
    """A linkage, its tracing point (link, point) and its input range (rad for a crank, m for
    a point coordinate; the reference pose lies inside it)."""

    name: str
    linkage: Linkage
    tracer: tuple
    input_range: tuple


def _four_bar(O, A, B, C, P, crank_range, name):
    """Four-bar O-A-B-C (ground O, C) with coupler point P, crank OA driven."""
    links = (Link("ground", {"O": O, "C": C}),
             Link("crank", {"O": O, "A": A}),
             Link("coupler", {"A": A, "B": B, "P": P}, outline=("A", "P", "B")),
             Link("rocker", {"B": B, "C": C}))
    joints = (Joint("O", ("ground", "crank")), Joint("A", ("crank", "coupler")),
              Joint("B", ("coupler", "rocker")), Joint("C", ("rocker", "ground")))
    return StraightLineMechanism(name, Linkage(links, joints, (CrankAngle("crank"),)),
                                 ("coupler", "P"), crank_range)


def watt_linkage(a=0.1, b=0.1, h=0.05, crank_range=(-0.2, 0.2)) -> StraightLineMechanism:
    """Watt's linkage (Section 2.1): |OA| = a, |BC| = b, |AB| = h, ground g^2 = h^2 + (a + b)^2
    (cranks parallel, coupler perpendicular to them in the middle pose). The tracing point P
    divides AB in the inverse ratio of the cranks, |AP| / |PB| = b / a, which makes the path's
    curvature vanish in the middle; the thesis prints x / (h - x) = a / b, which is the same
    point when x is measured from B (identical for a = b; see docs/eightbar.md)."""
    for name, value in (("a", a), ("b", b), ("h", h)):
        checks.positive(name, value, unit="m")
    x = h * b / (a + b)   # |AP|
    O, A, B, C = (-a, 0.0), (0.0, 0.0), (0.0, h), (b, h)
    return _four_bar(O, A, B, C, (0.0, x), crank_range, "watt")


def roberts_linkage(a=0.2, h=0.1, crank_range=(-0.2, 0.2)) -> StraightLineMechanism:
    """Roberts' linkage (Section 2.2): cranks |OA| = |BC| = a, coupler |AB| = h, ground g = 2h,
    tracing point P the apex of the isosceles coupler triangle, |AP| = |BP| = a, which in the
    middle position lies on the ground line midway between O and C."""
    for name, value in (("a", a), ("h", h)):
        checks.positive(name, value, unit="m")
    if not a > h / 2:
        raise ValueError(f"a = {a} m, must be > h/2 = {h / 2} m for the coupler to reach")
    y = np.sqrt(a**2 - (h / 2) ** 2)
    O, A, B, C = (-h, 0.0), (-h / 2, y), (h / 2, y), (h, 0.0)
    return _four_bar(O, A, B, C, (0.0, 0.0), crank_range, "roberts")


def chebyshev_linkage(h=0.1) -> StraightLineMechanism:
    """Chebyshev's linkage (Section 2.3): ground |OC| = 2h, coupler |AB| = h, crossed cranks
    |OA| = |BC| = 2.5h, P the coupler midpoint. Drawn in the symmetric pose A = (1.5h, 2h),
    B = (0.5h, 2h). The standard straight stretch takes P from above O (x = 0) to above C
    (x = 2h); P is exactly at height 2h at both ends and in the middle. Both ends are toggle
    positions of a crank (O, B, A collinear at x = 0; A, B, C collinear at x = 2h), so the input
    is P's x coordinate (m), which stays regular over the stretch."""
    checks.positive("h", h, unit="m")
    O, A, B, C = (0.0, 0.0), (1.5 * h, 2 * h), (0.5 * h, 2 * h), (2 * h, 0.0)
    mech = _four_bar(O, A, B, C, (h, 2 * h), (0.0, 2 * h), "chebyshev")
    linkage = Linkage(mech.linkage.links, mech.linkage.joints, (PointCoordinate("coupler", "P", 0),))
    return StraightLineMechanism("chebyshev", linkage, mech.tracer, mech.input_range)


def _peaucellier_cell(a, b, c, psi):
    """Points of a Peaucellier cell with arms |OA| = |OD| = a, rhombus A-C-D-P of side b, O at
    the origin, C on the circle of radius c about Q = (c, 0) at angle psi (rad)."""
    Q = np.array([c, 0.0])
    C = Q + c * np.array([np.cos(psi), np.sin(psi)])
    oc = np.hypot(*C)
    u = C / oc
    op = (a**2 - b**2) / oc          # signed: < 0 puts P on the other side of O
    P = u * op
    M = (C + P) / 2
    half = np.sqrt(b**2 - ((oc - op) / 2) ** 2)
    n = np.array([-u[1], u[0]])
    return {"O": (0.0, 0.0), "Q": tuple(Q), "C": tuple(C), "P": tuple(P),
            "A": tuple(M + half * n), "D": tuple(M - half * n)}


def _peaucellier(a, b, c, psi, crank_range, name):
    pts = _peaucellier_cell(a, b, c, psi)
    links = (Link("ground", {k: pts[k] for k in ("O", "Q")}),
             Link("arm_OA", {k: pts[k] for k in ("O", "A")}),
             Link("arm_OD", {k: pts[k] for k in ("O", "D")}),
             Link("side_AC", {k: pts[k] for k in ("A", "C")}),
             Link("side_CD", {k: pts[k] for k in ("C", "D")}),
             Link("side_AP", {k: pts[k] for k in ("A", "P")}),
             Link("side_DP", {k: pts[k] for k in ("D", "P")}),
             Link("crank_QC", {k: pts[k] for k in ("Q", "C")}))
    joints = (Joint("O", ("ground", "arm_OA")), Joint("O", ("ground", "arm_OD")),
              Joint("Q", ("ground", "crank_QC")),
              Joint("A", ("arm_OA", "side_AC")), Joint("A", ("arm_OA", "side_AP")),
              Joint("D", ("arm_OD", "side_CD")), Joint("D", ("arm_OD", "side_DP")),
              Joint("C", ("side_AC", "side_CD")), Joint("C", ("side_AC", "crank_QC")),
              Joint("P", ("side_AP", "side_DP")))
    return StraightLineMechanism(name, Linkage(links, joints, (CrankAngle("crank_QC"),)),
                                 ("side_AP", "P"), crank_range)


def peaucellier_linkage(a=0.3, b=0.2, c=0.1, psi=np.pi / 2,
                        crank_range=(-np.pi / 3, np.pi / 7)) -> StraightLineMechanism:
    """Peaucellier-Lipkin linkage (Section 2.4): arms |OA| = |OD| = a > rhombus side b, extra
    link |QC| = |OQ| = c. O, C, P stay collinear with OC * OP = a^2 - b^2 (Eq. 2.2 and the
    proof after Eq. 2.6), so P moves on the exact line x = (a^2 - b^2) / (2c)."""
    for name, value in (("a", a), ("b", b), ("c", c)):
        checks.positive(name, value, unit="m")
    if not a > b:
        raise ValueError(f"a = {a} m, must be > b = {b} m (else use the modified linkage)")
    return _peaucellier(a, b, c, psi, crank_range, "peaucellier")


def modified_peaucellier_linkage(a=0.1, b=0.2, c=0.1, psi=np.pi / 2,
                                 crank_range=(-np.pi / 3, np.pi / 7)) -> StraightLineMechanism:
    """Modified Peaucellier linkage (Section 2.5, our reading): arms shorter than the rhombus
    side (a < b) so the pivot O lies inside the rhombus, C and P' on opposite sides of O with
    OC * OP' = b^2 - a^2 (Eqs. 2.3-2.4, 2.7-2.8); P' moves on the exact line
    x = -(b^2 - a^2) / (2c), on the other side of O from the circle of C."""
    for name, value in (("a", a), ("b", b), ("c", c)):
        checks.positive(name, value, unit="m")
    if not a < b:
        raise ValueError(f"a = {a} m, must be < b = {b} m for the modified (inside) cell")
    return _peaucellier(a, b, c, psi, crank_range, "modified_peaucellier")


CLASSIC_LINKAGES = {
    "watt": watt_linkage,
    "roberts": roberts_linkage,
    "chebyshev": chebyshev_linkage,
    "peaucellier": peaucellier_linkage,
    "modified_peaucellier": modified_peaucellier_linkage,
}


def trace_straight_line(mechanism: StraightLineMechanism, n: int = 201):
    """Trace a mechanism's tracing point over its input range: (path (n, 2) m, LineDeviation)."""
    tr = trace_from_reference(mechanism.linkage, *mechanism.input_range, n)
    path = tr.path(*mechanism.tracer)
    return path, straight_line_deviation(path)
