"""The symmetric rectilinear eight-bar linkage, rigid-body (eight-bar thesis, Chapter 5).

The thesis does not print its link dimensions, so this is our own design with the same
structure: two 3R chains ground-crank-coupler-end-effector (Ch. 4) closed by two RR
constraints (the rockers), drawn mirror-symmetric about the y axis. Each half is a symmetric
four-bar (a generalised Roberts linkage, Section 2.2): ground pivots O, C a distance g apart,
equal cranks a, coupler AB of length h, and the coupler point P on the symmetry axis a depth p
below AB's midpoint M (the coupler is T-shaped: bar A-M-B and stem M-P). P's path is even
in its travel, y(s) = y0 + c2 s^2 + c4 s^4 + ..., and p is chosen so that c2 balances c4
over the travel (docs/eightbar.md tells how the dimensions were found). The end-effector joins P_L and P_R; since both halves trace
the same even path the end-effector translates without rotating. Input: the x coordinate of the
end-effector's reference point E. All lengths in m; drawn in the middle of the travel.

8 links (ground, 2 cranks, 2 couplers, 2 rockers, end-effector), 10 revolute joints:
Gruebler mobility 3(8 - 1) - 2 * 10 = 1.
"""
from dataclasses import dataclass, fields

import numpy as np

from .. import bounds
from ..linkage import Joint, Link, Linkage, PointCoordinate, trace_from_reference
from ..straight_line import LineDeviation, straight_line_deviation


@dataclass(frozen=True)
class EightBarParams:
    """Symmetric eight-bar, lengths in m (defaults: our design, 200 mm x 149 mm overall).

    ground_spacing g: |OC| of each half; crank_length a: |OA| = |CB|; coupler_length h: |AB|;
    coupler_point_depth p: P below the midpoint of AB; module_spacing: |P_L P_R| (distance
    between the halves' axes); ee_drop: the end-effector bar lies this far below P;
    travel: end-effector stroke traced, centred on the drawn pose.

    Every length is a finite real number in [10 nm, 10 m] (not a bool, string, None, list or
    complex: ValueError naming it, as DBMAParams), at most 10^4 between the largest and the
    smallest (geometry/bounds.py).
    """

    ground_spacing: float = 90e-3
    crank_length: float = 72e-3
    coupler_length: float = 50e-3
    coupler_point_depth: float = 122.5e-3
    module_spacing: float = 110e-3
    ee_drop: float = 25e-3
    travel: float = 35e-3

    def __post_init__(self):
        bounds.span("EightBarParams",
                    bounds.lengths("EightBarParams", self, [f.name for f in fields(self)]))
        reach = abs(self.ground_spacing - self.coupler_length) / 2
        if not self.crank_length > reach:
            raise ValueError(f"crank_length = {self.crank_length} m, must be > |g - h|/2 = "
                             f"{reach} m for the coupler to reach")
        if not self.module_spacing > self.ground_spacing:
            raise ValueError(f"module_spacing = {self.module_spacing} m, must be > ground_spacing "
                             f"= {self.ground_spacing} m so the two halves do not overlap")
        if not self.travel < self.ground_spacing:
            raise ValueError(f"travel = {self.travel} m, must be < ground_spacing = "
                             f"{self.ground_spacing} m")

    @property
    def coupler_height(self) -> float:
        """Height (m) of the coupler AB above the ground pivots in the drawn pose."""
        return float(np.sqrt(self.crank_length**2 - ((self.ground_spacing - self.coupler_length) / 2) ** 2))


def eightbar_points(params: EightBarParams) -> dict:
    """Named points (m) in the drawn (middle) pose; ground pivots on y = 0, symmetric about x = 0."""
    g, h, d = params.ground_spacing, params.coupler_length, params.module_spacing
    y_ab = params.coupler_height
    y_p = y_ab - params.coupler_point_depth
    y_e = y_p - params.ee_drop
    points = {"E": (0.0, y_e)}
    for side, sign in (("L", -1.0), ("R", 1.0)):
        axis = sign * d / 2
        # outer pivot O and crank A, inner pivot C and rocker B (mirror images)
        points[f"O_{side}"] = (axis + sign * g / 2, 0.0)
        points[f"C_{side}"] = (axis - sign * g / 2, 0.0)
        points[f"A_{side}"] = (axis + sign * h / 2, y_ab)
        points[f"B_{side}"] = (axis - sign * h / 2, y_ab)
        points[f"M_{side}"] = (axis, y_ab)
        points[f"P_{side}"] = (axis, y_p)
        points[f"E_{side}"] = (axis, y_e)
    return points


BASE_JOINTS = ("O_L", "C_L", "O_R", "C_R")


def build_eightbar(params: EightBarParams) -> Linkage:
    """The eight-bar as a :class:`Linkage`, input: x (m) of the end-effector point E."""
    pts = eightbar_points(params)

    def pick(*names):
        return {n: pts[n] for n in names}

    links = [Link("ground", pick(*BASE_JOINTS)),
             Link("end_effector", pick("P_L", "E_L", "E", "E_R", "P_R"),
                  outline=("P_L", "E_L", "E_R", "P_R"))]
    joints = []
    for s in ("L", "R"):
        links += [Link(f"crank_{s}", pick(f"O_{s}", f"A_{s}")),
                  Link(f"rocker_{s}", pick(f"C_{s}", f"B_{s}")),
                  Link(f"coupler_{s}", pick(f"A_{s}", f"M_{s}", f"B_{s}", f"P_{s}"),
                       outline=((f"A_{s}", f"M_{s}", f"B_{s}"), (f"M_{s}", f"P_{s}")))]
        joints += [Joint(f"O_{s}", ("ground", f"crank_{s}")),
                   Joint(f"A_{s}", (f"crank_{s}", f"coupler_{s}")),
                   Joint(f"B_{s}", (f"coupler_{s}", f"rocker_{s}")),
                   Joint(f"C_{s}", (f"rocker_{s}", "ground")),
                   Joint(f"P_{s}", (f"coupler_{s}", "end_effector"))]
    return Linkage(tuple(links), tuple(joints), (PointCoordinate("end_effector", "E", 0),))


@dataclass(frozen=True)
class EightBarTrace:
    """End-effector path along the travel: displacements (n,) m of E along x, points (n, 2) m
    of E, rotation (n,) rad of the end-effector, straightness, and the poses (for drawing)."""

    displacements: np.ndarray
    points: np.ndarray
    rotation: np.ndarray
    deviation: LineDeviation
    poses: np.ndarray


def trace_eightbar(params: EightBarParams, n: int = 251) -> EightBarTrace:
    """Trace the end-effector over ``params.travel`` centred on the drawn pose (n points)."""
    linkage = build_eightbar(params)
    x0 = eightbar_points(params)["E"][0]
    tr = trace_from_reference(linkage, x0 - params.travel / 2, x0 + params.travel / 2, n)
    points = tr.path("end_effector", "E")
    rotation = tr.poses[:, 3 * linkage.moving_links.index("end_effector") + 2]
    return EightBarTrace(tr.inputs[:, 0] - x0, points, rotation, straight_line_deviation(points),
                         tr.poses)


def _pose_at(params, linkage, displacement):
    x0 = eightbar_points(params)["E"][0]
    if displacement == 0:
        return np.zeros(3 * len(linkage.moving_links))
    tr = trace_from_reference(linkage, x0, x0 + displacement, 3)
    return tr.poses[-1]


def eightbar_joints(params: EightBarParams, pose: float = 0.0) -> dict:
    """Geometry for replacing the joints by flexures, at end-effector displacement ``pose`` (m).

    Returns {"joints": [{"name", "position" (x, y) m, "links" (a, b), "base" bool}],
    "links": {name: [((x0, y0), (x1, y1)), ...] centre-line segments between joint positions, m},
    "polylines": {name: [[(x, y), ...], ...]} the same centre-lines as polylines,
    "base_joints": [...]}; base joints join a link to the ground. A coupler is T-shaped: the bar
    A-M-B carrying the two crank joints, and the stem M-P down to the end-effector joint.
    """
    linkage = build_eightbar(params)
    q = _pose_at(params, linkage, pose)
    joints = [{"name": j.point,
               "position": tuple(float(c) for c in linkage.point_position(q, j.links[1], j.point)),
               "links": tuple(j.links), "base": "ground" in j.links} for j in linkage.joints]
    moving = [link for link in linkage.links if link.name != linkage.ground]

    def xy(link, name):
        return tuple(float(c) for c in linkage.point_position(q, link.name, name))

    segments = {link.name: [(xy(link, a), xy(link, b)) for a, b in link.segment_names] for link in moving}
    polylines = {link.name: [[xy(link, n) for n in line] for line in link.polylines] for link in moving}
    return {"joints": joints, "links": segments, "polylines": polylines, "base_joints": list(BASE_JOINTS)}


def overall_size(params: EightBarParams, trace_: EightBarTrace = None) -> tuple:
    """Width and height (m) of the box holding every link's centre-line over the travel."""
    trace_ = trace_eightbar(params, n=21) if trace_ is None else trace_
    linkage = build_eightbar(params)
    xy = np.array([linkage.point_position(trace_.poses, link.name, name)
                   for link in linkage.links for name in link.points]).reshape(-1, 2)
    return float(np.ptp(xy[:, 0])), float(np.ptp(xy[:, 1]))
