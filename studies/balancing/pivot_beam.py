"""Beam-model checks of the balancing robot's flexure pivots: the FEM checks' own analyses
(:func:`.pivot_fem.linear_moment_solve`, :func:`.pivot_fem.hub_rotation_curve`,
:func:`.pivot_fem.hub_state`: the same supports, rigid face and loads by group name) on the
reduced beam model (:func:`flexfem.reduced.pivot.pivot_beam_model`, groups "fixed" and
"hub") instead of the 2-D continuum.

Cross-spring pivot: the base roots clamped, the hub a rigid body free to translate; a pure
moment gives the small-angle stiffness, the hub rotation prescribed to theta_max (co-rotational
large-rotation solve) the moment-rotation curve, and the leaves' beam stress |N|/A + |M|c/I
at theta_max. Compressed leaf: the hub turned by theta with the dead compressive force P on
it, both growing together (as the FEM check does). The leaf width w is out of the plane
(plane stress, as the FEM's plane-stress reading). SI units.
"""
import math

from ...geometry.flexure_pivot import PivotGeometry
from ...reduced.pivot import pivot_beam_model
from .pivot_fem import hub_rotation_curve, hub_state, linear_moment_solve, pivot_geometry
from .pivots import leaf_bending_stress, pivot_stiffness_beam_theory


def pivot_beam_check(pivot, theta_max: float | None = None, steps: int = 8,
                     crossing_angle=math.pi / 2, root_extension=None) -> dict:
    """Beam-model stiffness (small angle, secant and tangent at theta_max, N m/rad), the
    moment-rotation curve and the peak beam stress at theta_max (Pa) of a FlexurePivot; keys
    as :func:`.pivot_fem.pivot_fem_check`'s."""
    theta_max = pivot.theta_max if theta_max is None else float(theta_max)
    g = pivot_geometry(pivot, crossing_angle)
    model, _ = pivot_beam_model(g, pivot.w, pivot.material, root_extension=root_extension)
    theta, _ = linear_moment_solve(model, 1.0)
    curve, path = hub_rotation_curve(model, theta_max, steps)
    peak = path.max_von_mises
    return {"n_leaves": pivot.n_leaves, "n_dofs": int(model.n_dofs),
            "theta_max_rad": theta_max,
            "stiffness_beam_Nm_per_rad": pivot_stiffness_beam_theory(pivot),
            "stiffness_linear_Nm_per_rad": 1.0 / theta, **curve,
            "stress_beam_Pa": float(leaf_bending_stress(pivot.material.E, pivot.t, theta_max,
                                                        pivot.L)),
            "stress_fem_peak_Pa": peak,
            "safety_factor_fem": pivot.material.yield_strength / peak}


def compressed_leaf_beam_check(pivot, fractions=(0.5, 1.0), steps: int = 8, P=None,
                               small_angle: float = 1e-4) -> dict:
    """Beam-model small-angle stiffness (N m/rad), moment-rotation curve and peak stress (Pa)
    of a CompressedLeafPivot under its preload P (N); keys as
    :func:`.negative_pivot_study.negative_pivot_fem_check`'s (the FEM ones)."""
    model, _ = pivot_beam_model(PivotGeometry("single", pivot.L, pivot.t), pivot.w,
                                pivot.material)
    P = pivot.P if P is None else float(P)
    m_small, _, _ = hub_state(model, P, small_angle, 2)
    out = {"L_m": pivot.L, "t_m": pivot.t, "w_m": pivot.w, "P_N": P, "n_dofs": model.n_dofs,
           "stiffness_fem_small_Nm_per_rad": m_small / small_angle}
    thetas, moments, dys, peak = [], [], [], None
    for f in sorted(fractions, key=abs):
        theta = f * pivot.theta_max
        moment, (_, dy), path = hub_state(model, P, theta, steps)
        thetas.append(theta)
        moments.append(moment)
        dys.append(dy)
        peak = path.max_von_mises
    out.update({"curve_theta_rad": thetas, "curve_moment_fem_Nm": moments,
                "curve_dy_fem_m": dys, "stress_fem_peak_nodal_Pa": peak,
                "safety_factor_fem": pivot.material.yield_strength / peak})
    return out
