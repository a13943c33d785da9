"""FEM check of the beam-theory flexure pivots of the balancing robot (balancing_pivots).

    check = pivot_fem_check(pivot)            # pivot: a FlexurePivot (beam-theory design)
    check["stiffness_error_linear"]           # beam theory / FEM - 1, small-angle stiffness

The pivot is drawn in its plane of rotation (geometry.flexure_pivot): the leaf thickness t in
the plane, the leaf width w out of it. A two-leaf pivot is a cross-spring pivot whose leaves
overlap without touching (as in the real, interleaved part); a one-leaf pivot is a single
leaf. The base and hub blocks are rigid: the leaf base ends are clamped (Fixed "fixed") and
the hub ends move as one rigid body (RigidFace "hub"), free to translate, so that the hub
carries a pure moment, as beam theory assumes.

Two 2-D models bracket the 3-D leaf. Plane stress (thickness w) is the beam of the beam
formula, whose cross-sections contract freely across the width. A leaf much wider than
sqrt(R t) (R = L / theta, the bending radius) cannot curl anticlastically except near its
edges (Searle's parameter beta = w^2 / (R t) >> 1): it bends as a plate in plane strain
across the width, stiffer by 1 / (1 - nu^2). Plane strain (thickness w) is that limit.

Stiffness: (1) small angle, a linear solve with a pure moment on the hub, K = M / theta;
(2) the moment-rotation curve of the large-deflection solver (total-Lagrangian St. Venant-
Kirchhoff, fem.nonlinear) with the hub rotation prescribed up to theta_max, hub translation
free. Stress: von Mises at theta_max, nodal (L2-projected) and element maximum (quadrature
points), over the whole leaf and over its middle part (more than t from either end, away from
the clamps' boundary layers), beside E t theta / (2 L). SI units throughout.
"""
import dataclasses
import math
from pathlib import Path

import numpy as np

from ...fem import (Fixed, Model, PlaneStrain, PlaneStress, RigidFace, material, solve_nonlinear,
                    solve_static, von_mises)
from ...fem.static import nodal_average
from ...geometry.flexure_pivot import PivotGeometry, mesh_pivot
from ..engine.tables import write_rows
from ..report.figures import label, pyplot, save
from .design import pivot_designs
from .pivots import (
    FlexurePivot,
    leaf_bending_stress,
    pivot_stiffness_beam_theory,
)

FORMULATIONS = ("plane_stress", "plane_strain")


def pivot_geometry(pivot: FlexurePivot, crossing_angle=math.pi / 2) -> PivotGeometry:
    """The in-plane geometry of a one-leaf (single) or two-leaf (cross-spring) pivot."""
    if pivot.n_leaves not in (1, 2):
        raise ValueError(f"n_leaves = {pivot.n_leaves} must be 1 (single leaf) or 2 "
                         "(cross-spring) for the 2-D model")
    kind = "single" if pivot.n_leaves == 1 else "cross"
    return PivotGeometry(kind, pivot.L, pivot.t, crossing_angle=crossing_angle)


def pivot_model(pivot: FlexurePivot, formulation="plane_stress", elements_through_thickness=2,
                nu=None, geometry: PivotGeometry | None = None) -> Model:
    """P2 plane model of the pivot, out-of-plane thickness = leaf width w (m)."""
    if formulation not in FORMULATIONS:
        raise ValueError(f"formulation = {formulation!r} must be one of {FORMULATIONS}")
    mat = pivot.material if nu is None else dataclasses.replace(pivot.material, nu=nu)
    mesh = mesh_pivot(geometry or pivot_geometry(pivot), elements_through_thickness)
    plane = PlaneStress(pivot.w) if formulation == "plane_stress" else PlaneStrain(pivot.w)
    return Model(mesh, mat, plane, order=2)


def linear_moment_solve(model, moment: float = 1.0) -> tuple:
    """Small-deflection solve with a pure moment (N m) on the rigid, translation-free "hub"
    and "fixed" clamped, of the continuum or the beam model: (rotation theta (rad), the
    StaticResult or BeamResult)."""
    result = solve_static(model, [Fixed("fixed")], [],
                          rigid_faces=[RigidFace("hub", moment=moment)])
    return float(result.face_motion["hub"][2]), result


def hub_rotation_curve(model, theta_max: float, steps: int) -> tuple:
    """The hub turned to ``theta_max`` (rad) in ``steps`` large-deflection steps, "fixed"
    clamped, the hub free to translate, on the continuum or the beam model: ({curve_theta_rad,
    curve_moment_Nm, stiffness_secant / _tangent_Nm_per_rad at theta_max,
    hub_centroid_shift_m, newton_iterations}, the solver's path)."""
    result = solve_nonlinear(model, [Fixed("fixed")], [], steps=steps,
                             rigid_faces=[RigidFace("hub", rotation=theta_max)])
    thetas = np.array([m["hub"][2] for m in result.face_motion])
    moments = np.array([r["hub"][2] for r in result.face_reactions])
    hub = np.array([m["hub"][:2] for m in result.face_motion])
    return {"curve_theta_rad": thetas.tolist(), "curve_moment_Nm": moments.tolist(),
            "stiffness_secant_Nm_per_rad": float(moments[-1] / thetas[-1]),
            "stiffness_tangent_Nm_per_rad": float((moments[-1] - moments[-2])
                                                  / (thetas[-1] - thetas[-2])),
            "hub_centroid_shift_m": float(np.linalg.norm(hub[-1])),
            "newton_iterations": [int(i) for i in result.iterations]}, result


def hub_state(model, P: float, theta: float, steps: int) -> tuple:
    """(moment (N m), (dx, dy) (m), the solver's path) with the hub turned by theta (rad)
    under the dead compressive load P (N), on the continuum or the beam model; preload and
    rotation grow together (a conservative system: the end state is that of preloading first,
    on the branch the Jacobi test shows to be the only stable one)."""
    result = solve_nonlinear(model, [Fixed("fixed")], [], steps=steps,
                             rigid_faces=[RigidFace("hub", rotation=theta, force=(-P, 0.0))])
    motion = result.face_motion[-1]["hub"]
    return float(result.face_reactions[-1]["hub"][2]), (float(motion[0]), float(motion[1])), result


def _leaf_middle(model: Model, geometry: PivotGeometry):
    """(element mask, vertex mask) of the leaf parts more than t from either leaf end."""
    mesh = model.mesh
    p, t = mesh.mesh.p, mesh.mesh.t
    centroids = p[:, t].mean(axis=1)
    elements = np.zeros(t.shape[1], dtype=bool)
    names = ["leaves"] if geometry.kind == "single" else ["leaf_1", "leaf_2"]
    for name, angle in zip(names, geometry.leaf_angles):
        idx = mesh.elements(name)
        s = centroids[0, idx] * math.cos(angle) + centroids[1, idx] * math.sin(angle)
        elements[idx[np.abs(s) <= 0.5 * geometry.L - geometry.t]] = True
    vertices = np.zeros(p.shape[1], dtype=bool)
    vertices[np.unique(t[:, elements])] = True
    return elements, vertices


def _stress_summary(nodal, element_max, middle, prefix):
    elements, vertices = middle
    return {f"{prefix}_peak_nodal_Pa": float(nodal.max()),
            f"{prefix}_peak_element_Pa": float(element_max.max()),
            f"{prefix}_mid_leaf_nodal_Pa": float(nodal[vertices].max()),
            f"{prefix}_mid_leaf_element_Pa": float(element_max[elements].max())}


def pivot_fem_check(pivot: FlexurePivot, theta_max: float | None = None, steps: int = 4,
                    formulation="plane_stress", elements_through_thickness=2, nu=None,
                    crossing_angle=math.pi / 2) -> dict:
    """FEM stiffness and stress of a beam-theory pivot, beside beam theory.

    theta_max: largest pivot rotation (rad; default pivot.theta_max); steps: load steps of the
    large-deflection solve (0 skips it). Returns a dict (SI): stiffness_beam, stiffness_linear,
    stiffness_secant / stiffness_tangent at theta_max (nonlinear), the errors of beam theory
    (beam / FEM - 1), the curve (theta_rad, moment_Nm), the beam stress E t theta / (2 L) and
    the FEM von Mises stresses at theta_max (from the nonlinear solve, else the linear one
    scaled to theta_max), their errors, and the safety factor yield / FEM peak nodal stress.
    """
    theta_max = pivot.theta_max if theta_max is None else theta_max
    if not (isinstance(theta_max, (int, float)) and 0 < theta_max <= math.pi / 2):
        raise ValueError(f"theta_max = {theta_max!r} rad must be in (0, pi/2]")
    if not (isinstance(steps, int) and steps >= 0):
        raise ValueError(f"steps = {steps!r} must be an integer >= 0")
    geometry = pivot_geometry(pivot, crossing_angle)
    model = pivot_model(pivot, formulation, elements_through_thickness, nu, geometry)
    middle = _leaf_middle(model, geometry)
    k_beam = pivot_stiffness_beam_theory(pivot)
    sigma_beam = float(leaf_bending_stress(pivot.material.E, pivot.t, theta_max, pivot.L))
    theta, linear = linear_moment_solve(model, moment=k_beam * theta_max)
    k_linear = k_beam * theta_max / theta
    sig = model.stress(linear.u * theta_max / theta)
    out = {"formulation": formulation, "n_leaves": pivot.n_leaves, "L_m": pivot.L,
           "t_m": pivot.t, "w_m": pivot.w, "nu": model.material.nu,
           "n_elements": int(model.mesh.mesh.t.shape[1]), "n_dofs": int(model.n_dofs),
           "theta_max_rad": float(theta_max), "stiffness_beam_Nm_per_rad": k_beam,
           "stiffness_linear_Nm_per_rad": k_linear,
           "stiffness_error_linear": k_beam / k_linear - 1.0,
           "stress_beam_Pa": sigma_beam}
    out.update(_stress_summary(von_mises(nodal_average(model, sig)),
                               von_mises(sig).max(axis=1), middle, "linear_stress"))
    prefix = "linear_stress"
    if steps:
        curve, result = hub_rotation_curve(model, theta_max, steps)
        out.update(curve)
        out["stiffness_error_secant"] = k_beam / out["stiffness_secant_Nm_per_rad"] - 1.0
        out["stiffness_error_tangent"] = k_beam / out["stiffness_tangent_Nm_per_rad"] - 1.0
        out.update(_stress_summary(result.von_mises_nodal, result.von_mises_element_max, middle,
                                   "nonlinear_stress"))
        prefix = "nonlinear_stress"
    out["stress_source"] = prefix
    out["stress_fem_peak_Pa"] = out[f"{prefix}_peak_nodal_Pa"]
    out["stress_fem_mid_leaf_Pa"] = out[f"{prefix}_mid_leaf_nodal_Pa"]
    out["stress_error_peak"] = sigma_beam / out["stress_fem_peak_Pa"] - 1.0
    out["stress_error_mid_leaf"] = sigma_beam / out["stress_fem_mid_leaf_Pa"] - 1.0
    out["yield_Pa"] = pivot.material.yield_strength
    out["safety_factor_fem"] = pivot.material.yield_strength / out["stress_fem_peak_Pa"]
    out["safety_factor_beam"] = pivot.material.yield_strength / sigma_beam
    return out


def pivot_from_dict(row: dict) -> FlexurePivot:
    """Rebuild a FlexurePivot from its as_dict() (pivot_designs rows)."""
    return FlexurePivot(L=row["L_m"], t=row["t_m"], w=row["w_m"], n_leaves=row["n_leaves"],
                        material=material(row["material"]),
                        transmission_ratio=row["transmission_ratio"],
                        theta_max=row["theta_max_rad"], stiffness=row["stiffness_Nm_per_rad"],
                        max_stress=row["max_stress_Pa"], safety_factor=row["safety_factor"])


def positive_stiffness_pivots(workspace=None) -> list:
    """(motor, reading, FlexurePivot) of every feasible design of studies.balancing's
    pivot_designs for the motors with K > 0 (readings "at_q_k", "at_mid_range")."""

    out = []
    for row in pivot_designs(workspace):
        for reading in ("at_q_k", "at_mid_range"):
            design = row.get(reading)
            if design and "infeasible" not in design:
                out.append((row["motor"], reading, pivot_from_dict(design)))
    return out


def pivot_fem_study(out_dir, quick: bool = False, workspace=None) -> dict:
    """pivot_fem_check, plane stress and plane strain, of every K > 0 pivot design; writes
    balancing_pivot_fem.csv (one row per motor and formulation) and balancing_pivot_fem.png
    (moment vs pivot rotation, FEM and beam theory) into out_dir. quick: 2 elements through
    the leaf and 4 load steps, else 3 and 8. Returns {"rows", "tables", "figures"}."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    n_through, steps = (2, 4) if quick else (3, 8)
    rows = []
    for motor, reading, pivot in positive_stiffness_pivots(workspace):
        for formulation in FORMULATIONS:
            check = pivot_fem_check(pivot, steps=steps, formulation=formulation,
                                    elements_through_thickness=n_through)
            rows.append({"motor": motor, "design": reading,
                         "transmission_ratio": pivot.transmission_ratio, **check})
    table = "balancing_pivot_fem.csv"
    keys = [k for k in rows[0] if not k.startswith("curve") and k != "newton_iterations"]
    write_rows(out_dir / table, rows, keys)
    figure = plot_moment_rotation(out_dir / "balancing_pivot_fem.png", rows)
    return {"rows": rows, "tables": [table], "figures": [figure]}


def plot_moment_rotation(path, rows: list) -> dict:
    """Moment (N m) vs pivot rotation (deg), FEM (large deflection) and beam theory K theta,
    one panel per motor."""
    plt = pyplot()
    motors = sorted({(r["motor"], r["design"]) for r in rows})
    fig, axes = plt.subplots(1, len(motors), figsize=(5.5 * len(motors), 4.2), squeeze=False)
    for ax, (motor, design) in zip(axes[0], motors):
        mine = [r for r in rows if (r["motor"], r["design"]) == (motor, design)]
        theta = np.linspace(0.0, mine[0]["theta_max_rad"], 50)
        ax.plot(np.degrees(theta), mine[0]["stiffness_beam_Nm_per_rad"] * theta, "k--",
                label="beam theory n E w t^3 / (12 L)")
        for r, style in zip(mine, ("o-", "s-")):
            if "curve_theta_rad" in r:
                ax.plot(np.degrees(r["curve_theta_rad"]), r["curve_moment_Nm"], style, ms=4,
                        label=f"FEM, {r['formulation'].replace('_', ' ')}")
        ax.set_title(f"motor {motor}: cross-spring, N = {mine[0]['transmission_ratio']:g}, "
                     f"L = {mine[0]['L_m'] * 1e3:.0f} mm, t = {mine[0]['t_m'] * 1e3:.2f} mm")
        label(ax, ("pivot rotation", "deg"), ("moment on the hub", "N m"), legend_size=8)
    fig.tight_layout()
    return save(fig, path, "Cross-spring flexure pivots sized as the torsion springs of motors "
                "3 and 5: hub moment against rotation by large-deflection FEM (plane stress and "
                "plane strain) beside beam theory.")
