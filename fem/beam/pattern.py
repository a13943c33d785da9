"""Fixed sparsity patterns: sparse matrices assembled by one ``np.bincount`` into precomputed
compressed arrays.

A beam model's element connectivity and rigid links never change during a solve, so where
each element entry lands in the global (or reduced) matrix is worked out once (a sort) and
every later assembly is a weighted sum into fixed slots, without building COO/CSR matrices
and sparse products anew (the Newton iterations of a stroke assemble dozens of times).
"""
from collections import OrderedDict

import numpy as np
import scipy.sparse as sp

_SHARED = OrderedDict()  # patterns by topology, shared between models (a sweep has one)
SHARED_SIZE = 16


class Pattern:
    """Where entries (rows, cols) land in a compressed ``shape`` matrix: ``matrix(values)``
    sums the values of duplicate positions. ``fmt``: "csr" or "csc"."""

    def __init__(self, rows, cols, shape, fmt: str = "csr"):
        rows, cols = np.asarray(rows, dtype=np.int64), np.asarray(cols, dtype=np.int64)
        self.shape, self.fmt = (int(shape[0]), int(shape[1])), fmt
        major, minor = (rows, cols) if fmt == "csr" else (cols, rows)
        n_major, n_minor = self.shape if fmt == "csr" else self.shape[::-1]
        # the compressed pattern by scipy's O(nnz) conversion, each entry's slot by bisection
        A = sp.csr_matrix((np.ones(len(major)), (major, minor)), shape=(n_major, n_minor))
        A.sum_duplicates()  # canonical: sorted, unique column indices in each row
        keys = np.repeat(np.arange(n_major, dtype=np.int64), np.diff(A.indptr)) * n_minor
        self.slot = np.searchsorted(keys + A.indices, major * n_minor + minor)
        self.nnz = A.nnz
        self.indices, self.indptr = A.indices.astype(np.int32), A.indptr.astype(np.int32)
        for a in (self.slot, self.indices, self.indptr):  # shared by the matrices built on it
            a.setflags(write=False)

    def data(self, values) -> np.ndarray:
        """Compressed data array: ``values`` (one per entry) summed into their slots."""
        return np.bincount(self.slot, weights=values, minlength=self.nnz)

    def matrix(self, values):
        """The sparse matrix (csr_matrix or csc_matrix) of ``values``."""
        cls = sp.csr_matrix if self.fmt == "csr" else sp.csc_matrix
        out = cls((self.data(values), self.indices, self.indptr), shape=self.shape)
        out.has_canonical_format = True  # sorted, unique indices: no check by its users
        return out


def shared(key, build):
    """``build()`` once per ``key`` (bytes describing a topology) among the last SHARED_SIZE
    keys: the designs of a sweep differ in dimensions, not in connectivity or supports."""
    if key in _SHARED:
        _SHARED.move_to_end(key)
        return _SHARED[key]
    value = _SHARED[key] = build()
    if len(_SHARED) > SHARED_SIZE:
        _SHARED.popitem(last=False)
    return value


def block_dofs(blocks) -> np.ndarray:
    """(m, 3 k) DOF indices of blocks of k nodes ((m, k) node indices)."""
    blocks = np.asarray(blocks, dtype=np.int64)
    return (3 * blocks[:, :, None] + np.arange(3)).reshape(len(blocks), -1)


def global_pattern(model) -> Pattern:
    """The global matrix pattern of a model (cached): every element entry, then every
    diagonal entry (nodes without elements, such as rigid-link masters, included)."""
    def build():
        dofs = block_dofs(model.connectivity)
        m, n = len(dofs), model.n_dofs
        rows = np.concatenate([np.broadcast_to(dofs[:, :, None], (m, 6, 6)).ravel(),
                               np.arange(n)])
        cols = np.concatenate([np.broadcast_to(dofs[:, None, :], (m, 6, 6)).ravel(),
                               np.arange(n)])
        return Pattern(rows, cols, (n, n))
    key = ("global", model.n_dofs, model.connectivity.tobytes())
    return model.cached("global_pattern", lambda: shared(key, build))


def global_matrix(model, ke, diagonal=None) -> sp.csr_matrix:
    """Global CSR matrix of element matrices ``ke`` (n_e + n_pairs, 6, 6: the elements',
    then the superelements' pairs') plus ``diagonal`` (n_dofs,)."""
    diagonal = np.zeros(model.n_dofs) if diagonal is None else diagonal
    return global_pattern(model).matrix(np.concatenate([ke.ravel(), diagonal]))


class Condensed:
    """T^T (sum of block matrices) T + diag(d) on the free unknowns of a Space, for blocks of
    DOFs ``dofs`` (m, k) (e.g. the elements' six), in CSC form: each full DOF is a combination
    of at most two unknowns (its own, or a rigid-link master's translation and rotation), so
    each block entry contributes to at most four reduced entries, with weights from the
    Space's link Jacobian at the current state."""

    def __init__(self, col, n: int, dofs):
        m, k = dofs.shape
        C = col[dofs]  # (m, k, 2) unknowns of each DOF
        W = 2 * dofs[:, :, None] + np.arange(2)  # (m, k, 2) positions in weights.ravel()
        E = np.arange(m * k * k).reshape(m, k, k)
        grid = lambda A, i, j: (np.broadcast_to(A[:, :, None, i], (len(A), k, k)),
                                np.broadcast_to(A[:, None, :, j], (len(A), k, k)))
        parts = [(*grid(C, 0, 0), E, *grid(W, 0, 0))]  # every DOF's own (first) unknown
        linked = np.flatnonzero((C[:, :, 1] >= 0).any(axis=1))  # blocks on rigid-link slaves
        for i, j in ((1, 0), (0, 1), (1, 1)):  # the master rotations' terms there
            parts.append((*grid(C[linked], i, j), E[linked], *grid(W[linked], i, j)))
        rows, cols, entry, wa, wb = (np.concatenate([p[q].ravel() for p in parts])
                                     for q in range(5))
        keep = (rows >= 0) & (rows < n) & (cols >= 0) & (cols < n)
        self.entry, self.wa, self.wb = entry[keep], wa[keep], wb[keep]
        diag = np.arange(n)  # every diagonal entry present (the links' second-order term)
        self.pattern = Pattern(np.concatenate([rows[keep], diag]),
                               np.concatenate([cols[keep], diag]), (n, n), "csc")

    def matrix(self, blocks, weights, diagonal) -> sp.csc_matrix:
        """Reduced matrix of block matrices ``blocks`` (m, k, k) at link ``weights`` (n_dofs,
        2) plus ``diagonal`` (n,)."""
        w = weights.ravel()
        values = blocks.ravel()[self.entry] * w[self.wa] * w[self.wb]
        return self.pattern.matrix(np.concatenate([values, diagonal]))
