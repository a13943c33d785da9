"""Arc-length continuation for ``solve_nonlinear(..., control="arc-length")``.

The load factor lambda becomes an unknown beside the reduced unknowns z (lengths, m), and
each step advances a fixed distance ds along the equilibrium path in z (cylindrical arc
length, Crisfield 1981, "A fast incremental/iterative solution procedure that handles
snap-through", Comput. Struct. 13:55): the tangent predictor dz = dlambda K^-1 q, q =
-dR/dlambda, in the direction of the previous increment (so the path is followed through
limit points, where lambda turns back), then corrections constrained to the plane normal to
the current increment (Riks-Wempner, updated normal plane). The last step lands on
lambda = 1 by load control (or ends earlier where the caller says). Preloads
(:mod:`.preload`) stay constant: the path starts from the preloaded state and only the scaled
loads follow lambda. Limit points (local extremes of lambda along the path) are reported in
``result.info["limit_points"]``.
"""
import math

import numpy as np

from .factor import SingularStiffness, factor
from .stepping import StepFailed
from .newton import NonConvergenceError, newton, newton_step


def _load_direction(problem, z, lam, rz) -> np.ndarray:
    """q = -dR/dlambda (N) by a forward difference (exact for dead loads and prescribed
    translations, which enter linearly)."""
    h = 1e-6 * max(1.0, abs(lam))
    return -(problem.evaluate(z, lam + h, tangent=False)[2] - rz) / h


def _solve2(K, a, b, kind="symmetric"):
    try:
        with factor(K, kind) as F:
            x = F.solve(np.column_stack([a, b]))
    except (RuntimeError, SingularStiffness) as error:
        raise StepFailed(f"the tangent is singular ({error})", []) from None
    if not np.all(np.isfinite(x)):
        raise StepFailed("the tangent is singular (non-finite increment)", [])
    return x[:, 0], x[:, 1]


def arc_step(problem, z, lam, ds, previous, max_iterations, tol):
    """One converged arc-length step of length ``ds`` (m) from (z, lam), continuing the
    direction ``previous`` (the last increment of z): (z, lam, u, r, iterations)."""
    _, _, rz, K, _, _, _ = problem.evaluate(z, lam)
    _, dz_t = _solve2(K, np.zeros_like(rz), _load_direction(problem, z, lam, rz),
                      problem.matrix_kind)
    sign = 1.0 if float(dz_t @ previous) >= 0 else -1.0
    dlam = sign * ds / max(np.linalg.norm(dz_t), 1e-300)
    Dz, Dlam = dlam * dz_t, dlam

    def residual(x):
        zc, lc = z + x[0], lam + x[1]
        u, r, rz, K, reference, _, _ = problem.evaluate(zc, lc)
        return rz, reference, (zc, lc, u, r, K)

    def correction(x, rz, state):
        zc, lc, _, _, K = state
        a, b = _solve2(K, -rz, _load_direction(problem, zc, lc, rz), problem.matrix_kind)
        denominator = 2.0 * float(x[0] @ b)
        if denominator == 0:
            raise StepFailed("the arc-length constraint is degenerate", [])
        dl = (ds ** 2 - float(x[0] @ x[0]) - 2.0 * float(x[0] @ a)) / denominator
        return a + dl * b, dl

    def converged(x, d, size, reference, state):
        return d is not None and size <= tol * reference and \
            np.linalg.norm(d[0]) <= math.sqrt(tol) * max(np.linalg.norm(state[2]), 1e-300)

    # fem/newton.py's driver on (Dz, Dlam): max_iterations evaluations of the residual
    found = newton((Dz, Dlam), residual, correction, tol=tol, max_iterations=max_iterations - 1,
                   update=lambda x, d: (x[0] + d[0], x[1] + d[1]), converged=converged)
    zc, lc, u, r, _ = found.state
    return zc, lc, u, r, found.iterations + 1


def limit_points(load_factors) -> list:
    """[(step, load factor, 'maximum' | 'minimum')] where lambda turns along the path."""
    lam = np.asarray(load_factors)
    out = []
    for k in range(1, len(lam) - 1):
        before, after = lam[k] - lam[k - 1], lam[k + 1] - lam[k]
        if before * after < 0:
            out.append((k, float(lam[k]), "maximum" if before > 0 else "minimum"))
    return out


def trace(problem, steps, max_iterations, tol, min_step, max_steps, on_step, z0=None):
    """Follow the path from the converged state ``z0`` at lambda = 0 (default unloaded; a
    preloaded state otherwise) to lambda = 1; ``on_step(z, lam, u, r, iterations)`` records
    each converged point and ends the trace when it returns true. Returns the number of step
    cuts."""
    z, lam = (np.zeros(problem.space.n) if z0 is None else z0), 0.0
    _, _, rz, K, _, _, _ = problem.evaluate(z, lam)
    _, dz_t = _solve2(K, np.zeros_like(rz), _load_direction(problem, z, lam, rz),
                      problem.matrix_kind)
    ds0 = float(np.linalg.norm(dz_t)) / steps
    if not ds0 > 0:
        raise ValueError("control='arc-length': the loads and prescribed motions move nothing")
    ds, previous, cuts, taken = ds0, dz_t, 0, 0
    while lam < 1.0 - 1e-12:
        if taken >= max_steps:
            raise NonConvergenceError(
                f"arc-length: load factor 1 not reached in max_steps = {max_steps} steps (at "
                f"{lam:.6g}); raise max_steps or steps", lam, 1.0, 0, [])
        try:
            z_new, lam_new, u, r, its = arc_step(problem, z, lam, ds, previous, max_iterations, tol)
            if lam_new > 1.0:
                guess = z + (1.0 - lam) / (lam_new - lam) * (z_new - z)
                z_new, u, r, its, _ = newton_step(problem, z, lam, 1.0, max_iterations, tol, guess)
                lam_new = 1.0
        except StepFailed as failure:
            if ds / 2 < min_step * ds0:
                raise NonConvergenceError(
                    f"arc-length: no convergence beyond load factor {lam:.6g} with arc length "
                    f"{ds:.3g} m after {cuts} cuts: {failure.reason}", lam, lam, len(failure.history),
                    failure.history) from None
            ds, cuts = ds / 2, cuts + 1
            continue
        previous, z, lam, taken = z_new - z, z_new, lam_new, taken + 1
        if on_step(z, lam, u, r, its):
            break
        if its <= 4:
            ds = min(1.5 * ds, ds0)
    return cuts
