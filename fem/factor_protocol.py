"""The factorisation protocol's two names, importable from anywhere in the package without an
import loop: :class:`LinearFactor` (what every factorisation is: ``solve(b)``, ``free()``,
``backend``) and :class:`SingularStiffness` (the one error of a singular matrix). The backends
and ``factor`` itself: fem/factor.py. And the one check of a solution against its matrix,
:func:`check_solution` (with :func:`refine_and_check`), that every solve path runs."""
import numpy as np

from .restriction import Restriction


class SingularStiffness(ValueError):
    """The stiffness (or tangent) matrix is singular: the model can move without straining
    (a support missing, a part not connected, a mechanism). ``free``: words naming what is
    free, where known."""

    def __init__(self, message: str, free: str | None = None):
        super().__init__(message if free is None else f"{message}; free: {free}")
        self.free = free


class LinearFactor:
    """A factorisation kept for many solves: ``solve(b)`` (also ``self(b)``) for b (n,) or
    (n, k); ``backend`` its name; ``free()`` (or ``with``) releases its memory."""

    backend = "none"
    n = 0

    def solve(self, b) -> np.ndarray:
        raise NotImplementedError

    def __call__(self, b) -> np.ndarray:
        return self.solve(b)

    def free(self) -> None:
        """Release the factor's memory; idempotent."""

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.free()


def checked_rhs(b, n: int) -> np.ndarray:
    """``b`` as a float array, ValueError where its rows are not ``n``."""
    b = np.asarray(b, dtype=float)
    if b.shape[0] != n:
        raise ValueError(f"right-hand side has {b.shape[0]} rows, the matrix {n}")
    return b


def _norm_inf(A) -> float:
    return A.norm_inf() if isinstance(A, Restriction) else float(abs(A).sum(axis=1).max())


def refine_and_check(A, b, solve, what: str = "static solve", rtol: float = 1e-6) -> np.ndarray:
    """``x = solve(b)`` (a factorization of ``A``) with one step of iterative refinement
    where the first residual is above ``rtol`` ||b||, then :func:`check_solution`."""
    x = solve(b)
    if np.all(np.isfinite(x)):
        r = b - A @ x
        if np.linalg.norm(r) > rtol * np.linalg.norm(b):
            x = x + solve(r)
    check_solution(A, x, b, what, rtol)
    return x


# check_solution: a direct solve's residual is at most ROUNDOFF_FACTOR eps ||A|| ||x|| (measured
# 0.2-0.4 eps ||A||_inf ||x||_2 on slender P2 cantilevers, L/H = 10 to 5000), and never more than
# FLOOR_CAP ||b|| (a singular system leaves the part of b outside A's range, ~ ||b||)
ROUNDOFF_FACTOR = 100.0
FLOOR_CAP = 1e-2


def check_solution(A, x, b, what: str = "static solve", rtol: float = 1e-6) -> None:
    """Raise :class:`SingularStiffness` if ``x`` does not solve ``A x = b``.

    Accepted: a residual ||A x - b|| of at most ``rtol`` ||b||, or one at the round-off floor
    of evaluating A x (at most ROUNDOFF_FACTOR eps ||A||_inf ||x||) that is still below
    FLOOR_CAP ||b||. The floor is what a correct direct solve of a slender flexure reaches
    (||r|| / ||b|| ~ eps cond(A): 1e-6 at L/H = 200, 3e-4 at L/H = 1000, P2 plane stress);
    a singular system (a free rigid-body motion or mechanism) leaves a residual of the order of
    ||b|| itself, or one far above the floor, and is refused.
    """
    if not np.all(np.isfinite(x)):
        raise SingularStiffness(f"{what}: the solution is not finite; the model is singular "
                                  "(under-constrained, or parts not connected to a support)")
    r = np.linalg.norm(A @ x - b)
    nb = max(np.linalg.norm(b), 1e-300)
    if r <= rtol * nb:
        return
    floor = ROUNDOFF_FACTOR * np.finfo(float).eps * _norm_inf(A) * np.linalg.norm(x)
    if r <= floor and r <= FLOOR_CAP * nb:
        return
    raise SingularStiffness(f"{what}: residual {r / nb:.1e} relative to the load (bound "
                              f"{rtol:.0e}, or the round-off floor {min(floor, FLOOR_CAP * nb) / nb:.1e}"
                              "); the stiffness matrix is singular or nearly so (under-constrained "
                              "model, disconnected parts, or a mechanism)")
