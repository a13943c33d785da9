"""Newton's method: the one driver of every Newton iteration in the package (:func:`newton`:
the continuum's load steps and arc-length corrections, topopt's large displacements), its
divergence rule, one load step of the continuum (:func:`newton_step`) and the error a stepped
solve raises when it cannot converge.

Divergence, one rule: an iteration diverges where its residual norm is not finite or exceeds
DIVERGENCE (1e6) times the larger of the first residual norm the driver tests and the
convergence target ``tol * reference``. Relative to the first residual, so that it does not
depend on the force unit or on the size of the load step; the floor ``tol * reference`` keeps
a first residual already near round-off from making any later round-off wobble a divergence.
"""
from dataclasses import dataclass
import math

import numpy as np

from .factor import SingularStiffness, factor
from .stepping import StepFailed

#: a residual norm above DIVERGENCE times max(first residual norm, tol * reference) diverged
DIVERGENCE = 1e6
#: halvings of a correction the optional line search tries while the residual grows
LINE_SEARCH_HALVINGS = 4


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
    with factor(A, kind) as F:
        return F.solve(np.asarray(b, dtype=float))


@dataclass
class NewtonResult:
    """A converged Newton iteration: ``x`` the solution, ``state`` what ``residual`` returned
    with it, ``iterations`` the corrections made (those before the driver included),
    ``history`` the relative residual norms (norm / reference) of the iterates tested."""

    x: object
    state: object
    iterations: int
    history: list


def diverged(size: float, first: float, target: float) -> bool:
    """The divergence rule (module docstring): ``size`` not finite, or above DIVERGENCE
    max(``first``, ``target``)."""
    return not math.isfinite(size) or size > DIVERGENCE * max(first, target)


def newton(x, residual, correction, *, tol: float, max_iterations: int, update=None,
           converged=None, norm=np.linalg.norm, line_search: bool = False, done: int = 0,
           dx=None) -> NewtonResult:
    """Newton's iteration from ``x``.

    residual(x) -> (r, reference, state): the residual ``r`` (``norm(r)`` its size, e.g. N),
    the scale ``reference`` (same unit) the tolerance is relative to, and ``state`` (what the
    correction needs: the tangent or its factor; returned with the solution).
    correction(x, r, state) -> dx: the Newton correction (a solve with the tangent); it may
    raise StepFailed, or SingularStiffness (a singular tangent: StepFailed).
    update(x, dx) -> the next iterate (default ``x + dx``; a rotation update for beams).
    converged(x, dx, size, reference, state) -> bool; default ``size <= tol * reference``;
    ``dx`` is the last correction (the argument ``dx`` before the first: e.g. a predictor, or None).
    line_search : halve a correction (up to LINE_SEARCH_HALVINGS times) while the residual
    norm grows. done : corrections already made before ``x`` (a predictor counts one);
    at most ``max_iterations`` in all.
    Raises StepFailed (with the relative residuals) on divergence (:func:`diverged`), a
    singular tangent or no convergence.
    """
    update = update if update is not None else (lambda x, dx: x + dx)
    converged = converged if converged is not None else (
        lambda x, dx, size, reference, state: size <= tol * reference)
    history, first = [], None
    try:
        r, reference, state = residual(x)
        while True:
            size = float(norm(r))
            history.append(size / reference if reference > 0 else size)
            first = size if first is None else first
            if diverged(size, first, tol * reference):
                break
            if converged(x, dx, size, reference, state):
                return NewtonResult(x, state, done, history)
            if done >= max_iterations:
                raise StepFailed(f"no convergence in {max_iterations} iterations", [])
            dx = correction(x, r, state)
            trial = update(x, dx)
            r_trial, ref_trial, state_trial = residual(trial)
            for _ in range(LINE_SEARCH_HALVINGS if line_search else 0):
                if float(norm(r_trial)) <= size:
                    break
                dx = 0.5 * dx
                trial = update(x, dx)
                r_trial, ref_trial, state_trial = residual(trial)
            x, r, reference, state = trial, r_trial, ref_trial, state_trial
            done += 1
    except SingularStiffness as error:
        raise StepFailed(f"the tangent is singular ({error})", history) from None
    except StepFailed as failure:
        raise StepFailed(failure.reason, history + failure.history) from None
    raise StepFailed("the residual diverged", history)


def newton_step(problem, z, lam_old, lam, max_iterations, tol, guess=None):
    """Converged z at load factor ``lam`` from the converged ``z`` at ``lam_old``. Starts
    from ``guess`` (extrapolated from earlier steps) if given, else from the tangent
    predictor: the increment of loads and prescribed motions applied through the tangent
    at the old state (counted as the first iteration). Returns (z, u, r, iterations,
    history); StepFailed where :func:`newton` fails."""
    space = problem.space
    if guess is None:
        u_old, r, _, K, _, T, full_K = problem.evaluate(z, lam_old)
        jump = space.displacement(z, lam) - u_old
        rz = T.T @ (r - (lam - lam_old) * problem.f_ext + full_K @ jump) - space.applied(lam, z)
        dz, done = problem.solve(K, -rz), 1
    else:
        dz, done = guess - z, 0

    def residual(z):
        u, r, rz, _, reference, T, _ = problem.evaluate(z, lam, tangent=False)
        return rz, reference, (u, r, T)

    def correction(z, rz, state):
        u, r, T = state
        return problem.solve(problem.reduced_tangent(z, lam, u, r, T), -rz)

    def converged(z, dz, size, reference, state):
        return size <= tol * reference and \
            np.linalg.norm(dz) <= math.sqrt(tol) * max(np.linalg.norm(state[0]), 1e-300)

    found = newton(z + dz, residual, correction, tol=tol, max_iterations=max_iterations,
                   converged=converged, done=done, dx=dz)
    u, r, _ = found.state
    return found.x, u, r, found.iterations, found.history
