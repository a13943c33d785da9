"""A block ``A[I][:, I]`` of a sparse matrix as a linear operator, without copying it."""
import numpy as np
import scipy.sparse.linalg as spla

from .symmetric import symmetric_matvec


class Restriction(spla.LinearOperator):
    """``A[I][:, I]`` of a square sparse ``A`` as an operator, without copying ``A``: the
    stiffness or mass on the free DOFs ``I`` (sorted). ``upper``: ``A`` is symmetric and
    holds its upper triangle only."""

    def __init__(self, A, I: np.ndarray, upper: bool = False):
        self.A, self.I, self.upper = A, I, upper
        super().__init__(float, (len(I), len(I)))

    def _product(self, full):
        return symmetric_matvec(self.A, full) if self.upper else self.A @ full

    def _matvec(self, x):
        full = np.zeros(self.A.shape[1])
        full[self.I] = np.ravel(x)
        return self._product(full)[self.I]

    def _matmat(self, X):
        full = np.zeros((self.A.shape[1], X.shape[1]))
        full[self.I] = X
        return self._product(full)[self.I]

    def _adjoint(self):
        return self if self.upper else Restriction(self.A.T.tocsr(), self.I)

    def diagonal(self) -> np.ndarray:
        return self.A.diagonal()[self.I]

    def norm_inf(self) -> float:
        """max_i sum_j |A_ij| over the block."""
        keep = np.zeros(self.A.shape[1])
        keep[self.I] = 1.0
        absolute = abs(self.A)
        sums = symmetric_matvec(absolute, keep) if self.upper else absolute @ keep
        return float(sums[self.I].max())
