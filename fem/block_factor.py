"""The factorization of the free-DOF block ``A[I][:, I]`` of a symmetric matrix kept as its
upper triangle, made on the matrix's own arrays where PARDISO factorizes it: the held DOFs'
off-diagonal entries are zeroed in place for the factorization and written back after, so no
copy of the block is made (the static and modal solves' memory peak is the factorization)."""
import numpy as np

from . import linsolve
from .factor import LinearFactor


def decouple(A, I: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Zero, in place, every off-diagonal entry of the upper-triangular CSR ``A`` (sorted
    indices) in a row or a column outside ``I``, keeping the diagonal: ``A`` is then the block
    ``A[I][:, I]`` beside a diagonal one. Returns the positions and values zeroed."""
    held = np.ones(A.shape[0], dtype=bool)
    held[I] = False
    touched = np.repeat(held, np.diff(A.indptr)) | held[A.indices]
    touched[A.indptr[:-1][np.diff(A.indptr) > 0]] = False  # each row's first entry: its diagonal
    positions = np.flatnonzero(touched)
    values = A.data[positions].copy()
    A.data[positions] = 0.0
    return positions, values


def _diagonal_first(A, I: np.ndarray) -> bool:
    """Whether every held row of the upper-triangular ``A`` (sorted) starts with a positive
    diagonal entry, so that the decoupled matrix stays positive on the held DOFs."""
    held = np.setdiff1d(np.arange(A.shape[0]), I)
    starts, ends = A.indptr[held], A.indptr[held + 1]
    if np.any(ends == starts):
        return False
    return bool(np.all(A.indices[starts] == held) and np.all(A.data[starts] > 0))


class BlockFactorization(LinearFactor):
    """``x = fact(b)`` solves ``A[I][:, I] x = b`` (``b``, ``x`` over ``I``: (len(I),) or
    (len(I), k)) for the symmetric ``A`` kept as its upper triangle (CSR, sorted; ``I``
    sorted). With PARDISO the factorization reads ``A``'s own arrays, decoupled in place
    (:func:`decouple`) and restored as soon as PARDISO no longer reads them (after the
    factorization, or at ``free()``); ``A[I][:, I]`` as an operator is unchanged meanwhile.
    Otherwise the block is copied. Free with ``free()`` or ``with``."""

    def __init__(self, A, I: np.ndarray, kind: str = "spd"):
        self.I, self.n = I, len(I)
        self._undo = None
        in_place = (kind != "general" and linsolve.direct_backend(kind) == "mkl-pardiso"
                    and _diagonal_first(A, I))
        if not in_place:
            self._factor = linsolve.Factorization(
                linsolve.block_to_factorize(A, I, kind, upper=True), kind)
        else:
            self._undo = (A, *decouple(A, I))
            try:
                self._factor = linsolve.Factorization(A, kind)
            except BaseException:
                self._restore()
                raise
            if not self._factor.holds_matrix:
                self._restore()
        self._embedded = in_place
        self.backend = self._factor.backend
        self.memory = self._factor.memory  # PARDISO's (in core, out of core) peaks, or None

    def _restore(self) -> None:
        if self._undo is not None:
            A, positions, values = self._undo
            A.data[positions] = values
            self._undo = None

    def solve(self, b) -> np.ndarray:
        """x over ``I`` of A[I][:, I] x = b (fem/factor.py's protocol)."""
        b = np.asarray(b, dtype=float)
        if not self._embedded:
            return self._factor(b)
        if b.shape[0] != self.n:
            raise ValueError(f"right-hand side has {b.shape[0]} rows, the block {self.n}")
        full = np.zeros((self._factor.n,) + b.shape[1:])
        full[self.I] = b
        return self._factor(full)[self.I]

    def free(self) -> None:
        """Release the factor and write back the held entries; idempotent."""
        self._factor.free()
        self._restore()
