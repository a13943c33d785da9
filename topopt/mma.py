"""One step of the method of moving asymptotes (Svanberg 1987, "The method of moving
asymptotes - a new method for structural optimization", IJNME 24:359-373,
doi:10.1002/nme.1620240207) as mmapy's ``mmasub`` takes it, with its defaults (asyinit 0.5,
asyincr 1.2, asydecr 0.7, albefa 0.1, raa0 1e-5, epsimin 1e-7; a0 = 1, a = 0, c = 1000,
d = 1): the same asymptotes, move limits, convex approximation and primal-dual Newton
iterations, written again for speed.

Why not ``mmasub`` itself: at 20,000 variables it takes 60-150 ms a step, mostly outside
its arithmetic (diagonal matrices built by scipy.sparse, the residual vectors concatenated
twice a Newton step, copies); this takes the same 30-40 Newton steps in a third of the time.
Why not an exact solution of the subproblem (its dual, m multipliers): ``mmasub``'s answer
is not the subproblem's optimum but the interior point's at barrier 1e-7, up to 1e-2 away
from it for variables with no sensitivity, which the barrier pulls to the middle of their
move window; on the force inverter that drift is what brings a design whose output has come
loose (all sensitivities zero) back to life, and the exact step stops there. Checked
against ``mmapy.mmasub`` step by step (tests/topopt/test_mma.py)."""
from dataclasses import dataclass

import numpy as np

ASYINIT, ASYINCR, ASYDECR, ASYMIN, ASYMAX = 0.5, 1.2, 0.7, 0.01, 10.0
ALBEFA, RAA0, C, D = 0.1, 1e-5, 1000.0, 1.0


@dataclass
class MMAState:
    """What MMA carries from one iteration to the next (vectors of n)."""

    xold1: np.ndarray
    xold2: np.ndarray
    low: np.ndarray
    upp: np.ndarray

    def __post_init__(self):
        for key in ("xold1", "xold2", "low", "upp"):  # states saved as (n, 1) columns too
            setattr(self, key, np.asarray(getattr(self, key), dtype=float).ravel())

    @classmethod
    def start(cls, z: np.ndarray) -> "MMAState":
        return cls(z.copy(), z.copy(), np.zeros_like(z), np.ones_like(z))


@dataclass
class Subproblem:
    """min sum p0/(upp - x) + q0/(x - low) + sum(c y + d y^2 / 2) subject to
    sum_j P_ij/(upp_j - x_j) + Q_ij/(x_j - low_j) - y_i <= b_i, alfa <= x <= beta, y >= 0."""

    low: np.ndarray
    upp: np.ndarray
    alfa: np.ndarray
    beta: np.ndarray
    p0: np.ndarray
    q0: np.ndarray
    P: np.ndarray   # (m, n)
    Q: np.ndarray
    b: np.ndarray   # (m,)


def asymptotes(state: MMAState, iteration: int, x: np.ndarray, xmin, xmax):
    """mmasub's (low, upp) at ``iteration`` (from 1)."""
    span = xmax - xmin
    if iteration <= 2:
        return x - ASYINIT * span, x + ASYINIT * span
    trend = (x - state.xold1) * (state.xold1 - state.xold2)
    factor = np.where(trend > 0, ASYINCR, np.where(trend < 0, ASYDECR, 1.0))
    low = np.clip(x - factor * (state.xold1 - state.low), x - ASYMAX * span, x - ASYMIN * span)
    upp = np.clip(x + factor * (state.upp - state.xold1), x + ASYMIN * span, x + ASYMAX * span)
    return low, upp


def subproblem(x, low, upp, df0, fval, dfdx, xmin, xmax, move) -> Subproblem:
    """mmasub's convex approximation at x (fval: (m,), dfdx: (m, n))."""
    span = xmax - xmin
    alfa = np.maximum(np.maximum(low + ALBEFA * (x - low), x - move * span), xmin)
    beta = np.minimum(np.minimum(upp - ALBEFA * (upp - x), x + move * span), xmax)
    reg = RAA0 / np.maximum(span, 1e-5)
    ux2, xl2 = (upp - x) ** 2, (x - low) ** 2
    p0, q0 = np.maximum(df0, 0.0), np.maximum(-df0, 0.0)
    pq0 = 0.001 * (p0 + q0) + reg
    P, Q = np.maximum(dfdx, 0.0), np.maximum(-dfdx, 0.0)
    PQ = 0.001 * (P + Q) + reg
    P, Q = (P + PQ) * ux2, (Q + PQ) * xl2
    b = P @ (1.0 / (upp - x)) + Q @ (1.0 / (x - low)) - fval
    return Subproblem(low, upp, alfa, beta, (p0 + pq0) * ux2, (q0 + pq0) * xl2, P, Q, b)


def _terms(s: Subproblem, x: np.ndarray, lam: np.ndarray) -> tuple:
    """What the residual and the Newton step share at (x, lam): x - alfa, beta - x,
    1/(upp - x), 1/(x - low), p0 + lam P, q0 + lam Q and the constraints' terms
    sum P/(upp - x) + Q/(x - low)."""
    xa, bx = x - s.alfa, s.beta - x
    iu, il = 1.0 / (s.upp - x), 1.0 / (x - s.low)
    plam, qlam = s.p0 + np.dot(lam, s.P), s.q0 + np.dot(lam, s.Q)
    return xa, bx, iu, il, plam, qlam, s.P @ iu + s.Q @ il


def _residual(s: Subproblem, pt: tuple, t: tuple, epsi: float):
    """(2-norm, max-norm) of the perturbed optimality conditions at the point
    pt = (x, y, z, lam, xsi, eta, mu, zet, sl) with its terms t, as mmapy's subsolv forms
    them."""
    x, y, z, lam, xsi, eta, mu, zet, sl = pt
    xa, bx, iu, il, plam, qlam, g = t
    rx = plam * iu
    rx *= iu
    rx -= qlam * il * il
    rx += eta - xsi
    rxsi, reta = xsi * xa, eta * bx
    rxsi -= epsi
    reta -= epsi
    small = np.concatenate([C + D * y - mu - lam, mu * y - epsi, g - y + sl - s.b,
                            lam * sl - epsi, [1.0 - zet, zet * z - epsi]])
    norm = np.sqrt(rx @ rx + rxsi @ rxsi + reta @ reta + small @ small)
    largest = max(max(v.max(), -v.min()) for v in (rx, rxsi, reta, small))
    return norm, largest


def _direction(s: Subproblem, pt: tuple, t: tuple, epsi: float) -> tuple:
    """The Newton direction of the perturbed optimality conditions (mmapy's subsolv, its
    m < n branch with a = 0)."""
    x, y, z, lam, xsi, eta, mu, zet, sl = pt
    xa, bx, iu, il, plam, qlam, g = t
    ixa, ibx = 1.0 / xa, 1.0 / bx
    pu2, ql2 = plam * iu * iu, qlam * il * il
    delx = pu2 - ql2 + epsi * (ibx - ixa)
    diagx = pu2 * iu
    diagx += ql2 * il
    diagx *= 2.0
    diagx += xsi * ixa + eta * ibx
    idiag = 1.0 / diagx
    dely = C + D * y - lam - epsi / y
    diagy = D + mu / y
    GG = s.P * (iu * iu) - s.Q * (il * il)
    GD = GG * idiag
    A = GD @ GG.T + np.diag(sl / lam + 1.0 / diagy)
    dlam = np.linalg.solve(A, g - y - s.b + epsi / lam + dely / diagy - GD @ delx)
    dz = -(1.0 - epsi / z) * z / zet
    dx = delx + np.dot(dlam, GG)
    dx *= -idiag
    dy = (dlam - dely) / diagy
    dxsi = (epsi - xsi * dx) * ixa - xsi
    deta = (epsi + eta * dx) * ibx - eta
    return (dx, dy, dz, dlam, dxsi, deta, -mu + (epsi - mu * dy) / y,
            -zet + (epsi - zet * dz) / z, -sl + (epsi - sl * dlam) / lam), (ixa, ibx)


def _step_length(pt: tuple, dpt: tuple, inverse: tuple) -> float:
    """The longest step (at most 1) keeping every variable 1 % inside its bounds."""
    dx, (ixa, ibx) = dpt[0], inverse
    longest = max(np.max(-dx * ixa), np.max(dx * ibx))
    for v, dv in zip(pt[1:], dpt[1:]):
        longest = max(longest, float(np.max(-dv / v)))
    return 1.0 / max(1.01 * longest, 1.0)


def subsolv(s: Subproblem, epsimin: float = 1e-7) -> np.ndarray:
    """x of the subproblem by mmapy's primal-dual Newton method, step for step: the
    barrier parameter from 1 down to ``epsimin`` by factors of 10, at each up to 200 Newton
    steps until the largest residual is below 0.9 of it, each step halved (up to 50 times)
    until the residual's norm decreases."""
    m, n = s.P.shape
    x = 0.5 * (s.alfa + s.beta)
    pt = (x, np.ones(m), 1.0, np.ones(m), np.maximum(1.0 / (x - s.alfa), 1.0),
          np.maximum(1.0 / (s.beta - x), 1.0), np.full(m, max(1.0, 0.5 * C)), 1.0, np.ones(m))
    t = _terms(s, x, pt[3])
    epsi = 1.0
    while epsi > epsimin:
        norm, largest = _residual(s, pt, t, epsi)
        for _ in range(200):
            if largest <= 0.9 * epsi:
                break
            dpt, inverse = _direction(s, pt, t, epsi)
            step = _step_length(pt, dpt, inverse)
            new_norm = 2.0 * norm
            for _ in range(50):
                if new_norm <= norm:
                    break
                trial = tuple(v + step * dv for v, dv in zip(pt, dpt))
                t = _terms(s, trial[0], trial[3])
                new_norm, largest = _residual(s, trial, t, epsi)
                step /= 2.0
            pt, norm = trial, new_norm
        epsi *= 0.1
    return pt[0]


def _mmapy_subsolv(s: Subproblem) -> np.ndarray:
    """mmapy's own subsolv, for the case m >= n that :func:`subsolv` does not cover."""
    from mmapy import subsolv as mmapy_subsolv

    m, n = s.P.shape
    col = [v.reshape(-1, 1) for v in (s.low, s.upp, s.alfa, s.beta, s.p0, s.q0)]
    return mmapy_subsolv(m, n, 1e-7, *col, s.P, s.Q, 1.0, np.zeros((m, 1)), s.b.reshape(-1, 1),
                         np.full((m, 1), C), np.full((m, 1), D))[0].ravel()


def mma_update(state: MMAState, iteration: int, z, f0, df0, fvals, dfdx, lower, upper,
               move: float) -> np.ndarray:
    """The next design variables of min f0 s.t. fvals <= 0 (normalised constraints, their
    gradients the rows of dfdx); ``iteration`` counts from 1; updates ``state`` in place.
    The variables' box is [0, 1]; pinned variables are clipped to [lower, upper] after."""
    n = z.size
    xmin, xmax = np.zeros(n), np.ones(n)
    fval = np.asarray(fvals, dtype=float).ravel() if len(fvals) else -np.ones(1)
    dfdx = np.asarray(dfdx, dtype=float).reshape(len(fvals), n) if len(fvals) else np.zeros((1, n))
    low, upp = asymptotes(state, iteration, z, xmin, xmax)
    sub = subproblem(z, low, upp, np.asarray(df0, dtype=float), fval, dfdx, xmin, xmax, move)
    x = subsolv(sub) if fval.size < n else _mmapy_subsolv(sub)
    state.xold2, state.xold1 = state.xold1, z.copy()
    state.low, state.upp = low, upp
    return np.clip(x, lower, upper)
