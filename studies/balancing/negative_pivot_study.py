"""Compressed-leaf negative-stiffness pivots for the balancing robot's K < 0 motors, checked by
FEM (total-Lagrangian, large deflection) beside the beam-column and elastica closed forms of
:mod:`.negative_pivot`; the study writes balancing_negative_pivot.csv and .png. SI units.
"""
import math
from pathlib import Path

import numpy as np

from ...fem import material as library_material
from ...geometry.flexure_pivot import PivotGeometry
from ..engine.tables import write_rows
from ..report.figures import label, pyplot, save
from .design import default_workspace
from .gravity import load_robot, workspace_torques
from .negative_pivot import (
    KL_DEFAULT,
    CompressedLeafPivot,
    beam_column_rotational_stiffness,
    compressed_leaf_elastica,
    plate_modulus,
    preload_for_stiffness,
    size_negative_pivot,
)
from .optimum import optimal_torsion_spring, rms_reduction_pct
from .pivot_fem import hub_state, pivot_model


# ---------------------------------------------------------------- FEM check (large deflection)

def leaf_model(pivot: CompressedLeafPivot, formulation, elements_through_thickness, nu):

    geometry = PivotGeometry("single", pivot.L, pivot.t)
    return pivot_model(pivot, formulation, elements_through_thickness, nu, geometry)


def negative_pivot_fem_check(pivot: CompressedLeafPivot, fractions=(0.5, 1.0), steps=4,
                             formulation="plane_stress", elements_through_thickness=2, nu=None,
                             P=None, small_angle=1e-4) -> dict:
    """FEM (total-Lagrangian SVK, fem.nonlinear) of the compressed leaf beside the closed forms.

    The leaf is clamped ("fixed"); the hub face is a RigidFace turned by theta with the dead
    compressive force P (N; default pivot.P) and free translation. fractions: hub rotations
    as fractions of pivot.theta_max (negative ones check the odd symmetry; none: the small-
    angle stiffness only). Returns (SI):
    stiffness_closed (beam-column) and stiffness_fem_small (M / theta at small_angle rad),
    their difference over E I / L, the curve theta / moment_fem / moment_elastica /
    dy_fem / dy_elastica, and at theta_max the FEM peak von Mises stress (nodal and element)
    beside the elastica clamp stress E t kappa(0) / 2 + P / (w t), the safety factors and the
    Jacobi stability of every elastica state. plane_strain uses E / (1 - nu^2) in the closed
    forms (the plate limit of a wide leaf).
    """
    if not (isinstance(steps, int) and steps >= 1):
        raise ValueError(f"steps = {steps!r} must be an integer >= 1")
    fractions = [float(f) for f in fractions]
    if any(not (0 < abs(f) <= 1) for f in fractions):
        raise ValueError(f"fractions = {fractions!r} must each be in [-1, 0) or (0, 1]")
    model = leaf_model(pivot, formulation, elements_through_thickness, nu)
    E = pivot.material.E
    if formulation == "plane_strain":
        E = plate_modulus(E, model.material.nu)
    P = pivot.P if P is None else float(P)
    I, L = pivot.I, pivot.L
    k_closed = beam_column_rotational_stiffness(E, I, L, P)
    m_small, _, _ = hub_state(model, P, small_angle, 2)
    out = {"formulation": formulation, "L_m": L, "t_m": pivot.t, "w_m": pivot.w, "P_N": P,
           "kL": L * math.sqrt(P / (E * I)), "nu": model.material.nu,
           "n_dofs": int(model.n_dofs), "EI_over_L_Nm_per_rad": E * I / L,
           "stiffness_closed_Nm_per_rad": k_closed,
           "stiffness_fem_small_Nm_per_rad": m_small / small_angle,
           "stiffness_error_over_EI_L": (k_closed - m_small / small_angle) / (E * I / L)}
    if not fractions:
        return out
    curve = {k: [] for k in ("theta_rad", "moment_fem_Nm", "moment_elastica_Nm", "dy_fem_m",
                             "dy_elastica_m", "elastica_stable")}
    last = None
    for f in sorted(fractions, key=abs):
        theta = f * pivot.theta_max
        moment, (_, dy), result = hub_state(model, P, theta, steps)
        ela = compressed_leaf_elastica(E, I, L, P, theta)
        for key, value in zip(curve, (theta, moment, ela.moment, dy, ela.dy, ela.stable)):
            curve[key].append(value)
        if last is None or theta > last[1].theta:
            last = (result, ela)
    out.update({f"curve_{k}": v for k, v in curve.items()})
    out["elastica_stable_all"] = all(curve["elastica_stable"])
    result, ela = last
    sigma_closed = E * pivot.t * abs(ela.clamp_curvature) / 2.0 + P / (pivot.w * pivot.t)
    out.update({"theta_stress_rad": ela.theta, "stress_elastica_Pa": sigma_closed,
                "stress_fem_peak_nodal_Pa": result.max_von_mises,
                "stress_fem_peak_element_Pa": result.max_von_mises_element,
                "yield_Pa": pivot.material.yield_strength,
                "safety_factor_fem": pivot.material.yield_strength / result.max_von_mises,
                "newton_iterations": [int(i) for i in result.iterations],
                "step_cuts": int(result.info["step_cuts"])})
    return out


# ---------------------------------------------------------------- motors 2 and 4

def motor_rms_reductions(q, tau, K, q_k, pivot: CompressedLeafPivot, theta, moment):
    """RMS torque reductions (%) of one motor over the workspace samples q (rad), tau (N m):
    the ideal torsion spring K (q_k - q), and the compressed leaf neutral at mid-range whose
    hub moment (N m) is known at pivot rotations theta (rad; odd in theta, mirrored and
    interpolated), plus the constant K (q_k - q_mid) supplied apart."""

    q_mid = 0.5 * (q.min() + q.max())
    N = pivot.transmission_ratio
    th, m = np.asarray(theta, float), np.asarray(moment, float)
    keep = th > 0
    th, m = np.concatenate([-th[keep][::-1], [0.0], th[keep]]), np.concatenate(
        [-m[keep][::-1], [0.0], m[keep]])
    leaf = -np.interp((q - q_mid) / N, th, m) / N
    return (float(rms_reduction_pct(tau, tau + K * (q_k - q))),
            float(rms_reduction_pct(tau, tau + K * (q_k - q_mid) + leaf)))


def negative_pivot_designs(workspace=None, material="spring_steel_aisi1095", safety_factor=2.0,
                           max_pivot_rotation_rad=math.radians(15.0), kL=KL_DEFAULT) -> list:
    """(motor, K, q_k, q, tau, CompressedLeafPivot) of every motor whose RMS-optimal torsion
    spring has K < 0: the leaf straight at mid-range, the smallest integer N keeping the pivot
    rotation <= max_pivot_rotation_rad (as studies.balancing.pivot_designs does for K > 0)."""

    wt = workspace_torques(load_robot(), workspace or default_workspace())
    out = []
    for i, motor in enumerate(wt.motors):
        q, tau = wt.q[:, i], wt.tau[:, i]
        spring = optimal_torsion_spring(q, tau)
        if spring.K >= 0.0:
            continue
        half = 0.5 * (q.max() - q.min())
        N = float(math.ceil(half / max_pivot_rotation_rad))
        pivot = size_negative_pivot(spring.K, (-half, half), library_material(material),
                                    safety_factor, transmission_ratio=N, kL=kL)
        out.append((motor, spring.K, spring.q_k, q, tau, pivot))
    return out


def negative_pivot_study(out_dir, quick: bool = False, workspace=None) -> dict:
    """Compressed-leaf pivots for the K < 0 motors, checked by FEM; writes
    balancing_negative_pivot.csv and balancing_negative_pivot.png into out_dir. quick: the
    hub turned to theta_max only, 3 load steps; else to theta_max / 2, 1 and -1 with 4 steps,
    and the small-angle plane-strain (plate) stiffness with the preload retuned for
    E / (1 - nu^2).
    Returns {"rows", "tables", "figures"} (SI units)."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    fractions, steps = ((1.0,), 3) if quick else ((0.5, 1.0, -1.0), 4)
    rows = []
    for motor, K, q_k, q, tau, pivot in negative_pivot_designs(workspace):
        check = negative_pivot_fem_check(pivot, fractions, steps)
        dense = np.linspace(0.0, pivot.theta_max, 13)[1:]
        elastica = [compressed_leaf_elastica(pivot.material.E, pivot.I, pivot.L, pivot.P, th)
                    for th in dense]
        ideal, with_elastica = motor_rms_reductions(q, tau, K, q_k, pivot, dense,
                                                    [e.moment for e in elastica])
        _, with_fem = motor_rms_reductions(q, tau, K, q_k, pivot, check["curve_theta_rad"],
                                           check["curve_moment_fem_Nm"])
        q_mid = float(0.5 * (q.min() + q.max()))
        row = {"motor": motor, "K_motor_Nm_per_rad": K, "q_k_rad": q_k, "q_mid_rad": q_mid,
               "constant_torque_Nm": K * (q_k - q_mid),
               **pivot.as_dict(), "curve_elastica_theta_rad": dense.tolist(),
               "curve_elastica_moment_Nm": [e.moment for e in elastica],
               "secant_stiffness_elastica_at_theta_max_Nm_per_rad":
                   elastica[-1].moment / pivot.theta_max,
               "rms_reduction_ideal_torsion_pct": ideal,
               "rms_reduction_leaf_elastica_pct": with_elastica,
               "rms_reduction_leaf_fem_pct": with_fem,
               **{f"fem_{k}": v for k, v in check.items() if k not in pivot.as_dict()}}
        if not quick:
            nu = check["nu"]
            E_plate = plate_modulus(pivot.material.E, nu)
            P_plate = preload_for_stiffness(pivot.stiffness, E_plate, pivot.I, pivot.L)
            plate = negative_pivot_fem_check(pivot, (), steps, "plane_strain", P=P_plate)
            row.update({"plate_P_N": P_plate,
                        "plate_stiffness_at_beam_P_Nm_per_rad": beam_column_rotational_stiffness(
                            E_plate, pivot.I, pivot.L, pivot.P),
                        "plate_stiffness_fem_small_Nm_per_rad":
                            plate["stiffness_fem_small_Nm_per_rad"]})
        rows.append(row)
    table = "balancing_negative_pivot.csv"
    keys = [k for k in rows[0] if not k.startswith(("curve", "fem_curve", "fem_newton"))]
    write_rows(out_dir / table, rows, keys)
    figure = plot_negative_pivots(out_dir / "balancing_negative_pivot.png", rows)
    return {"rows": rows, "tables": [table], "figures": [figure]}


def plot_negative_pivots(path, rows: list) -> dict:
    """Hub moment (N m) vs pivot rotation (deg): linear K theta, elastica, FEM; one panel per
    motor."""
    plt = pyplot()
    fig, axes = plt.subplots(1, len(rows), figsize=(5.5 * len(rows), 4.2), squeeze=False)
    for ax, r in zip(axes[0], rows):
        th = np.array(r["curve_elastica_theta_rad"])
        th = np.concatenate([-th[::-1], [0.0], th])
        m = np.array(r["curve_elastica_moment_Nm"])
        m = np.concatenate([-m[::-1], [0.0], m])
        ax.plot(np.degrees(th), r["stiffness_Nm_per_rad"] * th, "k--",
                label="beam-column K theta (kL cot kL)")
        ax.plot(np.degrees(th), m, "b-", label="elastica")
        ax.plot(np.degrees(r["fem_curve_theta_rad"]), r["fem_curve_moment_fem_Nm"], "ro", ms=5,
                label="FEM (plane stress, large deflection)")
        ax.set_title(f"motor {r['motor']}: N = {r['transmission_ratio']:g}, L = "
                     f"{r['L_m'] * 1e3:.0f} mm, t = {r['t_m'] * 1e3:.2f} mm, "
                     f"w = {r['w_m'] * 1e3:.0f} mm, P = {r['P_N']:.0f} N", fontsize=9)
        label(ax, ("pivot rotation", "deg"), ("moment on the hub", "N m"), legend_size=8)
    fig.tight_layout()
    return save(fig, path, "Negative-stiffness compressed-leaf pivots of motors 2 and 4: hub "
                "moment against rotation, beam-column linear stiffness, elastica and "
                "large-deflection FEM.")
