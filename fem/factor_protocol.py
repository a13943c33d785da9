"""The factorisation protocol's two names, importable from anywhere in the package without an
import loop: :class:`LinearFactor` (what every factorisation is: ``solve(b)``, ``free()``,
``backend``) and :class:`SingularStiffness` (the one error of a singular matrix). The backends
and ``factor`` itself: fem/factor.py."""
import numpy as np


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
