"""Newton's method for one load step of a nonlinear solve, and the error it raises when
it cannot converge (used by load control and by arc-length continuation)."""
import math

import numpy as np

from . import linsolve
from .stepping import StepFailed


def check_step_arguments(steps, max_iterations, tol, min_step) -> None:
    """ValueError naming the first bad argument of a stepped Newton solve: steps and
    max_iterations integers >= 1, tol in (0, 1), min_step (a load-factor increment) in (0, 1]."""
    for name, value in (("steps", steps), ("max_iterations", max_iterations)):
        if not (isinstance(value, (int, np.integer)) and not isinstance(value, bool) and value >= 1):
            raise ValueError(f"{name} = {value!r} must be an integer >= 1")
    if not (0 < tol < 1):
        raise ValueError(f"tol = {tol!r} must lie in (0, 1)")
    if not (0 < min_step <= 1):
        raise ValueError(f"min_step = {min_step!r} must lie in (0, 1]")


class NonConvergenceError(ValueError):
    """Newton's method failed at the smallest allowed load step. Attributes: load_factor
    (last converged), attempted (the load factor it failed to reach), iterations,
    residual_history (relative residuals of the last attempt)."""

    def __init__(self, message, load_factor, attempted, iterations, residual_history):
        super().__init__(message)
        self.load_factor = load_factor
        self.attempted = attempted
        self.iterations = iterations
        self.residual_history = residual_history


def solve_tangent(A, b, kind="symmetric") -> np.ndarray:
    """Direct solve of a Newton step: the tangent is symmetric but need not be positive
    definite (a compressed or buckling flexure); ``kind`` 'general' for follower pressure."""
    return linsolve.solve_direct(A, np.asarray(b, dtype=float), kind=kind)


def newton_step(problem, z, lam_old, lam, max_iterations, tol, guess=None):
    """Converged z at load factor ``lam`` from the converged ``z`` at ``lam_old``. Starts
    from ``guess`` (extrapolated from earlier steps) if given, else from the tangent
    predictor: the increment of loads and prescribed motions applied through the tangent
    at the old state (counted as the first iteration)."""
    space = problem.space
    history = []
    try:
        if guess is None:
            u_old, r, _, K, _, T, full_K = problem.evaluate(z, lam_old)
            jump = space.displacement(z, lam) - u_old
            rz = T.T @ (r - (lam - lam_old) * problem.f_ext + full_K @ jump) - space.applied(lam, z)
            dz = problem.solve(K, -rz)
            first = 2
        else:
            dz, first = guess - z, 1
        z = z + dz
        for iteration in range(first, max_iterations + 2):
            u, r, rz, _, reference, T, _ = problem.evaluate(z, lam, tangent=False)
            norm = float(np.linalg.norm(rz))
            history.append(norm / reference if reference > 0 else norm)
            if not math.isfinite(norm) or (len(history) > 1 and norm > 1e8 * max(reference, 1e-300)):
                raise StepFailed("the residual diverged", history)
            step_small = np.linalg.norm(dz) <= math.sqrt(tol) * max(np.linalg.norm(u), 1e-300)
            if norm <= tol * reference and step_small:
                return z, u, r, iteration - 1, history
            if iteration == max_iterations + 1:
                break
            dz = problem.solve(problem.reduced_tangent(z, lam, u, r, T), -rz)
            z = z + dz
    except StepFailed as failure:
        raise StepFailed(failure.reason, history + failure.history) from None
    raise StepFailed(f"no convergence in {max_iterations} iterations", history)
