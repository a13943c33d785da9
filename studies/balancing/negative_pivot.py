"""Negative-stiffness flexure pivots for motors 2 and 4 of the balancing robot (Table IV, K < 0).

A flexure stores energy about its unstressed state, so alone it is a positive spring. A leaf
under an axial compressive force P is not: the force does work as the leaf's tip swings
sideways (the P-delta effect), and past the leaf's own cantilever buckling load the hub
rotation theta costs negative energy. The element here is one leaf (length L, thickness t in
the plane of rotation, width w) clamped to the base at one end and to the hub at the other,
with a constant compressive force P along the leaf's unloaded axis on the hub (a dead load:
in a real part a soft, long, preloaded spring on an axially sliding base, or a constant-force
spring, adjustable). The hub's rotation theta is imposed by the motor (through a transmission
of ratio N: theta = motor angle / N); its translation is free, i.e. no shear force at the hub.

Beam-column (Euler-Bernoulli, inextensible), k^2 = P / (E I), I = w t^3 / 12. Small theta: the
leaf is v'' + k^2 v = (M + P delta) / (E I) with v(0) = v'(0) = 0; the end conditions
v'(L) = theta and zero shear give

    M = (E I / L) (k L) cot(k L) theta                                     (N m)

(the beam-column stiffness with sway and zero end shear; Timoshenko & Gere, Theory of Elastic
Stability, 2nd ed., 1961, Ch. 1, the cantilever beam-column: k L cot k L, and its tension form
k L coth k L). It is E I / L at P = 0 and ~ E I / L - P L / 3 for small P, zero at the
cantilever buckling load (k L = pi / 2) and negative for pi / 2 < k L < pi; k L = pi is the
buckling load of the leaf with theta held (guided end), the end of the usable range. The hub
moves sideways by delta = theta tan(k L / 2) / k (= L / 2 at P = 0), and the peak stress is at
the clamp: sigma = E t theta (k L / sin k L) / (2 L) + P / (w t).

Large theta: the elastica E I phi'' + P sin phi = 0, phi(0) = 0, phi(L) = theta, M = E I phi'(L)
(Timoshenko & Gere, Ch. 2, large deflections of buckled bars), solved here with scipy's
solve_bvp; the branch is stable with theta held when the Jacobi equation
E I eta'' + P cos(phi) eta = 0, eta(0) = 0, eta'(0) = 1 has no zero in (0, L] (the second
variation of int E I phi'^2 / 2 + P cos phi ds is positive).

Sizing. The leaf's volume for a given |K| and rotation at a given stress grows like
(k L / sin k L)^2 / |k L cot k L| = 2 k L / |sin 2 k L|, least at k L = 3 pi / 4 (4.71 times a
pure-bending leaf of the same |K|): the default. SI units throughout.
"""
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.integrate import solve_bvp, solve_ivp
from scipy.optimize import brentq

from ...fem import Fixed, RigidFace
from ...fem.nonlinear import solve_nonlinear
from ...geometry.flexure_pivot import PivotGeometry
from ..engine.tables import write_rows
from .design import default_workspace
from .gravity import load_robot, workspace_torques
from .optimum import optimal_torsion_spring, rms_reduction_pct
from .pivot_fem import pivot_model
from .pivots import FlexureMaterial, flexure_material

KL_DEFAULT = 0.75 * math.pi


def _check_positive(name, value):
    if not (isinstance(value, (int, float, np.floating)) and math.isfinite(value) and value > 0):
        raise ValueError(f"{name} = {value!r} must be a finite number > 0")


def stiffness_factor(kL):
    """f(k L) = k L cot(k L) (compression, kL > 0), 1 at kL = 0; E I f / L is the stiffness."""
    kL = np.asarray(kL, dtype=float)
    small = np.abs(kL) < 1e-6
    safe = np.where(small, 1.0, kL)
    return np.where(small, 1.0 - kL**2 / 3.0, safe / np.tan(safe))


def beam_column_rotational_stiffness(E, I, L, P):
    """Small-angle hub stiffness (N m/rad) of a leaf under compression P (N, >= 0; tension
    < 0): (E I / L) k L cot k L, k^2 = P / (E I); tension gives (E I / L) k L coth k L.
    Raises ValueError at or beyond the guided buckling load P = pi^2 E I / L^2."""
    for name, value in (("E", E), ("I", I), ("L", L)):
        _check_positive(name, value)
    if not math.isfinite(P):
        raise ValueError(f"P = {P!r} must be finite")
    p_guided = math.pi**2 * E * I / L**2
    if P >= p_guided:
        raise ValueError(f"P = {P} N must be < pi^2 E I / L^2 = {p_guided:.6g} N (the leaf "
                         "buckles sideways with its hub rotation held)")
    if P < 0:
        x = math.sqrt(-P / (E * I)) * L
        return E * I / L * (x / math.tanh(x) if x > 1e-6 else 1.0 + x**2 / 3.0)
    return E * I / L * float(stiffness_factor(math.sqrt(P / (E * I)) * L))


def kL_for_stiffness_factor(f):
    """k L in [0, pi) with k L cot k L = f (f <= 1); inverse of :func:`stiffness_factor`."""
    if not (math.isfinite(f) and f <= 1.0):
        raise ValueError(f"stiffness factor f = {f!r} must be <= 1 (compression only lowers it)")
    if f == 1.0:
        return 0.0
    return brentq(lambda x: float(stiffness_factor(x)) - f, 1e-9, math.pi - 1e-12, xtol=1e-14)


def preload_for_stiffness(K, E, I, L):
    """Compressive force P (N) giving the small-angle hub stiffness K (N m/rad, < E I / L)."""
    for name, value in (("E", E), ("I", I), ("L", L)):
        _check_positive(name, value)
    kL = kL_for_stiffness_factor(K * L / (E * I))
    return kL**2 * E * I / L**2


def bending_stress_factor(kL):
    """Clamp moment / tip moment of the straight-branch solution over that of pure bending:
    k L / sin(k L) (1 at kL = 0)."""
    return 1.0 if kL < 1e-6 else kL / math.sin(kL)


@dataclass(frozen=True)
class Elastica:
    """Large-rotation state of the compressed leaf: hub rotation theta (rad), moment (N m),
    clamp curvature (1/m), hub translation dx (axial, m) and dy (sideways, m), and whether
    the branch is stable with theta held (Jacobi test)."""

    theta: float
    moment: float
    clamp_curvature: float
    dx: float
    dy: float
    stable: bool


def compressed_leaf_elastica(E, I, L, P, theta, n_nodes=201) -> Elastica:
    """Solve E I phi'' + P sin phi = 0, phi(0) = 0, phi(L) = theta (inextensible elastica,
    dead compressive P along the unloaded axis, no shear at the hub). SI units."""
    for name, value in (("E", E), ("I", I), ("L", L)):
        _check_positive(name, value)
    if not (math.isfinite(P) and P >= 0):
        raise ValueError(f"P = {P!r} N must be >= 0 (compression)")
    if not (math.isfinite(theta) and abs(theta) <= math.pi / 2):
        raise ValueError(f"theta = {theta!r} rad must be in [-pi/2, pi/2]")
    a = P * L**2 / (E * I)  # (k L)^2
    if a >= math.pi**2:
        raise ValueError(f"P = {P} N must be < pi^2 E I / L^2 = {math.pi**2 * E * I / L**2:.6g} N")
    kL = math.sqrt(a)
    s = np.linspace(0.0, 1.0, n_nodes)
    if kL < 1e-6:
        guess = np.vstack([theta * s, np.full_like(s, theta)])
    else:
        guess = np.vstack([theta * np.sin(kL * s) / math.sin(kL),
                           theta * kL * np.cos(kL * s) / math.sin(kL)])

    def rhs(_, y):
        return np.vstack([y[1], -a * np.sin(y[0])])

    sol = solve_bvp(rhs, lambda ya, yb: np.array([ya[0], yb[0] - theta]), s, guess, tol=1e-10,
                    max_nodes=100_000)
    if not sol.success:
        raise RuntimeError(f"elastica did not converge at theta = {theta}: {sol.message}")
    fine = np.linspace(0.0, 1.0, 4001)
    phi = sol.sol(fine)[0]
    dx = L * (np.trapezoid(np.cos(phi), fine) - 1.0)
    dy = L * np.trapezoid(np.sin(phi), fine)
    jacobi = solve_ivp(lambda x, y: [y[1], -a * math.cos(float(sol.sol(x)[0])) * y[0]],
                       (0.0, 1.0), [0.0, 1.0], rtol=1e-10, atol=1e-12, dense_output=True)
    stable = bool(np.all(jacobi.sol(fine[1:])[0] > 0.0))
    return Elastica(theta=float(theta), moment=float(E * I / L * sol.sol(1.0)[1]),
                    clamp_curvature=float(sol.sol(0.0)[1] / L), dx=float(dx), dy=float(dy),
                    stable=stable)


@dataclass(frozen=True)
class CompressedLeafPivot:
    """A leaf of length L, thickness t, width w (m) under compressive preload P (N) giving the
    hub stiffness ``stiffness`` (N m/rad, < 0) at the pivot; transmission_ratio N (motor
    angle / pivot angle), theta_max (rad, largest pivot rotation), kL = L sqrt(P / E I),
    max_stress (Pa, clamp, beam-column small-angle), safety_factor = yield / max_stress."""

    L: float
    t: float
    w: float
    P: float
    material: FlexureMaterial
    transmission_ratio: float
    theta_max: float
    stiffness: float
    max_stress: float
    safety_factor: float

    def __post_init__(self):
        for attr in ("L", "t", "w", "P", "transmission_ratio", "theta_max", "max_stress",
                     "safety_factor"):
            _check_positive(attr, getattr(self, attr))
        if not self.t <= 0.2 * self.L:
            raise ValueError(f"t = {self.t} m must be <= L / 5 = {0.2 * self.L} m (a leaf)")
        if not self.kL < math.pi:
            raise ValueError(f"P = {self.P} N must be < pi^2 E I / L^2 (kL = {self.kL:.4g} "
                             ">= pi: the leaf buckles sideways)")

    @property
    def I(self) -> float:
        """Second moment of area w t^3 / 12 (m^4)."""
        return self.w * self.t**3 / 12.0

    @property
    def kL(self) -> float:
        return self.L * math.sqrt(self.P / (self.material.E * self.I))

    @property
    def stiffness_at_motor(self) -> float:
        """K / N^2 (N m/rad)."""
        return self.stiffness / self.transmission_ratio**2

    def as_dict(self) -> dict:
        return {"L_m": self.L, "t_m": self.t, "w_m": self.w, "P_N": self.P, "kL": self.kL,
                "material": self.material.name, "transmission_ratio": self.transmission_ratio,
                "theta_max_rad": self.theta_max, "stiffness_Nm_per_rad": self.stiffness,
                "stiffness_at_motor_Nm_per_rad": self.stiffness_at_motor,
                "max_stress_Pa": self.max_stress, "safety_factor": self.safety_factor}


def compressed_leaf_stress(E, t, w, L, P, theta):
    """Small-angle peak stress (Pa) at the clamp: E t theta (kL / sin kL) / (2 L) + P / (w t)."""
    kL = L * math.sqrt(P / (E * w * t**3 / 12.0))
    return E * t * abs(theta) * bending_stress_factor(kL) / (2.0 * L) + P / (w * t)


def size_negative_pivot(K, theta_range_rad, material: FlexureMaterial, safety_factor=2.0,
                        transmission_ratio=1.0, kL=KL_DEFAULT, max_width=0.1, lengths=None,
                        thickness_step=1e-5) -> CompressedLeafPivot:
    """Size a compressed leaf of motor-side stiffness K < 0 (N m/rad) over a motor rotation
    range theta_range_rad (rad, from the leaf's straight state), transmission_ratio N.

    For each leaf length L (m, shortest first) the thickness is the largest multiple of
    thickness_step (m) whose clamp stress at theta_max = max|range| / N stays below
    yield / safety_factor at the chosen k L, the width follows from
    (E w t^3 / 12 L) kL cot kL = N^2 K and the preload from P = kL^2 E I / L^2. The first L
    with t <= w <= max_width is returned. Raises ValueError for K >= 0, kL outside
    (pi/2, pi), or when no length fits.
    """
    if not K < 0.0:
        raise ValueError(f"K = {K} N m/rad must be < 0 (use size_flexure_pivot for K > 0)")
    if not (math.pi / 2 < kL < math.pi):
        raise ValueError(f"kL = {kL!r} must be in (pi/2, pi): negative stiffness, below the "
                         "guided buckling load")
    if not safety_factor >= 1.0:
        raise ValueError(f"safety_factor = {safety_factor} must be >= 1")
    _check_positive("transmission_ratio", transmission_ratio)
    theta_max = float(np.max(np.abs(theta_range_rad))) / transmission_ratio
    if not theta_max > 0.0:
        raise ValueError(f"theta_range_rad = {theta_range_rad} must not be all zero")
    k_pivot = K * transmission_ratio**2
    E, allowable = material.E, material.yield_strength / safety_factor
    f, b = float(stiffness_factor(kL)), bending_stress_factor(kL)
    if lengths is None:
        lengths = np.arange(0.02, 0.4001, 0.005)
    for L in lengths:
        # allowable = E (t/L) theta b / 2 + kL^2 E (t/L)^2 / 12: a quadratic in t / L
        qa, qb = kL**2 * E / 12.0, E * theta_max * b / 2.0
        ratio = (-qb + math.sqrt(qb**2 + 4.0 * qa * allowable)) / (2.0 * qa)
        t = math.floor(ratio * L / thickness_step) * thickness_step
        if t <= 0.0 or t > 0.2 * L:
            continue
        w = 12.0 * k_pivot * L / (f * E * t**3)
        if t <= w <= max_width:
            P = kL**2 * E * w * t**3 / (12.0 * L**2)
            stress = compressed_leaf_stress(E, t, w, L, P, theta_max)
            return CompressedLeafPivot(L=float(L), t=float(t), w=float(w), P=float(P),
                                       material=material,
                                       transmission_ratio=float(transmission_ratio),
                                       theta_max=theta_max, stiffness=float(k_pivot),
                                       max_stress=float(stress),
                                       safety_factor=float(material.yield_strength / stress))
    raise ValueError(
        f"no compressed leaf with L in [{lengths[0]:.3f}, {lengths[-1]:.3f}] m and width <= "
        f"max_width = {max_width} m gives K = {K} N m/rad over theta_max = {theta_max:.3f} rad "
        f"({material.name}, safety factor {safety_factor}, N = {transmission_ratio}, kL = {kL:.3f})")


# ---------------------------------------------------------------- FEM check (large deflection)

def _leaf_model(pivot: CompressedLeafPivot, formulation, elements_through_thickness, nu):

    geometry = PivotGeometry("single", pivot.L, pivot.t)
    return pivot_model(pivot, formulation, elements_through_thickness, nu, geometry)


def _hub_state(model, P, theta, steps):
    """(moment (N m), (dx, dy) (m), result) with the hub turned by theta under the dead load P;
    preload and rotation grow together (a conservative system: the end state is that of
    preloading first, on the branch the Jacobi test shows to be the only stable one)."""

    result = solve_nonlinear(model, [Fixed("fixed")], [], steps=steps,
                             rigid_faces=[RigidFace("hub", rotation=theta, force=(-P, 0.0))])
    motion = result.face_motion[-1]["hub"]
    return float(result.face_reactions[-1]["hub"][2]), (float(motion[0]), float(motion[1])), result


def plate_modulus(E, nu):
    """E / (1 - nu^2) (Pa): the bending modulus of a leaf much wider than sqrt(R t)."""
    return E / (1.0 - nu**2)


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
    model = _leaf_model(pivot, formulation, elements_through_thickness, nu)
    E = pivot.material.E
    if formulation == "plane_strain":
        E = plate_modulus(E, model.material.nu)
    P = pivot.P if P is None else float(P)
    I, L = pivot.I, pivot.L
    k_closed = beam_column_rotational_stiffness(E, I, L, P)
    m_small, _, _ = _hub_state(model, P, small_angle, 2)
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
        moment, (_, dy), result = _hub_state(model, P, theta, steps)
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
        pivot = size_negative_pivot(spring.K, (-half, half), flexure_material(material),
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
    figure = "balancing_negative_pivot.png"
    plot_negative_pivots(out_dir / figure, rows)
    return {"rows": rows, "tables": [table], "figures": [figure]}


def plot_negative_pivots(path, rows: list):
    """Hub moment (N m) vs pivot rotation (deg): linear K theta, elastica, FEM; one panel per
    motor."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

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
        ax.set_xlabel("pivot rotation (deg)")
        ax.set_ylabel("moment on the hub (N m)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
