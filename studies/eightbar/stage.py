"""The eight-bar suspension as a precision stage: what the end-effector face does along the
whole stroke, beyond its drive stiffness.

    out = stage_study(EightBarFlexureParams(), quick=True)
    out["stroke"][k]["k_x"], out["stroke"][k]["support_ratio"], out["buckling"]["drive_factor"]

At the drawn pose (linear) and about the converged large-deflection states at several stroke
positions (the end-effector face driven along x, y and rotation free, as in
:func:`.analysis.large_deflection`), the 3 x 3 compliance of the "end_effector" face at its
centroid, (u_x, u_y, theta) per (F_x, F_y, M), is taken from :func:`fem.compliance_matrix`
(tangent about the state: material and geometric stiffness). From it, per position:

- ``k_x`` (N/m): drive stiffness, 1 / C_xx (y and rotation free);
- ``k_y`` (N/m): support stiffness across the motion with the motion held and the rotation
  free (Compliance.support_stiffness), ``support_ratio`` = k_y / k_x;
- ``k_theta`` (N m/rad): rotational stiffness of the stage, 1 / C_tt (forces free: the tilt
  a payload's moment causes);
- ``parasitic_y`` (m/m), ``parasitic_rotation`` (rad/m): the motion across and the rotation
  per unit drive when the face is pushed along x;
- ``f1_hz`` .. ``f3_hz``: the first three modes, prestressed about the state (the face free,
  i.e. the drive disconnected: the stage's own dynamics at that position).

The part is mirror-symmetric about x = 0, so these are even in the stroke; quick mode solves
the +x half and mirrors it, as the analysis does.

Buckling along the stroke, at both fidelities: about each converged state, the critical load
added on the released end-effector face (:func:`fem.analyses.solve_incremental_buckling`, the
incremental linearised buckling about the state, not the path's limit point): the drive force
F_x in the stroke's sense (``drive_critical_n``) and an off-axis force F_y across the stroke in
each sense (``off_axis_plus_y_n``, ``off_axis_minus_y_n``: the stage's support direction,
loaded e.g. by the payload's weight when the stroke is horizontal in a vertical plane). The
same numbers of the beam model (:func:`.beam_model.beam_model`) about its own large-deflection
path to the same positions (``beam_...``) and their ratios to the continuum's
(``..._ratio``). At the drawn pose (x = 0) this is the linear buckling of the load on the free
face; ``buckling`` keeps that row: the critical drive force over the drive force the
large-deflection solve needs at the end of the stroke, and the off-axis loads.
"""
import numpy as np

from ...fem import Fixed, Force, RigidFace, compliance_matrix, solve_modes, solve_nonlinear
from ...fem.analyses import solve_incremental_buckling
from ...geometry.eightbar.flexure import EightBarFlexureParams
from .analysis import NEWTON_TOL, build_model, linear_analysis
from .beam_model import beam_model

FACE = "end_effector"
N_MODES = 3
# the load cases of the buckling along the stroke: the added force's direction on the face
# (the drive's sense is the stroke's), and the key of its critical force (N)
BUCKLING_CASES = {"drive_critical_n": None, "off_axis_plus_y_n": (0.0, 1.0),
                  "off_axis_minus_y_n": (0.0, -1.0)}
BEAM_TOLERANCE = 0.05  # issue 33: the beam model's buckling within 5 % of the continuum's


def face_row(compliance, x: float, force_x: float = 0.0) -> dict:
    """The stage's numbers of one compliance (see the module) at stroke ``x`` (m)."""
    C = compliance.matrix
    k_x, k_y = compliance.support_stiffness((1.0, 0.0))
    across, rotation = compliance.parasitic((1.0, 0.0))
    return {"x_m": float(x), "force_x_n": float(force_x), "k_x": k_x, "k_y": k_y,
            "support_ratio": k_y / k_x, "k_theta": 1.0 / float(C[2, 2]),
            "parasitic_y": float(across), "parasitic_rotation": float(rotation),
            "compliance": C.tolist()}


def _half_stroke_states(model, end: float, steps: int):
    """The converged nonlinear states from the middle to ``end`` (m)."""
    face = RigidFace(FACE, x=end)
    return solve_nonlinear(model, [Fixed("fixed")], [], steps=steps, tol=NEWTON_TOL,
                           rigid_faces=[face], check_stability=False)


def _modes(model, state) -> list:
    modes = solve_modes(model, N_MODES, [Fixed("fixed")], shift_hz=-1.0, prestress=state)
    return [float(f) for f in modes.frequencies_hz]


def critical_loads(model, state, x: float) -> dict:
    """{key of BUCKLING_CASES: the critical added force (N)} on the released end-effector face
    about ``state`` ((path, step) of the continuum or the beam model) at stroke ``x`` (m): the
    drive in the stroke's sense (+x at x = 0), the off-axis force in each sense of y."""
    sense = -1.0 if x < 0 else 1.0
    out = {}
    for key, vector in BUCKLING_CASES.items():
        b = solve_incremental_buckling(model, state, [Fixed("fixed")],
                                       [Force(FACE, vector or (sense, 0.0))], n=1)
        out[key] = float(b.load_factors[0])
    return out


def stroke_rows(model, travel: float, steps: int, both_halves: bool,
                stride: int = 1) -> tuple:
    """(rows, buckling rows), each sorted by stroke x: the stage's compliance numbers and
    prestressed modes about the nonlinear states at ``steps`` positions per half stroke (0
    included); the critical loads (:func:`critical_loads`) at every ``stride``-th of the +x
    half's, mirrored to -x."""
    rows, buckled = [], []
    for sign in ((1.0, -1.0) if both_halves else (1.0,)):
        result = _half_stroke_states(model, sign * travel / 2, steps)
        for k in range(len(result.load_factors)):
            if sign < 0 and k == 0:
                continue
            motion = result.face_motion[k][FACE]
            force = result.face_reactions[k][FACE]
            c = compliance_matrix(model, [Fixed("fixed")], FACE, state=(result, k))
            row = face_row(c, motion[0], force[0])
            row["y_m"], row["rotation_rad"] = float(motion[1]), float(motion[2])
            f = _modes(model, (result, k))
            row.update({f"f{i + 1}_hz": v for i, v in enumerate(f)})
            rows.append(row)
            if sign > 0 and k % stride == 0:
                buckled.append({"x_m": row["x_m"],
                                **critical_loads(model, (result, k), row["x_m"])})
    if not both_halves:
        rows += [_mirror(r) for r in rows if r["x_m"] > 0]
    buckled += [{**r, "x_m": -r["x_m"], "mirrored": True} for r in buckled if r["x_m"] > 0]
    return sorted(rows, key=lambda r: r["x_m"]), sorted(buckled, key=lambda r: r["x_m"])


def _mirror(row: dict) -> dict:
    """The row at -x by the part's mirror symmetry (x -> -x): odd quantities change sign."""
    C = np.array(row["compliance"])
    S = np.diag([-1.0, 1.0, -1.0])
    return {**row, "x_m": -row["x_m"], "force_x_n": -row["force_x_n"],
            "rotation_rad": -row["rotation_rad"], "parasitic_y": -row["parasitic_y"],
            "compliance": (S @ C @ S).tolist(), "mirrored": True}


def beam_stroke_buckling(params: EightBarFlexureParams, xs) -> dict:
    """{x: critical_loads} of the beam model about its own large-deflection path to each
    stroke position in ``xs`` (m): one path per half stroke through its positions (the
    continuum's steps, equal increments of x), a position off those steps solved alone."""
    model, _, _ = beam_model(params)
    out = {}
    for sign in (1.0, -1.0):
        half = sorted({abs(x) for x in xs if x * sign > 0 or (x == 0 and sign > 0)})
        if not half:
            continue
        end = sign * half[-1]
        steps = max(sum(1 for x in half if x > 0), 1)
        path = solve_nonlinear(model, [Fixed("fixed")], [], steps=steps,
                               rigid_faces=[RigidFace(FACE, x=end)])
        reached = {round(float(m[FACE][0]), 12): k for k, m in enumerate(path.face_motion)}
        for x in half:
            x = sign * x
            k = reached.get(round(x, 12))
            if k is None:
                alone = solve_nonlinear(model, [Fixed("fixed")], [], steps=4,
                                        rigid_faces=[RigidFace(FACE, x=x)])
                out[x] = critical_loads(model, (alone, -1), x)
            else:
                out[x] = critical_loads(model, (path, k), x)
    return out


def ratio_key(key: str) -> str:
    """The key of the beam / continuum ratio of a critical load's key ("drive_ratio", ...)."""
    return key.removesuffix("_n").removesuffix("_critical") + "_ratio"


def add_beam_buckling(rows: list, params: EightBarFlexureParams) -> None:
    """The beam model's critical loads beside each row's (``beam_<key>``) and their ratios
    to the continuum's (``<case>_ratio``, beam / continuum), in place; a mirrored row takes
    its twin's (the part is mirror-symmetric)."""
    beam = beam_stroke_buckling(params, [r["x_m"] for r in rows if not r.get("mirrored")])
    for row in rows:
        numbers = beam[-row["x_m"] if row.get("mirrored") else row["x_m"]]
        for key, value in numbers.items():
            row[f"beam_{key}"] = value
            row[ratio_key(key)] = value / row[key]


def buckling(rows: list, drive_force: float) -> dict:
    """The drawn pose's critical loads (the row at x = 0: linear buckling of the load on the
    free face): the drive force (N), its factor over ``drive_force`` (N, the end-of-stroke
    drive), the off-axis loads in each sense of y (N, +y: towards the links) and the lower;
    and the least critical drive force along the stroke (N) and its factor."""
    middle = min(rows, key=lambda r: abs(r["x_m"]))
    plus, minus = middle["off_axis_plus_y_n"], middle["off_axis_minus_y_n"]
    return {"drive_critical_n": middle["drive_critical_n"],
            "drive_force_n": float(abs(drive_force)),
            "drive_factor": middle["drive_critical_n"] / abs(drive_force),
            "off_axis_critical_plus_y_n": plus, "off_axis_critical_minus_y_n": minus,
            "off_axis_critical_n": min(plus, minus),
            "drive_critical_min_n": min(r["drive_critical_n"] for r in rows),
            "drive_factor_min": min(r["drive_critical_n"] for r in rows) / abs(drive_force),
            "off_axis_load": ("a force across the stroke (y) on the end-effector face, each "
                              "sense: the support direction, loaded by e.g. the payload's "
                              "weight when the stroke is horizontal in a vertical plane")}


def stage_study(params: EightBarFlexureParams | None = None, quick: bool = False,
                travel: float | None = None) -> dict:
    """The stage study (see the module), SI units. quick: coarse mesh (size factor 2), two
    steps per half stroke, +x half mirrored; else the default mesh, four steps per half, both
    halves solved. The buckling along the stroke (three load cases, Lanczos ~5 s a case on the
    coarse mesh) at the +x half's 0, travel / 4 and travel / 2 in both modes, mirrored.
    Returns {"linear": face row at the drawn pose, "stroke": rows, "stroke_buckling": rows of
    the critical loads (N) and the beam model's ratios, "buckling": the drawn pose's and the
    extremes along the stroke,
    "summary": extremes over the stroke, "linear_analysis": k_x, k_y of the prescribed-motion
    solves (the check), "travel_m", "dofs", "mesh_size_factor"}."""
    params = params or EightBarFlexureParams()
    travel = params.rigid.travel if travel is None else float(travel)
    size_factor = 2.0 if quick else 1.0
    model, _ = build_model(params, size_factor)
    linear = face_row(compliance_matrix(model, [Fixed("fixed")], FACE), 0.0)
    check = linear_analysis(model, 1e-4)
    rows, buckled = stroke_rows(model, travel, 2 if quick else 4, both_halves=not quick,
                                stride=1 if quick else 2)
    # the middle state is the unloaded reference: its modes are the linear ones
    middle = min(rows, key=lambda r: abs(r["x_m"]))
    linear.update({k: middle[k] for k in middle if k.startswith("f") and k.endswith("_hz")})
    drive_end = max(abs(r["force_x_n"]) for r in rows)
    add_beam_buckling(buckled, params)
    return {"linear": linear, "stroke": rows, "stroke_buckling": buckled,
            "buckling": {**buckling(buckled, drive_end), **buckling_summary(buckled)},
            "summary": stroke_summary(rows), "travel_m": travel,
            "linear_analysis": {"k_x": check["k_x"], "k_y": check["k_y"]}, "dofs": int(model.n_dofs),
            "mesh_size_factor": size_factor}


def stroke_summary(rows: list) -> dict:
    """Extremes over the stroke: the least support stiffness and ratio, the least rotational
    stiffness, the largest parasitic motions, the range of each frequency."""
    def lo(key):
        return float(min(r[key] for r in rows))

    def hi_abs(key):
        return float(max(abs(r[key]) for r in rows))

    out = {"k_x_min": lo("k_x"), "k_x_max": float(max(r["k_x"] for r in rows)),
           "k_y_min": lo("k_y"), "support_ratio_min": lo("support_ratio"),
           "k_theta_min": lo("k_theta"), "parasitic_y_max": hi_abs("parasitic_y"),
           "parasitic_rotation_max": hi_abs("parasitic_rotation")}
    for i in range(1, N_MODES + 1):
        out[f"f{i}_hz_min"] = lo(f"f{i}_hz")
        out[f"f{i}_hz_max"] = float(max(r[f"f{i}_hz"] for r in rows))
    return out


def buckling_summary(rows: list) -> dict:
    """The least critical loads over the stroke (N), the continuum's and the beam model's,
    and the beam model's worst ratio to the continuum (-) with its case and position (m),
    judged by BEAM_TOLERANCE."""
    out = {"off_axis_critical_min_n": min(min(r["off_axis_plus_y_n"], r["off_axis_minus_y_n"])
                                          for r in rows)}
    ratios = [(r[k], k, r["x_m"]) for r in rows for k in r if k.endswith("_ratio")
              and k != "support_ratio"]
    if ratios:
        worst = max(ratios, key=lambda t: abs(t[0] - 1.0))
        out.update({"beam_drive_critical_min_n": min(r["beam_drive_critical_n"] for r in rows),
                    "beam_buckling_worst_ratio": worst[0], "beam_buckling_worst_case": worst[1],
                    "beam_buckling_worst_x_m": worst[2],
                    "beam_buckling_within": bool(abs(worst[0] - 1.0) <= BEAM_TOLERANCE)})
    return out
