"""The driving linkage of the eight-bar thesis, Chapter 6: two Chebyshev lambda linkages, mirror
images about x = 0, whose coupler points P_L, P_R are joined by a small input link (the
*shuttle*); pushing the shuttle along y drives, through a connecting bar per side, the
end-effectors of two eight-bar suspensions (:mod:`flexfem.geometry.eightbar.rigid`) in opposite
x directions.

The thesis gives no dimensions and its figures are not in the text, so the arrangement is ours
(docs/eightbar_driving.md, "Driving linkage"): each lambda has its ground line O-C vertical, so its
coupler point P runs along y; the lambda's crank O-A is extended to a lever point Q whose
x-motion a horizontal connecting bar Q-D carries to the suspension's end-effector (D a point on
it). The lambda is the Roberts-Chebyshev cognate of the Chebyshev linkage of Section 2.3
(ground 2h, cranks 2.5h, coupler h, P mid-coupler): ground h, crank h/2, coupler and rocker
1.25h, P on AB extended with |AP| = 2.5h; it traces the same curve (tested).

Mobility. One half (lambda + bar + suspension) has Gruebler count 1. The whole, with the
shuttle, counts 3(24 - 1) - 2 * 34 = 1, but its rigid-body motion is not the symmetric one:
the shuttle keeps |P_L P_R| = 2e, which the two mirrored lambda paths respect only to their
straight-line deviation. The rigid trace therefore drives each half by y of its own P (two
inputs, equal values) and reports the misfit |P_R - P_L| - 2e that the flexures absorb (it
takes no share of the end-effectors' path: the flexure part without its shuttle traces the
same one, tested). The suspensions default to the Chapter 5 eight-bar with a longer coupler,
pre-bowed against its flexures' elastic bow (:func:`compensated_suspension`). All lengths in m.
"""
import math
from dataclasses import dataclass, field, fields

import numpy as np

from ...data import load_toml
from ...fem import checks
from ...fem.materials import material
from ..flexure_drawing import mesh_layout
from ..flexure_linkage import FlexureLayout, flexure_layout
from ..linkage import CrankAngle, Joint, Link, Linkage, PointCoordinate, trace
from ..straight_line import (
    LineDeviation,
    StraightLineMechanism,
    straight_line_deviation,
)
from .flexure import check_mesh_options
from .rigid import EightBarParams, build_eightbar, eightbar_points


def chebyshev_lambda_linkage(h: float = 0.1) -> StraightLineMechanism:
    """Chebyshev's lambda linkage, the cognate of Section 2.3's linkage of parameter h (m):
    ground O = (0, 0), C = (h, 0); crank |OA| = h/2; coupler A-B-P with |AB| = |BP| = 1.25h;
    rocker |CB| = 1.25h. P runs near y = 2h from x = 2h (crank at 90 deg) to x = 0 (270 deg),
    exactly at y = 2h at x = 0, h, 2h. Drawn at crank angle 180 deg (P = (h, 2h)); input: the
    crank rotation from there (rad), range +-pi/2 (the whole straight stretch)."""
    checks.positive("h", h, unit="m")
    O, C, A, P = (0.0, 0.0), (h, 0.0), (-h / 2, 0.0), (h, 2 * h)
    B = ((A[0] + P[0]) / 2, (A[1] + P[1]) / 2)
    links = (Link("ground", {"O": O, "C": C}), Link("crank", {"O": O, "A": A}),
             Link("coupler", {"A": A, "B": B, "P": P}, outline=("A", "B", "P")),
             Link("rocker", {"C": C, "B": B}))
    joints = (Joint("O", ("ground", "crank")), Joint("A", ("crank", "coupler")),
              Joint("B", ("coupler", "rocker")), Joint("C", ("rocker", "ground")))
    linkage = Linkage(links, joints, (CrankAngle("crank"),))
    return StraightLineMechanism("chebyshev_lambda", linkage, ("coupler", "P"), (-np.pi / 2, np.pi / 2))


# Coupler length (m) of the suspensions driven here, against the Chapter 5 design's 50 mm:
# the flexure suspension bows (its large-deflection path is y ~ c2 x^2) where its rigid-body
# linkage runs straight, and a longer coupler pre-bows the rigid path the other way. Derived by
# flexfem.studies.eightbar.compensation.compensated_coupler_length (data/eightbar_design.toml).
FLEXURE_COMPENSATED_COUPLER_LENGTH = load_toml("eightbar_design.toml")["driving"][
    "compensated_coupler_length_m"]


def compensated_suspension() -> EightBarParams:
    """The Chapter 5 eight-bar with its coupler lengthened to
    :data:`FLEXURE_COMPENSATED_COUPLER_LENGTH` (m), so that its *flexure* version, driven here,
    runs straight; its rigid-body path bows the other way (c2 = -0.86 /m: 0.31 % of a 22.4 mm
    stroke; the flexures' elastic bow grows with h too)."""
    return EightBarParams(coupler_length=FLEXURE_COMPENSATED_COUPLER_LENGTH)


@dataclass(frozen=True)
class DrivingParams:
    """The driving linkage with its two suspensions, m.

    suspension : the eight-bar of each side (right one as drawn, left its mirror image;
    default :func:`compensated_suspension`, ``EightBarParams()`` for the Chapter 5 design);
    lambda_crank a : |OA| of each lambda (its straight stretch is 4a long); lever_length r :
    |OQ|, the crank extended beyond A (r > a) to the bar; shuttle_half_width e : P_R at x = e;
    clearance : x gap between a lambda's ground line and its suspension's outer pivot;
    shuttle_height : length of the shuttle's stem (input face on top); input_travel : shuttle
    stroke along y traced, centred on the drawn pose (< 4a).
    """

    suspension: EightBarParams = field(default_factory=compensated_suspension)
    lambda_crank: float = 30e-3
    lever_length: float = 75e-3
    shuttle_half_width: float = 25e-3
    clearance: float = 30e-3
    shuttle_height: float = 30e-3
    input_travel: float = 12e-3

    def __post_init__(self):
        if not isinstance(self.suspension, EightBarParams):
            raise ValueError(f"suspension = {self.suspension!r} must be an EightBarParams")
        for f in fields(self):
            if f.name == "suspension":
                continue
            checks.positive(f.name, getattr(self, f.name), owner="DrivingParams", unit="m")
        if not self.lever_length > self.lambda_crank:
            raise ValueError(f"lever_length = {self.lever_length} m, must be > lambda_crank = "
                             f"{self.lambda_crank} m (Q lies beyond A on the crank)")
        if not self.input_travel < 4 * self.lambda_crank:
            raise ValueError(f"input_travel = {self.input_travel} m, must be < 4 lambda_crank = "
                             f"{4 * self.lambda_crank} m (the lambda's straight stretch)")

    @property
    def suspension_axis(self) -> float:
        """x (m) of the right suspension's axis."""
        s = self.suspension
        return (self.shuttle_half_width + 4 * self.lambda_crank + self.clearance
                + s.module_spacing / 2 + s.ground_spacing / 2)

    @property
    def shuttle_y(self) -> float:
        """y (m) of P_L, P_R in the drawn pose: the bar Q-D is level with the end-effector."""
        y_e = eightbar_points(self.suspension)["E"][1]
        return y_e + 2 * self.lambda_crank + self.lever_length


def _mirror(xy):
    return (-xy[0], xy[1])


def _placed_suspension(params: DrivingParams, side: str, extra: dict):
    """The suspension's links and joints renamed with prefix "sus<side>_", moved to its axis
    (mirrored for the left side); ``extra`` {point: xy (right side)} is added to its
    end-effector."""
    base = build_eightbar(params.suspension)
    X = params.suspension_axis
    pre = f"sus{side}_"

    def where(xy):
        xy = (xy[0] + X, xy[1])
        return _mirror(xy) if side == "L" else xy

    def rename(line):
        return tuple(rename(x) for x in line) if isinstance(line, tuple) else pre + line

    links = []
    for link in base.links:
        pts = {pre + k: where(v) for k, v in link.points.items()}
        if link.name == "end_effector":
            pts.update({k: (_mirror(v) if side == "L" else v) for k, v in extra.items()})
        name = "ground" if link.name == "ground" else pre + link.name
        links.append(Link(name, pts, rename(link.outline) if link.outline else ()))
    joints = [Joint(pre + j.point, tuple("ground" if n == "ground" else pre + n for n in j.links))
              for j in base.joints]
    return links, joints


def _lambda_points(params: DrivingParams) -> dict:
    """Right lambda, bar and shuttle points (m), drawn pose (crank at 180 deg of the lambda)."""
    a, r, e, yj = params.lambda_crank, params.lever_length, params.shuttle_half_width, params.shuttle_y
    x0 = e + 4 * a                     # the lambda's ground line O-C
    susp = eightbar_points(params.suspension)
    # D: on the end-effector, left of its bottom corner E_L by half a flexure and half a bar
    # width is added by the flexure layout; the rigid point is E_L itself moved by `d_offset`
    e_l = (susp["E_L"][0] + params.suspension_axis, susp["E_L"][1])
    return {"O": (x0, yj - 2 * a), "C": (x0, yj), "A": (x0, yj - 3 * a), "B": (e + 2 * a, yj - 1.5 * a),
            "P": (e, yj), "Q": (x0, yj - 2 * a - r), "E_L": e_l}


def driving_points(params: DrivingParams, d_offset: float = 0.0) -> dict:
    """Named world points (m) of the lambdas, bars and shuttle: "lam<side>_<O|C|A|B|P|Q|D>",
    "S", "T" (shuttle stem bottom and top). D lies ``d_offset`` (m) left of the right
    suspension's end-effector corner E_L (mirrored on the left)."""
    pts = _lambda_points(params)
    d = (pts["E_L"][0] - d_offset, pts["E_L"][1])
    right = {f"lamR_{k}": v for k, v in pts.items() if k != "E_L"}
    right["lamR_D"] = d
    out = dict(right)
    out.update({k.replace("lamR_", "lamL_"): _mirror(v) for k, v in right.items()})
    out["S"] = (0.0, params.shuttle_y)
    out["T"] = (0.0, params.shuttle_y + params.shuttle_height)
    return out


def _lambda_side(pts: dict, side: str):
    p = f"lam{side}_"

    def pick(*names):
        return {p + n: pts[p + n] for n in names}

    links = [Link(p + "crank", pick("O", "A", "Q"), outline=(p + "O", p + "A", p + "Q")),
             Link(p + "coupler", pick("A", "B", "P"), outline=(p + "A", p + "B", p + "P")),
             Link(p + "rocker", pick("C", "B")), Link(p + "bar", pick("Q", "D"))]
    joints = [Joint(p + "O", ("ground", p + "crank")), Joint(p + "A", (p + "crank", p + "coupler")),
              Joint(p + "B", (p + "coupler", p + "rocker")), Joint(p + "C", (p + "rocker", "ground")),
              Joint(p + "Q", (p + "crank", p + "bar")),
              Joint(p + "D", (p + "bar", f"sus{side}_end_effector"))]
    return links, joints


def build_driving_linkage(params: DrivingParams, shuttle: bool = True, d_offset: float = 0.0) -> Linkage:
    """The whole mechanism as a :class:`Linkage`. With ``shuttle`` (default) the coupler points
    are pinned to the shuttle and the input is the shuttle's S.y (Gruebler count 1, see the
    module docstring); without it, the two halves are independent and driven by y of P_R and
    y of P_L (two inputs)."""
    pts = driving_points(params, d_offset)
    links, joints, ground = [], [], {}
    for side in ("R", "L"):
        sus_links, sus_joints = _placed_suspension(params, side, {"lam" + side + "_D": pts["lamR_D"]})
        for link in sus_links:
            if link.name == "ground":
                ground.update(link.points)
            else:
                links.append(link)
        lam_links, lam_joints = _lambda_side(pts, side)
        links += lam_links
        joints += sus_joints + lam_joints
        ground.update({f"lam{side}_O": pts[f"lam{side}_O"], f"lam{side}_C": pts[f"lam{side}_C"]})
    links.insert(0, Link("ground", ground))
    if shuttle:
        links.append(Link("shuttle", {k: pts[k] for k in ("lamL_P", "lamR_P", "S", "T")},
                          outline=(("lamL_P", "lamR_P"), ("S", "T"))))
        joints += [Joint("lamR_P", ("lamR_coupler", "shuttle")), Joint("lamL_P", ("lamL_coupler", "shuttle"))]
        inputs = (PointCoordinate("shuttle", "S", 1),)
    else:
        inputs = (PointCoordinate("lamR_coupler", "lamR_P", 1), PointCoordinate("lamL_coupler", "lamL_P", 1))
    return Linkage(tuple(links), tuple(joints), inputs)


def half_mobility(params: DrivingParams) -> int:
    """Gruebler count of one half (its lambda, bar and suspension, ground shared): 1."""
    linkage = build_driving_linkage(params, shuttle=False)
    joints = [j for j in linkage.joints if j.point.startswith(("susR_", "lamR_"))]
    names = {n for j in joints for n in j.links}
    return 3 * (len(names) - 1) - 2 * len(joints)


@dataclass(frozen=True)
class DrivingTrace:
    """Rigid-body trace over the shuttle stroke: ``s`` (n,) shuttle displacement along y (m);
    ``ee_left``, ``ee_right`` (n, 2) the suspensions' end-effector points E (m); their x
    displacements ``dx_left``, ``dx_right`` (n,) (m); straightness of each path and of the
    coupler points' paths; ``misfit`` (n,) |P_R P_L| - 2e (m); ``poses`` of the two-input
    linkage (for drawing)."""

    s: np.ndarray
    ee_left: np.ndarray
    ee_right: np.ndarray
    dx_left: np.ndarray
    dx_right: np.ndarray
    deviation_left: LineDeviation
    deviation_right: LineDeviation
    coupler_deviation: LineDeviation
    misfit: np.ndarray
    poses: np.ndarray
    linkage: Linkage


def trace_driving(params: DrivingParams, n: int = 121) -> DrivingTrace:
    """Trace both halves over ``params.input_travel`` centred on the drawn pose (n points),
    each driven by y of its own coupler point (equal values)."""
    if not (isinstance(n, (int, np.integer)) and n >= 3):
        raise ValueError(f"n = {n!r}, must be an integer >= 3")
    linkage = build_driving_linkage(params, shuttle=False)
    y0, half = params.shuttle_y, params.input_travel / 2
    s = np.linspace(-half, half, n)
    k = int(np.argmin(np.abs(s)))
    up = trace(linkage, np.column_stack([y0 + np.r_[0.0, s[k:]]] * 2))
    down = trace(linkage, np.column_stack([y0 + np.r_[0.0, s[:k][::-1]]] * 2))
    poses = np.concatenate([down.poses[1:][::-1], up.poses[1:]])
    ee_r = linkage.point_position(poses, "susR_end_effector", "susR_E")
    ee_l = linkage.point_position(poses, "susL_end_effector", "susL_E")
    p_r = linkage.point_position(poses, "lamR_coupler", "lamR_P")
    p_l = linkage.point_position(poses, "lamL_coupler", "lamL_P")
    misfit = np.hypot(*(p_r - p_l).T) - 2 * params.shuttle_half_width
    return DrivingTrace(s, ee_l, ee_r, ee_l[:, 0] - ee_l[k, 0], ee_r[:, 0] - ee_r[k, 0],
                        straight_line_deviation(ee_l), straight_line_deviation(ee_r),
                        straight_line_deviation(p_r), misfit, poses, linkage)


def transmission_ratio(tr: DrivingTrace) -> float:
    """d(dx_right)/ds at the drawn pose (central difference), dimensionless."""
    k = int(np.argmin(np.abs(tr.s)))
    return float((tr.dx_right[k + 1] - tr.dx_right[k - 1]) / (tr.s[k + 1] - tr.s[k - 1]))


# -- the flexure version (Section 6.2): every pivot a beam flexure -------------------------------
_LAMBDA_HOSTS = {"O": "crank", "C": "rocker", "A": "coupler", "B": "rocker", "P": "coupler",
                 "Q": "bar", "D": "bar"}
_SUSPENSION_HOSTS = {"O": "crank", "C": "rocker", "A": "coupler", "B": "coupler", "P": "coupler"}


def _host(joint: str) -> str:
    if joint.startswith("lam"):
        side, key = joint[3], joint.split("_", 1)[1]
        return f"lam{side}_{_LAMBDA_HOSTS[key]}"
    pre, key = joint[:5], joint[5:]        # "susR_" + "O_L"
    return pre + _SUSPENSION_HOSTS[key[0]] + key[1:]


def _is_base(joint: str) -> bool:
    return joint.split("_", 1)[1][0] in "OC"


def _end_cap(link: str, point, W: float):
    """Edge callable: the square end (width W, m) of ``link``'s bar that runs W/2 past ``point``."""
    def cap(parts):
        for part in parts:
            a, b = np.asarray(part.p0), np.asarray(part.p1)
            d = (b - a) / np.linalg.norm(b - a)
            if part.link == link and part.kind == "bar" and np.allclose(b, np.asarray(point) + W / 2 * d):
                n = np.array([-d[1], d[0]]) * W / 2
                return tuple(b - n), tuple(b + n)
        raise ValueError(f"no bar of {link!r} ends at {point}")
    return cap


def driving_layout(params: DrivingParams, flexure, shuttle: bool = True) -> FlexureLayout:
    """The flexure part's rectangles (m) in the drawn pose, with the flexure sizes, link width,
    of ``flexure`` (an :class:`~flexfem.geometry.eightbar.flexure.EightBarFlexureParams`, whose
    ``rigid`` is ignored: the suspensions are ``params.suspension``). Edges: "fixed" (anchors),
    "input" (top face of the shuttle's stem), "ee_L", "ee_R" (bottom faces of the two
    suspensions' end-effector bars). Without ``shuttle`` the two halves are separate parts, each
    lambda's coupler ending W/2 past P in a free end face "input_L" / "input_R" (to drive each
    half by its own coupler point, as :func:`trace_driving` does: no misfit to take up)."""

    W, L = flexure.link_width, flexure.flexure_length
    linkage = build_driving_linkage(params, shuttle=shuttle, d_offset=L / 2 + W / 2)
    polylines = {link.name: [[tuple(link.points[n]) for n in line] for line in link.polylines]
                 for link in linkage.links if link.name != "ground"}
    joints = [{"name": j.point, "position": tuple(linkage.link(j.links[1]).points[j.point]),
               "links": tuple(j.links), "base": "ground" in j.links} for j in linkage.joints]
    sizes = {j["name"]: ((flexure.base_flexure_length, flexure.base_flexure_width) if _is_base(j["name"])
                         else (flexure.flexure_length, flexure.flexure_width)) for j in joints}
    ee = linkage.link("susR_end_effector").points
    (xl, y), xr = ee["susR_E_L"], ee["susR_E_R"][0]
    bottom_r = ((xl - W / 2, y - W / 2), (xr + W / 2, y - W / 2))
    bottom_l = tuple(_mirror(p) for p in bottom_r[::-1])
    edges = {"ee_R": bottom_r, "ee_L": bottom_l}
    if shuttle:
        tx, ty = linkage.link("shuttle").points["T"]
        edges["input"] = ((tx - W / 2, ty + W / 2), (tx + W / 2, ty + W / 2))
    else:
        for side in ("L", "R"):
            edges[f"input_{side}"] = _end_cap(f"lam{side}_coupler",
                                              linkage.link(f"lam{side}_coupler").points[f"lam{side}_P"], W)
    return flexure_layout(polylines, joints, {j["name"]: _host(j["name"]) for j in joints}, sizes, W,
                          edges=edges)


def mesh_driving_flexure(params: DrivingParams, flexure, n_across: int = 3, size_factor: float = 1.0,
                         aspect: float = 4.0, shuttle: bool = True):
    """Mesh the driving linkage's flexure part (see :func:`driving_layout`, with or without the
    ``shuttle``): triangles (use order=2), as
    :func:`flexfem.geometry.eightbar.flexure.mesh_eightbar_flexure` meshes the suspension.
    Returns (FEMesh, sizes dict, m)."""

    check_mesh_options(n_across, size_factor)
    n = max(int(n_across), int(math.ceil(3 / size_factor)))
    return mesh_layout(driving_layout(params, flexure, shuttle), n_across=n,
                       aspect=min(20.0, max(0.5, aspect * size_factor)),
                       coarse=flexure.link_width / 2 * size_factor, name="driving_flexure")


def lever_shear_rate(params: DrivingParams, flexure) -> float:
    """Pseudo-rigid-body y force (N) on each end-effector per metre of its x motion, N/m.

    The crank turns by dx / r (the bar, level in the drawn pose, does not turn), so the flexure
    at Q bends and its moment k_Q dx / r (k_Q = E t w^3 / 12 L) is balanced by a shear force
    across the bar Q-D: k_Q / (r |QD|) per metre. Divided by the suspension's k_y it tilts the
    end-effector's path by that many radians (odd in the stroke, so a tilt, not a curvature)."""

    E = material(flexure.material).E
    k_q = E * flexure.thickness * flexure.flexure_width**3 / (12 * flexure.flexure_length)
    pts = driving_points(params, flexure.flexure_length / 2 + flexure.link_width / 2)
    bar = float(np.hypot(*np.subtract(pts["lamR_D"], pts["lamR_Q"])))
    return k_q / (params.lever_length * bar)
