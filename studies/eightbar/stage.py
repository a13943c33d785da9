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

Buckling (linear, about the linear static state of the load on the free end-effector face):
under the drive force (F_x, the mechanism's drive) the critical F_x over the drive force the
large-deflection solve needs at the end of the stroke; under an off-axis load, F_y across
the stroke in each sense: the stage's support direction, loaded e.g. by the payload's weight
when the stroke is horizontal in a vertical plane, the load a stage is judged to carry.
"""
import numpy as np

from ...fem import (Fixed, Force, RigidFace, compliance_matrix, solve_buckling, solve_modes,
                    solve_nonlinear)
from ...geometry.eightbar.flexure import EightBarFlexureParams
from .analysis import NEWTON_TOL, build_model, linear_analysis

FACE = "end_effector"
N_MODES = 3


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


def stroke_rows(model, travel: float, steps: int, both_halves: bool) -> list:
    """Rows (sorted by stroke x) of the stage's compliance numbers and prestressed modes about
    the nonlinear states at ``steps`` positions per half stroke (0 included)."""
    rows = []
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
    if not both_halves:
        rows += [_mirror(r) for r in rows if r["x_m"] > 0]
    return sorted(rows, key=lambda r: r["x_m"])


def _mirror(row: dict) -> dict:
    """The row at -x by the part's mirror symmetry (x -> -x): odd quantities change sign."""
    C = np.array(row["compliance"])
    S = np.diag([-1.0, 1.0, -1.0])
    return {**row, "x_m": -row["x_m"], "force_x_n": -row["force_x_n"],
            "rotation_rad": -row["rotation_rad"], "parasitic_y": -row["parasitic_y"],
            "compliance": (S @ C @ S).tolist(), "mirrored": True}


def buckling(model, drive_force: float, senses=(1.0, -1.0)) -> dict:
    """Linear buckling of the flexures: critical drive force F_x (N) on the free end-effector
    face and its factor over ``drive_force`` (N, the end-of-stroke drive), and the critical
    off-axis loads F_y (N) in the ``senses`` of y (+y: towards the links; the lower is the
    stage's)."""
    supports = [Fixed("fixed")]
    drive = solve_buckling(model, supports, [Force(FACE, (1.0, 0.0))], n=1)
    out = {"drive_critical_n": float(drive.load_factors[0]),
           "drive_factors": [float(f) for f in drive.load_factors],
           "drive_force_n": float(abs(drive_force)),
           "drive_factor": float(drive.load_factors[0] / abs(drive_force))}
    for sense in senses:
        b = solve_buckling(model, supports, [Force(FACE, (0.0, sense))], n=1)
        out[f"off_axis_critical_{'plus' if sense > 0 else 'minus'}_y_n"] = float(b.load_factors[0])
    if senses:
        out["off_axis_critical_n"] = min(v for k, v in out.items()
                                         if k.startswith("off_axis_crit"))
    out["off_axis_load"] = ("a force across the stroke (y) on the end-effector face, each "
                            "sense: the support direction, loaded by e.g. the payload's weight "
                            "when the stroke is horizontal in a vertical plane")
    return out


def stage_study(params: EightBarFlexureParams | None = None, quick: bool = False,
                travel: float | None = None) -> dict:
    """The stage study (see the module), SI units. quick: coarse mesh (size factor 2), two
    steps per half stroke, +x half mirrored, no off-axis buckling (Lanczos on this mesh takes
    5-20 s a load case); else the default mesh, four steps per half, both halves solved.
    Returns {"linear": face row at the drawn pose, "stroke": rows, "buckling",
    "summary": extremes over the stroke, "linear_analysis": k_x, k_y of the prescribed-motion
    solves (the check), "travel_m", "dofs", "mesh_size_factor"}."""
    params = params or EightBarFlexureParams()
    travel = params.rigid.travel if travel is None else float(travel)
    size_factor = 2.0 if quick else 1.0
    model, _ = build_model(params, size_factor)
    linear = face_row(compliance_matrix(model, [Fixed("fixed")], FACE), 0.0)
    check = linear_analysis(model, 1e-4)
    rows = stroke_rows(model, travel, 2 if quick else 4, both_halves=not quick)
    # the middle state is the unloaded reference: its modes are the linear ones
    middle = min(rows, key=lambda r: abs(r["x_m"]))
    linear.update({k: middle[k] for k in middle if k.startswith("f") and k.endswith("_hz")})
    drive_end = max(abs(r["force_x_n"]) for r in rows)
    return {"linear": linear, "stroke": rows, "buckling": buckling(model, drive_end, () if quick else (1.0, -1.0)),
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
