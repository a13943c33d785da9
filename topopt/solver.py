"""One factorisation per design, the fill-reducing ordering computed once: a matrix of fixed
sparsity pattern is analysed once (MKL PARDISO phase 11) and refactorised numerically for
every new set of values (phase 22); elsewhere each design is factorised anew through
flexfem's ``factor`` (CHOLMOD or SuperLU). A :class:`PatternSolver` is a factor of
fem/factor.py's protocol (``solve``, ``free``, ``backend``)."""
import weakref

import numpy as np
import scipy.sparse as sp

from ..fem import linsolve
from ..fem.pardiso import pardiso_call, pardiso_release
from ..fem.factor import LinearFactor, factor

SPD = 2  # PARDISO's real symmetric positive definite matrix type


def _iparm() -> np.ndarray:
    iparm = np.zeros(64, dtype=np.int32)
    iparm[0] = 1    # these values, not the defaults
    iparm[1] = 2    # METIS nested dissection
    iparm[9] = 8    # pivot perturbation 1e-8
    # conditional numerical reproducibility, one thread: without it a solve's last bits
    # depend on MKL's threading layer (Intel or GNU OpenMP, chosen at MKL's first call: GNU
    # where libgomp is already loaded, e.g. by gmsh) and, on more than one thread, vary from
    # call to call; the optimiser's path followed them (needs the sequential METIS above)
    iparm[33] = 1
    iparm[34] = 1   # zero-based indices
    return iparm


class PatternSolver(LinearFactor):
    """Factorise SPD matrices sharing the CSR pattern (``indptr``, ``indices``; upper
    triangle for PARDISO, full otherwise): ``factor(data)`` then ``solve(b)``."""

    def __init__(self, indptr: np.ndarray, indices: np.ndarray, n: int):
        self.n = n
        self.backend = linsolve.direct_backend("spd")
        self._indptr = np.ascontiguousarray(indptr, dtype=np.int32)
        self._indices = np.ascontiguousarray(indices, dtype=np.int32)
        self._factor = None
        self._analysed = False
        if self.backend == "mkl-pardiso":
            self._pt, self._iparm = np.zeros(64, dtype=np.int64), _iparm()
            self._finalizer = weakref.finalize(self, pardiso_release, self._pt, SPD,
                                               n, self._iparm)

    def factor(self, data: np.ndarray) -> None:
        """Numeric factorisation of the matrix with these values (pattern order)."""
        self._data = np.ascontiguousarray(data, dtype=float)
        if self.backend != "mkl-pardiso":
            if self._factor is not None:
                self._factor.free()
            A = sp.csr_matrix((self._data, self._indices, self._indptr), shape=(self.n, self.n))
            self._factor = factor(A, "spd")
            return
        dummy = np.zeros(self.n)
        if not self._analysed:
            self._call(11, dummy, dummy.copy())
            self._analysed = True
        self._call(22, dummy, dummy.copy())

    def solve(self, b: np.ndarray) -> np.ndarray:
        """x of A x = b, b of shape (n,) or (n, k)."""
        if self.backend != "mkl-pardiso":
            return np.asarray(self._factor.solve(b))
        b = np.asfortranarray(b, dtype=float)
        x = np.zeros_like(b, order="F")
        self._call(33, b, x)
        return np.ascontiguousarray(x)

    def _call(self, phase: int, b, x) -> None:
        pardiso_call(self._pt, SPD, phase, self.n, self._data, self._indptr,
                               self._indices, self._iparm, b, x)

    def free(self) -> None:
        """Release the factor's memory; idempotent."""
        if self.backend == "mkl-pardiso":
            self._finalizer()
        elif self._factor is not None:
            self._factor.free()
            self._factor = None
