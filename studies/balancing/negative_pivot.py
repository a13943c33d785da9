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

The FEM check and the motors' study are in :mod:`.negative_pivot_study`.
"""
import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_bvp, solve_ivp
from scipy.optimize import brentq

from ...fem import Material
from ...fem.checks import positive
from .pivots import LeafPivot, no_leaf_fits, pivot_rotation

KL_DEFAULT = 0.75 * math.pi


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
        positive(name, value)
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
        positive(name, value)
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
        positive(name, value)
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
class CompressedLeafPivot(LeafPivot):
    """A leaf (a :class:`~.pivots.LeafPivot`) under compressive preload P (N) giving the hub
    stiffness ``stiffness`` (N m/rad, < 0) at the pivot; kL = L sqrt(P / E I); max_stress at
    the clamp (beam-column, small-angle)."""

    P: float

    def __post_init__(self):
        for attr in ("L", "t", "w", "P", "transmission_ratio", "theta_max", "max_stress",
                     "safety_factor"):
            positive(attr, getattr(self, attr))
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

    def as_dict(self) -> dict:
        return self.row(P_N=self.P, kL=self.kL)


def compressed_leaf_stress(E, t, w, L, P, theta):
    """Small-angle peak stress (Pa) at the clamp: E t theta (kL / sin kL) / (2 L) + P / (w t)."""
    kL = L * math.sqrt(P / (E * w * t**3 / 12.0))
    return E * t * abs(theta) * bending_stress_factor(kL) / (2.0 * L) + P / (w * t)


def size_negative_pivot(K, theta_range_rad, material: Material, safety_factor=2.0,
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
    theta_max = pivot_rotation(theta_range_rad, transmission_ratio, safety_factor)
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
    raise no_leaf_fits("compressed leaf", lengths, max_width, K, theta_max,
                       f"{material.name}, safety factor {safety_factor}, N = "
                       f"{transmission_ratio}, kL = {kL:.3f}")


def plate_modulus(E, nu):
    """E / (1 - nu^2) (Pa): the bending modulus of a leaf much wider than sqrt(R t)."""
    return E / (1.0 - nu**2)
