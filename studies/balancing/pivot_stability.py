"""Stability of the balancing robot's flexure pivots and the parasitic motion of their hubs.

    out = pivot_stability_study(quick=True)
    out["negative"][0]["limit_rotation_rad"], out["cross"]["rows"][k]["shift_m"]

Negative-stiffness (compressed-leaf) pivots. The leaf carries the dead preload P; the hub is
turned by theta (the motor's linkage holds it) with its translation free. Per rotation, from
the working range to well past it: the hub moment M (N m) beside the elastica closed form
(:func:`.negative_pivot.compressed_leaf_elastica`), the tangent rotational stiffness dM/dtheta
(N m/rad) from the hub's tangent compliance about the state (fem.compliance_matrix, forces
free: 1 / C_tt) and the stability of the state with the hub's rotation held
(result.stable: the reduced tangent positive definite). The moment-rotation curve has a
limit point where dM/dtheta crosses 0: held by a moment instead of a rotation, the pivot
would snap there; ``limit_rotation_rad`` (the stationary point of the cubic Hermite
interpolant of M and dM/dtheta around it) over the working range's
theta_max is the snap margin. The preload margin with the rotation held is the clamped-
guided leaf's buckling load pi^2 E I / L^2 over P = (pi / kL)^2.

The curve is traced by rotation control (each rotation its own solve, preload and rotation
growing together to a state on the stable branch, as negative_pivot_study does), which passes
the limit point of the moment. The same leaf driven by a moment, the preload held and the
moment continued by arc-length, is :mod:`.pivot_arclength`.

Cross-spring pivots: the hub turned by theta (translation free, a pure moment), the motion of
the hub point that sat at the leaves' crossing ("centre shift") against the closed form for
leaves crossing at their middles, derived as Haringx (1949, "The cross-spring pivot as a
constructional element", Appl. Sci. Res. A1:313) and Wittrick (1951, "The properties of
crossed flexure pivots, and the influence of the point at which the strips cross", Aeronaut.
Q. 2:272) do from inextensible Euler-Bernoulli leaves: a hub turning about the crossing bends
each leaf into a circular arc (pure moment), whose chord is shorter by L theta^2 / 6 while the
rotation about the crossing asks L theta^2 / 4; each leaf's end thus sits L theta^2 / 12
further out along the leaf, and the hub moves along the pivot's axis of symmetry (towards the
hub) by

    shift = L theta^2 / (12 cos(alpha / 2)),   alpha the crossing angle,

0.118 L theta^2 at 90 degrees, to second order in theta (no first-order shift when the leaves
cross at their middles). SI units.
"""
import math

import numpy as np
from scipy.optimize import minimize_scalar

from ...fem import Fixed, RigidFace, compliance_matrix
from ...fem.nonlinear import solve_nonlinear
from .negative_pivot import compressed_leaf_elastica
from .negative_pivot_study import leaf_model, negative_pivot_designs
from .pivot_fem import pivot_geometry, pivot_model, positive_stiffness_pivots


def leaf_state(model, P: float, theta: float, steps: int) -> dict:
    """The compressed leaf with the hub turned by ``theta`` (rad) under the dead preload P
    (N): moment (N m), tangent dM/dtheta (N m/rad, hub forces free), stable with the
    rotation held, hub translation (m), peak von Mises (Pa, nodal)."""
    face = RigidFace("hub", rotation=theta, force=(-P, 0.0))
    result = solve_nonlinear(model, [Fixed("fixed")], [], steps=steps, rigid_faces=[face],
                             check_stability=True)
    c = compliance_matrix(model, [Fixed("fixed")], "hub", state=result)
    motion = result.face_motion[-1]["hub"]
    return {"theta_rad": float(theta), "moment_fem_Nm": float(result.face_reactions[-1]["hub"][2]),
            "tangent_stiffness_Nm_per_rad": 1.0 / float(c.matrix[2, 2]),
            "stable_rotation_held": bool(result.stable[-1]),
            "negative_eigenvalues": result.negative_eigenvalues[-1],
            "hub_dx_m": float(motion[0]), "hub_dy_m": float(motion[1]),
            "stress_fem_peak_nodal_Pa": float(result.max_von_mises)}


def hermite_extremum(theta, moment, slope) -> tuple[float, float]:
    """(theta, moment) of the first extremum of the moment-rotation curve: where the slope
    dM/dtheta changes sign, the stationary point of the cubic Hermite interpolant of M and its
    slope on that interval; (nan, nan) if the slope keeps its sign."""
    for k in range(1, len(slope)):
        if slope[k - 1] * slope[k] > 0 or slope[k] == slope[k - 1]:
            continue
        h = theta[k] - theta[k - 1]
        m0, m1, d0, d1 = moment[k - 1], moment[k], slope[k - 1] * h, slope[k] * h
        # p(s) = a s^3 + b s^2 + d0 s + m0 on s in [0, 1]; p'(s) = 3a s^2 + 2b s + d0
        a, b = 2 * (m0 - m1) + d0 + d1, 3 * (m1 - m0) - 2 * d0 - d1
        roots = np.roots([3 * a, 2 * b, d0]) if abs(a) > 0 else np.array([-d0 / (2 * b)])
        s = [float(r.real) for r in np.atleast_1d(roots) if abs(r.imag) < 1e-12
             and -1e-9 <= r.real <= 1 + 1e-9]
        if s:
            u = min(s)
            return (float(theta[k - 1] + u * h),
                    float(a * u ** 3 + b * u ** 2 + d0 * u + m0))
    return math.nan, math.nan


def elastica_limit(pivot) -> tuple[float, float]:
    """(theta (rad), moment (N m)) of the elastica's limit point at the design preload: the
    largest |M| over theta_max..pi/2 (bounded scalar search, ~0.1 s an elastica)."""
    E, I, L, P = pivot.material.E, pivot.I, pivot.L, pivot.P

    def size(theta):
        return -abs(compressed_leaf_elastica(E, I, L, P, theta).moment)
    found = minimize_scalar(size, bounds=(pivot.theta_max, math.pi / 2), method="bounded",
                            options={"xatol": 1e-4})
    return float(found.x), float(compressed_leaf_elastica(E, I, L, P, found.x).moment)


def negative_pivot_limit(pivot, fractions, steps: int = 3) -> dict:
    """Moment-rotation curve of one compressed-leaf pivot at rotations ``fractions`` x
    theta_max, with the elastica's moment, the limit point and the margins (see module)."""
    model = leaf_model(pivot, "plane_stress", 2, None)
    E, I, L, P = pivot.material.E, pivot.I, pivot.L, pivot.P
    rows = []
    for f in fractions:
        row = leaf_state(model, P, f * pivot.theta_max, steps)
        ela = compressed_leaf_elastica(E, I, L, P, row["theta_rad"])
        row.update({"fraction_of_theta_max": float(f), "moment_elastica_Nm": float(ela.moment),
                    "elastica_stable": bool(ela.stable)})
        rows.append(row)
    theta = [r["theta_rad"] for r in rows]
    slopes = [r["tangent_stiffness_Nm_per_rad"] for r in rows]
    limit, limit_moment = hermite_extremum(theta, [r["moment_fem_Nm"] for r in rows], slopes)
    working = [r for r in rows if r["fraction_of_theta_max"] <= 1.0]
    buckling = math.pi ** 2 * E * I / L ** 2
    elastic = elastica_limit(pivot)
    return {"L_m": L, "P_N": P, "kL": pivot.kL, "theta_max_rad": pivot.theta_max,
            "stiffness_design_Nm_per_rad": pivot.stiffness, "rows": rows,
            "limit_rotation_rad": limit, "limit_margin": limit / pivot.theta_max,
            "limit_moment_Nm": limit_moment,
            "limit_rotation_elastica_rad": elastic[0], "limit_moment_elastica_Nm": elastic[1],
            "stable_over_working_range": all(r["stable_rotation_held"] for r in working),
            "tangent_stiffness_at_theta_max_Nm_per_rad":
                float(np.interp(pivot.theta_max, theta, slopes)),
            "preload_buckling_N": buckling, "preload_margin": buckling / P}


def cross_pivot_shift(pivot, steps: int = 6) -> dict:
    """Centre shift (m) of a cross-spring pivot's hub against its rotation, FEM beside the
    closed form L theta^2 / (12 cos(alpha / 2)) (see module); the hub turned to theta_max."""
    geometry = pivot_geometry(pivot)
    model = pivot_model(pivot, "plane_stress", 2, None, geometry)
    result = solve_nonlinear(model, [Fixed("fixed")], [], steps=steps,
                             rigid_faces=[RigidFace("hub", rotation=pivot.theta_max)],
                             check_stability=False)
    half = 0.5 * geometry.crossing_angle
    centre = np.array([0.5 * pivot.L * math.cos(half), 0.0])  # hub-end faces' centroid
    rows = []
    for motion in result.face_motion[1:]:
        cx, cy, theta = motion["hub"]
        R = np.array([[math.cos(theta), -math.sin(theta)], [math.sin(theta), math.cos(theta)]])
        shift = centre + np.array([cx, cy]) - R @ centre  # the crossing point's motion
        closed = float(pivot.L * theta ** 2 / (12.0 * math.cos(half)))
        rows.append({"theta_rad": float(theta), "shift_x_m": float(shift[0]),
                     "shift_y_m": float(shift[1]), "shift_m": float(np.hypot(*shift)),
                     "shift_closed_m": closed,
                     "shift_over_closed": float(shift[0] / closed)})
    return {"L_m": pivot.L, "t_m": pivot.t, "crossing_angle_rad": geometry.crossing_angle,
            "theta_max_rad": pivot.theta_max, "rows": rows,
            "shift_at_theta_max_m": rows[-1]["shift_m"],
            "shift_closed_at_theta_max_m": rows[-1]["shift_closed_m"]}


def pivot_stability_study(quick: bool = False) -> dict:
    """Every negative-stiffness pivot's moment-rotation curve, limit point and margins, and
    the first cross-spring pivot's centre shift. quick: rotations 0.5, 1, 3, 5, 6 theta_max
    (2 load steps each; the limit point is near 4.5 on the default design), the first negative pivot only, 4 rotation steps for the shift."""
    fractions = (0.5, 1.0, 3.0, 5.0, 6.0) if quick else (0.25, 0.5, 1.0, 2.0, 3.0, 4.0, 4.5,
                                                       5.0, 5.5, 6.0)
    designs = negative_pivot_designs()
    negative = []
    for motor, _, _, _, _, pivot in designs[:1] if quick else designs:
        negative.append({"motor": motor, **negative_pivot_limit(pivot, fractions,
                                                                2 if quick else 3)})
    cross = [p for _, _, p in positive_stiffness_pivots() if p.n_leaves == 2]
    out = {"negative": negative}
    if cross:
        out["cross"] = cross_pivot_shift(cross[0], 4 if quick else 8)
    return out
