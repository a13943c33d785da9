"""Banded Cholesky factor of a beam model's reduced stiffness (symmetric positive definite).

A beam model is a chain of elements (with rigid links between chains): after a reverse
Cuthill-McKee ordering its reduced stiffness is a narrow band (the eight-bar's 981 unknowns:
half-bandwidth 15), which LAPACK's banded Cholesky factors ~5x faster than SuperLU's general
LU with its column ordering. The ordering and where each stored entry lands in the band are
worked out once per sparsity pattern (fem/beam/pattern.py's shared cache).
"""
import numpy as np
from scipy.linalg import lapack
import scipy.sparse as sp
from scipy.sparse.csgraph import reverse_cuthill_mckee, shortest_path

from .assembly import Factor, SingularBeamError
from .pattern import shared

MAX_BAND_FRACTION = 0.1  # wider bands (half-bandwidth over size) go to SuperLU's LU
# smallest scaled pivot accepted: below it SuperLU's LU (Factor, whose own test decides
# whether K is singular); the pivots of an ordering differ, a singular K (a pinned beam)
# left a Cholesky pivot of 1e-12 where the LU's was 2e-15; the eight-bar's least: 1e-8
PIVOT_TOL = 1e-10


def _peripheral(pattern, start: int, sweeps: int = 8) -> int:
    """A pseudo-peripheral node (George and Liu): from ``start``, repeatedly the least
    connected node of the last breadth-first level, while the eccentricity grows."""
    degree = np.diff(pattern.indptr)
    ecc = -1
    for _ in range(sweeps):
        level = shortest_path(pattern, unweighted=True, directed=False, indices=start)
        level[~np.isfinite(level)] = -1  # another component
        if level.max() <= ecc:
            break
        ecc = level.max()
        last = np.flatnonzero(level == ecc)
        start = int(last[np.argmin(degree[last])])
    return start


def _rcm_from(pattern, start: int) -> np.ndarray:
    """Reverse Cuthill-McKee ordering begun at ``start``: SciPy's (which begins at a least
    connected node) on the pattern with one extra node joined only to ``start``."""
    n = pattern.shape[0]
    extra = sp.csr_matrix((np.ones(2), ([n, start], [start, n])), shape=(n + 1, n + 1))
    grown = sp.block_diag([pattern, sp.csr_matrix((1, 1))], format="csr") + extra
    perm = reverse_cuthill_mckee(grown, symmetric_mode=True)
    return perm[perm != n]


def _bandwidth(perm, rows, cols) -> int:
    where = np.empty(len(perm), dtype=np.int64)
    where[perm] = np.arange(len(perm))
    return int(np.abs(where[rows] - where[cols]).max()) if len(rows) else 0


def _ordering(pattern) -> np.ndarray:
    """The narrower band of two reverse Cuthill-McKee orderings: SciPy's, and one begun at
    a pseudo-peripheral node (the DBMA's ground-held K: half-bandwidth 20 against 32)."""
    pattern = pattern.tocsr()
    first = reverse_cuthill_mckee(pattern, symmetric_mode=True)
    if pattern.shape[0] < 3:
        return first
    second = _rcm_from(pattern, _peripheral(pattern, int(first[-1])))
    coo = pattern.tocoo()
    return min((first, second), key=lambda perm: _bandwidth(perm, coo.row, coo.col))


class _Band:
    """Reverse Cuthill-McKee permutation ``perm`` of a CSC pattern, its half-bandwidth and,
    for each stored entry on or above the permuted diagonal (``upper``), its flat position
    in LAPACK's upper band storage (bw + 1, n)."""

    def __init__(self, indptr, indices, n: int):
        pattern = sp.csc_matrix((np.ones(len(indices)), indices, indptr), shape=(n, n))
        self.perm = _ordering(pattern)
        where = np.empty(n, dtype=np.int64)
        where[self.perm] = np.arange(n)
        self.col = np.repeat(np.arange(n), np.diff(indptr))  # each stored entry's column
        r, c = where[indices], where[self.col]
        self.upper = np.flatnonzero(r <= c)
        self.bw = int((c - r)[self.upper].max()) if len(self.upper) else 0
        self.flat = (self.bw + r[self.upper] - c[self.upper]) * n + c[self.upper]
        self.n = n


def _band(K) -> _Band:
    key = ("band", K.shape[0], K.indptr.tobytes(), K.indices.tobytes())
    return shared(key, lambda: _Band(K.indptr, K.indices, K.shape[0]))


class BandedCholesky:
    """Cholesky factor of the Jacobi-scaled K (unit diagonal, pivots compared as Factor's)
    in band storage. Raises SingularBeamError where K is not positive definite (a
    mechanism, or a tangent past a limit point) or its band is too wide."""

    def __init__(self, K):
        K = _canonical_csc(K)
        diag = K.diagonal()
        if not np.all(np.isfinite(diag)) or np.any(diag <= 0):
            raise SingularBeamError("stiffness not positive definite: a DOF without stiffness")
        band = _band(K)
        n = band.n
        if band.bw > MAX_BAND_FRACTION * n and band.bw > 32:
            raise SingularBeamError(f"band too wide ({band.bw} of {n}) for a banded factor")
        self.scale = 1.0 / np.sqrt(diag)
        values = K.data * self.scale[K.indices] * self.scale[band.col]
        ab = np.zeros((band.bw + 1) * n)
        ab[band.flat] = values[band.upper]
        # LAPACK's dpbtrf itself (scipy's cholesky_banded, without its wrapper's cost)
        self.cb, info = lapack.dpbtrf(ab.reshape(band.bw + 1, n), lower=0)
        if info != 0:
            raise SingularBeamError("stiffness not positive definite")
        if self.cb[-1].min() ** 2 <= PIVOT_TOL:
            raise SingularBeamError(f"nearly singular stiffness (scaled pivot "
                                    f"{self.cb[-1].min() ** 2:.1e})")
        self.perm = band.perm
        self.scale_perm = self.scale[self.perm]

    def solve(self, b):
        """K^-1 b for b (n,) or (n, k)."""
        b = np.asarray(b, dtype=float)
        scale = self.scale_perm if b.ndim == 1 else self.scale_perm[:, None]
        # LAPACK's dpbtrs itself: cho_solve_banded's checks cost 1/3 of a 4-column solve
        y, info = lapack.dpbtrs(self.cb, scale * b[self.perm], lower=0)
        if info != 0:
            raise ValueError(f"dpbtrs: illegal argument {-info}")
        x = np.empty_like(y)
        x[self.perm] = scale * y
        return x


def _canonical_csc(K) -> sp.csc_matrix:
    """K as a CSC matrix with sorted, unique indices (K itself where it is one)."""
    if not (sp.issparse(K) and K.format == "csc"):
        K = sp.csc_matrix(K)
    if not K.has_canonical_format:
        K = K.copy()
        K.sum_duplicates()
    return K


def spd_factor(K):
    """A factor of K (``.solve``): the banded Cholesky where K is positive definite with a
    narrow band, else SuperLU's LU (Factor; raises SingularBeamError where K is singular)."""
    try:
        return BandedCholesky(K)
    except SingularBeamError:
        return Factor(K)
