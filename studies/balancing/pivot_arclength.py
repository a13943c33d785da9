"""The compressed-leaf (negative-stiffness) pivot driven by a moment, traced by arc-length
continuation through and past the limit point of its moment-rotation curve.

    out = pivot_arclength(pivot)
    out["limit_rotation_rad"], out["limit_moment_Nm"], out["rows"][k]["stable_moment_driven"]

The leaf is clamped ("fixed"); the hub face is free (rotation and translation). The axial
preload P is a fem preload: applied first (load control, the straight leaf) and held while
the moment on the hub, M = lambda M_ref, follows the load factor by arc-length control
(fem.solve_nonlinear(..., preloads=..., control="arc-length")). M_ref = 2 x the elastica's
limit moment, so that lambda peaks near 0.5 and comes back down past the limit point; the
path ends at a hub rotation of ``end_fraction`` theta_max. Per state: the hub rotation and
moment, the elastica's moment at that rotation (:func:`.negative_pivot.compressed_leaf_elastica`)
and the stability of the moment-driven pivot (result.stable: no negative eigenvalue of the
tangent with the hub free), which the limit point changes: a moment-driven pivot is unstable
while dM/dtheta < 0 (its working range: the motor's linkage holds it there) and stable past
the limit point. The limit point (rotation, moment) is the vertex of the parabola M(theta)
through the three path points around the load factor's maximum; the margins are its rotation
over theta_max and its moment over the moment at theta_max (cubic spline of the path). SI units.
"""
import math

import numpy as np
from scipy.interpolate import CubicSpline

from ...fem import Fixed, RigidFace
from ...fem.nonlinear import solve_nonlinear
from .negative_pivot import compressed_leaf_elastica
from .negative_pivot_study import leaf_model, negative_pivot_designs
from .pivot_stability import elastica_limit


def trace_moment_driven(model, P: float, moment_ref: float, theta_end: float, steps: int = 10,
                        preload_steps: int = 2):
    """solve_nonlinear of the leaf: preload P (N) held, hub moment lambda moment_ref (N m)
    continued by arc-length until the hub has turned by theta_end (rad, the sign of
    -moment_ref: the stiffness is negative)."""
    if not (math.isfinite(theta_end) and theta_end > 0):
        raise ValueError(f"theta_end = {theta_end!r} rad must be a finite number > 0")
    sign = -math.copysign(1.0, moment_ref)
    return solve_nonlinear(model, [Fixed("fixed")], [], steps=steps,
                           rigid_faces=[RigidFace("hub", moment=moment_ref)],
                           preloads=[RigidFace("hub", force=(-P, 0.0))],
                           preload_steps=preload_steps, control="arc-length",
                           stop_when=lambda lam, u, faces: sign * faces["hub"][2] >= theta_end)


def parabola_vertex(x, y) -> tuple[float, float]:
    """(x, y) of the vertex of the parabola through three points."""
    a, b, c = np.polyfit(np.asarray(x, float), np.asarray(y, float), 2)
    x0 = -b / (2 * a)
    return float(x0), float(c - b * b / (4 * a))


def path_rows(result, pivot) -> list[dict]:
    """One row per state of the moment-driven path (from the preloaded straight leaf)."""
    E, I, L, P = pivot.material.E, pivot.I, pivot.L, pivot.P
    rows = []
    for k in range(result.preload_end, len(result.load_factors)):
        cx, cy, theta = result.face_motion[k]["hub"]
        elastica = (compressed_leaf_elastica(E, I, L, P, theta) if abs(theta) <= math.pi / 2
                    else None)
        rows.append({"step": k, "load_factor": float(result.load_factors[k]),
                     "theta_rad": float(theta),
                     "moment_fem_Nm": float(result.face_reactions[k]["hub"][2]),
                     "moment_elastica_Nm": elastica.moment if elastica else math.nan,
                     "hub_dx_m": float(cx), "hub_dy_m": float(cy),
                     "negative_eigenvalues": result.negative_eigenvalues[k],
                     "stable_moment_driven": bool(result.stable[k])})
    return rows


def pivot_arclength(pivot, steps: int = 10, end_fraction: float = 6.0) -> dict:
    """The moment-driven compressed leaf by arc-length (see module): rows, limit point,
    margins, the preload stage's largest sideways hub motion (m) and the solve's counts."""
    theta_e, moment_e = elastica_limit(pivot)
    model = leaf_model(pivot, "plane_stress", 2, None)
    result = trace_moment_driven(model, pivot.P, 2.0 * moment_e, end_fraction * pivot.theta_max,
                                 steps)
    rows = path_rows(result, pivot)
    limits = [k for k, _, kind in result.info["limit_points"] if kind == "maximum"]
    if not limits:
        raise RuntimeError("the arc-length path of the compressed leaf has no limit point up to "
                           f"{end_fraction} theta_max")
    k = limits[0] - result.preload_end
    near = rows[k - 1:k + 2]
    theta_l, moment_l = parabola_vertex([r["theta_rad"] for r in near],
                                        [r["moment_fem_Nm"] for r in near])
    spline = moment_spline(rows)
    m_max = float(spline(pivot.theta_max))
    working = [r for r in rows if abs(r["theta_rad"]) <= pivot.theta_max]
    return {"L_m": pivot.L, "P_N": pivot.P, "theta_max_rad": pivot.theta_max,
            "moment_ref_Nm": 2.0 * moment_e, "rows": rows, "limit_step": int(k),
            "limit_rotation_rad": theta_l, "limit_moment_Nm": moment_l,
            "limit_rotation_elastica_rad": theta_e, "limit_moment_elastica_Nm": moment_e,
            "moment_at_theta_max_Nm": m_max,
            "tangent_stiffness_at_theta_max_Nm_per_rad": float(spline(pivot.theta_max, 1)),
            "rotation_margin": theta_l / pivot.theta_max, "moment_margin": moment_l / m_max,
            "moment_driven_unstable_over_working_range":
                all(r["negative_eigenvalues"] == 1 for r in working),
            "preload_hub_dy_max_m": max(abs(m["hub"][1])
                                        for m in result.face_motion[:result.preload_end + 1]),
            "steps": len(rows) - 1, "step_cuts": int(result.info["step_cuts"]),
            "n_dofs": int(model.n_dofs)}


def moment_spline(rows) -> CubicSpline:
    """Cubic spline M(theta) (N m against rad) of the path's first stretch along which theta
    grows."""
    theta = np.array([r["theta_rad"] for r in rows])
    falls = np.flatnonzero(np.diff(theta) <= 0)
    n = int(falls[0]) + 1 if len(falls) else len(rows)
    return CubicSpline(theta[:n], [r["moment_fem_Nm"] for r in rows[:n]])


def against_rotation_control(arc: dict, rotation_rows: list) -> float:
    """Largest |M_arc(theta) - M_rotation(theta)| over |limit moment| at the rotation-
    controlled states (theta > 0) within the arc-length path (cubic spline of the path)."""
    spline = moment_spline(arc["rows"])
    top = spline.x[-1]
    diffs = [abs(float(spline(r["theta_rad"])) - r["moment_fem_Nm"]) for r in rotation_rows
             if 0 < r["theta_rad"] <= top]
    return max(diffs) / abs(arc["limit_moment_Nm"]) if diffs else math.nan


def arclength_curves(quick: bool = False) -> list[dict]:
    """:func:`pivot_arclength` of every negative-stiffness pivot of the balancing robot
    (quick: the first, 8 arc-length steps; else 10), each with its motor."""
    designs = negative_pivot_designs()
    return [{"motor": motor, **pivot_arclength(pivot, steps=8 if quick else 10)}
            for motor, _, _, _, _, pivot in (designs[:1] if quick else designs)]
