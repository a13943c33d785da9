"""RMS-optimal partial static balancing of one motor (Lessard et al., IFToMM 2007, Eqs. 13-26).

For a motor with gravity torques tau_i (N m) at angles q_i (rad) over the workspace samples,
each balancer adds a torque tau_k(q) and its parameters minimise f = sum (tau + tau_k)^2
(Eq. 16). Angles in rad, torques in N m, stiffness in N m/rad.
"""
from dataclasses import dataclass, fields

import numpy as np

# ---------------------------------------------------------------- balancer torques

def spring_torque(q, C, q_k):
    """Zero-free-length spring on the arm, Eq. 15: C sin(q - q_k) with C = K l_k z_k (N m)."""
    return C * np.sin(q - q_k)


def torsion_spring_torque(q, K, q_k):
    """Torsion spring on the motor axis, Eq. 20: K (q_k - q) (N m; K in N m/rad)."""
    return K * (q_k - q)


def counterweight_torque(q, C, q_c):
    """Counterweight on the arm, Eq. 26: -C sin(q - q_c) with C = M l_c g (N m)."""
    return -C * np.sin(q - q_c)


def rms_reduction_pct(tau, tau_balanced):
    """Reduction of the RMS torque over the workspace (%), 100 (1 - RMS_bal / RMS)."""
    return 100.0 * (1.0 - np.sqrt(np.mean(tau_balanced**2) / np.mean(tau**2)))


def max_reduction_pct(tau, tau_balanced):
    """Reduction of the largest |torque| over the workspace (%)."""
    return 100.0 * (1.0 - np.max(np.abs(tau_balanced)) / np.max(np.abs(tau)))


# ---------------------------------------------------------------- spring (Eqs. 16-19, App. 2)

def spring_polynomial(q, tau):
    """Coefficients [a6, ..., a0] of the sextic p(t) of Appendix 2 (highest power first).

    Its real roots t give the stationary fixed-arm angles q_k = 2 arctan(t) (Eq. 18).
    """
    s, c = np.sin(q), np.cos(q)
    b0, b1 = -np.sum(tau * s), np.sum(tau * c)
    b2, b3, b4 = np.sum(s * s), np.sum(c * c), -2.0 * np.sum(c * s)
    b5 = np.sum(tau * b2 * c + b0 * c * s)
    b6 = np.sum(tau * b3 * s - b1 * c * s)
    b7 = np.sum(tau * (b4 * c + b2 * s) + b0 * (s * s - c * c) + b1 * c * s)
    b8 = np.sum(tau * (b3 * c + b4 * s) + b1 * (s * s - c * c) - b0 * c * s)
    a0, a1, a2, a3 = b5, 2.0 * b7, -3.0 * b5 + 4.0 * b8, -4.0 * b7 + 8.0 * b6
    return np.array([-a0, a1, -a2, a3, a2, a1, a0])


def spring_constant_for_angle(q, tau, q_k):
    """The best C (N m) for a fixed-arm angle q_k (rad), Eq. 19."""
    s = np.sin(q - q_k)
    return -np.sum(tau * s) / np.sum(s * s)


class Balancer:
    """A balancer given by its dataclass fields: ``torque(q)`` (N m at the motor angles q,
    rad) by its torque law ``law(q, *fields)``, ``params()`` {keys: fields}."""

    law = None   # staticmethod(torque law (q, *fields) -> N m) in each balancer
    keys = ()    # the params() names of its fields

    def values(self) -> list:
        return [getattr(self, f.name) for f in fields(self)]

    def torque(self, q):
        return self.law(q, *self.values())

    def params(self) -> dict:
        return dict(zip(self.keys, self.values()))


@dataclass(frozen=True)
class SpringBalance(Balancer):
    """Zero-free-length spring: C (N m) and fixed-arm angle q_k (rad), Eq. 15."""

    C: float
    q_k: float
    law, keys = staticmethod(spring_torque), ("C_Nm", "q_k_rad")


def optimal_spring(q, tau) -> SpringBalance:
    """RMS-optimal zero-free-length spring through the roots of Appendix 2 (Eqs. 18-19).

    Every real root is tried; the one with the least f and C > 0 (the sign the paper
    tabulates; q_k and q_k + pi with -C are the same spring torque) is returned.
    """
    roots = np.roots(spring_polynomial(q, tau))
    real = roots[np.abs(roots.imag) <= 1e-9 * np.maximum(1.0, np.abs(roots))].real
    candidates = list(2.0 * np.arctan(real)) + [np.pi]          # t -> infinity is q_k = pi
    best = None
    for q_k in candidates:
        C = spring_constant_for_angle(q, tau, q_k)
        f = np.sum((tau + spring_torque(q, C, q_k)) ** 2)
        if best is None or f < best[0] * (1.0 - 1e-12):
            best = (f, C, q_k)
    _, C, q_k = best
    if C < 0.0:
        C, q_k = -C, q_k + np.pi
    return SpringBalance(C=float(C), q_k=float(np.angle(np.exp(1j * q_k))))


# ---------------------------------------------------------------- torsion spring (Eqs. 21-24)

@dataclass(frozen=True)
class TorsionBalance(Balancer):
    """Torsion spring: stiffness K (N m/rad) and free angle q_k (rad), Eq. 20."""

    K: float
    q_k: float
    law, keys = staticmethod(torsion_spring_torque), ("K_Nm_per_rad", "q_k_rad")


def optimal_torsion_spring(q, tau) -> TorsionBalance:
    """RMS-optimal torsion spring, q_k by Eq. 23 and K by Eq. 24 (N = number of samples)."""
    N = q.size
    st, sq, stq, sq2 = np.sum(tau), np.sum(q), np.sum(tau * q), np.sum(q * q)
    q_k = (stq * sq - st * sq2) / (N * stq - st * sq)                       # Eq. 23
    K = -np.sum(tau * (q_k - q)) / np.sum((q_k - q) ** 2)                   # Eq. 24
    return TorsionBalance(K=float(K), q_k=float(q_k))


# ---------------------------------------------------------------- counterweight (Eqs. 25-26)

@dataclass(frozen=True)
class CounterweightBalance(Balancer):
    """Counterweight: C = M l_c g (N m) and angle q_c (rad), Eq. 26."""

    C: float
    q_c: float
    law, keys = staticmethod(counterweight_torque), ("C_Nm", "q_c_rad")


def optimal_counterweight(q, tau) -> CounterweightBalance:
    """RMS-optimal counterweight: the spring problem with q_c = q_k - pi (Section V.C).

    -C sin(q - q_k + pi) = C sin(q - q_k), so the optimum is the spring's; q_c is returned
    in (-2 pi, 0] as Table V prints it.
    """
    spring = optimal_spring(q, tau)
    q_c = np.angle(np.exp(1j * (spring.q_k - np.pi)))
    return CounterweightBalance(C=spring.C, q_c=float(q_c if q_c <= 0.0 else q_c - 2 * np.pi))


# ---------------------------------------------------------------- beyond the paper

@dataclass(frozen=True)
class SpringTorsionBalance:
    """A zero-free-length spring (C, q_k) and a torsion spring (K, q_t) on the same motor."""

    spring: SpringBalance
    torsion: TorsionBalance

    def torque(self, q):
        return self.spring.torque(q) + self.torsion.torque(q)

    def params(self) -> dict:
        return {"C_Nm": self.spring.C, "q_k_rad": self.spring.q_k,
                "K_Nm_per_rad": self.torsion.K, "q_t_rad": self.torsion.q_k}


def optimal_spring_and_torsion(q, tau) -> SpringTorsionBalance:
    """Spring plus torsion spring minimising f: linear least squares in sin q, cos q, q, 1.

    C sin(q - q_k) = u sin q + v cos q and K (q_t - q) = K q_t - K q are linear in
    (u, v, K, K q_t), so the four-variable optimum is global and closed-form. (Two springs,
    or a spring and a counterweight, add nothing: a sum of sin(q - phi) is again one.)
    """
    basis = np.column_stack([np.sin(q), np.cos(q), -q, np.ones_like(q)])
    (u, v, K, Kq), *_ = np.linalg.lstsq(basis, -tau, rcond=None)
    C, q_k = np.hypot(u, v), np.arctan2(-v, u)
    return SpringTorsionBalance(SpringBalance(float(C), float(q_k)),
                                TorsionBalance(float(K), float(Kq / K)))


def optimal_coupled_springs(q_a, q_b, tau_a, tau_b):
    """Two motors of one five-bar: a spring on each arm plus a zero-free-length spring
    joining the two arms, minimising f_a + f_b.

    A spring of stiffness k between points at l_a, l_b along arms a, b adds (beyond terms in
    sin q, cos q that the arm springs absorb) the torques c sin(q_a - q_b) on motor a and
    -c sin(q_a - q_b) on motor b, c = k l_a l_b (N m). Returns (balance_a, balance_b, c):
    the arm springs as SpringBalance and c in N m; global (linear least squares).
    """
    n = q_a.size
    d = np.sin(q_a - q_b)
    zeros = np.zeros(n)
    rows_a = np.column_stack([np.sin(q_a), np.cos(q_a), zeros, zeros, d])
    rows_b = np.column_stack([zeros, zeros, np.sin(q_b), np.cos(q_b), -d])
    x, *_ = np.linalg.lstsq(np.vstack([rows_a, rows_b]), -np.concatenate([tau_a, tau_b]),
                            rcond=None)
    ua, va, ub, vb, c = x
    return (SpringBalance(float(np.hypot(ua, va)), float(np.arctan2(-va, ua))),
            SpringBalance(float(np.hypot(ub, vb)), float(np.arctan2(-vb, ub))), float(c))
