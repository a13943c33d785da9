"""Sparse linear solvers: a direct factorization (MKL PARDISO where MKL is installed, as it is
by default on x86-64; CHOLMOD or SuperLU otherwise) and smoothed-aggregation AMG-preconditioned CG with rigid-body
modes as the near null space. :func:`factor_bytes` says, from PARDISO's analysis alone, how much memory a factor
will take (fem/solver_choice.py picks the solver by it).

A factorization is kept in a :class:`Factorization` object: factorize once, call it for many
right-hand sides (the static solve, every Lanczos step of the modal solve), then ``free()`` it
(or use it as a context manager; it is also freed when the object is collected). PARDISO's
factor lives in MKL's memory, outside Python's, and is released only by ``free()``.
"""
import functools
import os
import tempfile
import weakref

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from . import memory
from .amg import AmgFactor
from .budget import FACTOR_SHARE, available_memory_bytes, factor_plan
from .factor_protocol import (FLOOR_CAP, ROUNDOFF_FACTOR, LinearFactor,  # noqa: F401
                              SingularStiffness, check_solution, refine_and_check)  # interface
from .pardiso import mkl_pardiso, pardiso_call, pardiso_iparm, pardiso_memory, pardiso_release
from .restriction import Restriction  # noqa: F401 (part of this module's interface)
from .symmetric import symmetric_from_upper

# matrix kinds -> PARDISO matrix type: real SPD (Cholesky on the upper triangle), real
# symmetric indefinite (Bunch-Kaufman on the upper triangle), real non-symmetric (LU)
MATRIX_KINDS = {"spd": 2, "symmetric": -2, "general": 11}

#: the singular-matrix error of every factorisation (fem/factor.py), by its older name
SingularSystemError = SingularStiffness


class Factorization(LinearFactor):
    """A sparse direct factorization of ``A``, kept for many solves: ``x = fact.solve(b)``
    (or ``fact(b)``) for b of shape (n,) or (n, k). ``kind``: 'spd' (symmetric positive
    definite: Cholesky), 'symmetric' (indefinite) or 'general'; symmetric kinds read the upper
    triangle only. ``backend``: 'mkl-pardiso', 'cholmod' or 'superlu' (None: :func:`direct_backend`
    of ``kind``; a complex ``A``: 'superlu' only). Free its memory with ``free()`` or ``with``. ``analysis_only``: PARDISO's
    reordering alone, no factor (:func:`factor_bytes`). Through fem/factor.py's ``factor``.

    PARDISO out of core (its factor in files, read back at each solve): ``out_of_core`` None
    chooses by memory (fem/budget.py's ``factor_plan``: in core wherever the factor fits half
    the available memory, out of core beyond), True or False forces it. The files go to a
    new folder in ``scratch`` (None: the system temp, ``TMPDIR``), removed by ``free()``;
    ``backend`` then reads 'mkl-pardiso-ooc' and ``memory`` holds the analysis' (in core, out
    of core) peaks in bytes.
    """

    def __init__(self, A, kind: str = "general", analysis_only: bool = False,
                 backend: str | None = None, out_of_core: bool | None = None,
                 scratch: str | None = None):
        if kind not in MATRIX_KINDS:
            raise ValueError(f"kind = {kind!r}; choose one of {sorted(MATRIX_KINDS)}")
        self.dtype = complex if np.iscomplexobj(A.data if sp.issparse(A) else A) else float
        if self.dtype is complex and backend != "superlu":
            raise ValueError("a complex matrix is factorised by backend='superlu' only")
        A = sp.csr_matrix(A, dtype=self.dtype)
        if A.shape[0] != A.shape[1]:
            raise ValueError(f"the matrix must be square, not {A.shape}")
        self.kind, self.n = kind, A.shape[0]
        self._finalizer = None
        self.holds_matrix = False  # whether the solves still read A's arrays (PARDISO)
        self.memory = None  # PARDISO's (in core, out of core) peaks, bytes
        self.backend = direct_backend(kind) if backend is None else backend
        if self.backend == "mkl-pardiso" and mkl_pardiso() is None:
            raise ValueError("backend 'mkl-pardiso': MKL's runtime library is not installed")
        if self.backend == "cholmod" and (kind != "spd" or _cholmod() is None):
            raise ValueError("backend 'cholmod': SPD matrices only, with scikit-sparse installed")
        if out_of_core and self.backend != "mkl-pardiso":
            raise ValueError(f"out_of_core: PARDISO's mode only, not backend {self.backend!r}")
        if self.backend == "mkl-pardiso":
            self._init_pardiso(A, keep_matrix=analysis_only, analysis_only=analysis_only,
                               out_of_core=out_of_core, scratch=scratch)
        elif self.backend == "cholmod":
            try:
                self._factor = _cholmod().cholesky(A.tocsc())
            except Exception as error:  # sksparse's CholmodNotPositiveDefiniteError
                raise SingularStiffness(f"CHOLMOD: {error}") from None
        else:
            try:
                self._factor = spla.splu(A.tocsc(), permc_spec="MMD_AT_PLUS_A")
            except RuntimeError as error:  # "Factor is exactly singular"
                raise SingularStiffness(f"SuperLU: {error}") from None

    def _init_pardiso(self, A, keep_matrix: bool = False, analysis_only: bool = False,
                      out_of_core: bool | None = False, scratch: str | None = None):
        self._mtype = MATRIX_KINDS[self.kind]
        if self.kind != "general" and not _is_upper(A):
            A = sp.triu(A, format="csr")
        A.sum_duplicates()
        A.sort_indices()
        if np.any(np.diff(A.indptr) == 0):
            raise SingularStiffness("the matrix has an empty row: a DOF that nothing stiffens")
        self._data = np.ascontiguousarray(A.data, dtype=float)
        self.holds_matrix = True
        self._indptr = A.indptr.astype(np.int32, copy=False)
        self._indices = A.indices.astype(np.int32, copy=False)
        self._iparm = pardiso_iparm(self.kind)
        self._pt = np.zeros(64, dtype=np.int64)
        memory.release_freed()  # before the factor, the largest allocation, is made
        # release the MKL factor when this object goes away, even without free()
        self._finalizer = weakref.finalize(self, pardiso_release, self._pt, self._mtype, self.n,
                                          self._iparm)
        self._call(11)  # the analysis: the ordering and the factor's size
        self.memory = pardiso_memory(self._iparm)
        if analysis_only:
            return  # nothing to drop
        if out_of_core is None:
            out_of_core = factor_plan(*self.memory)[0] != "in-core"
        if out_of_core:
            self._factorize_out_of_core(scratch)
            return  # its solves keep the matrix (not checked out of core)
        self._call(22)
        # no perturbed pivot: PARDISO's Cholesky solves read the factor only (checked once
        # per process), so the matrix, as big as K's upper triangle, is dropped before the
        # solves; with perturbed pivots they refine iteratively on the matrix
        if (not keep_matrix and self.kind == "spd" and self._iparm[13] == 0
                and not _spd_solve_reads_matrix()):
            self._data, self._indices = np.zeros(1), np.zeros(1, dtype=np.int32)
            self.holds_matrix = False

    def _call(self, phase: int) -> None:
        """One PARDISO phase on this factorization; freed where it fails."""
        try:
            pardiso_call(self._pt, self._mtype, phase, self.n, self._data, self._indptr,
                         self._indices, self._iparm, np.zeros(self.n), np.zeros(self.n))
        except BaseException:
            self.free()
            raise

    def _factorize_out_of_core(self, scratch: str | None) -> None:
        """PARDISO's numerical factorization with the factor in files (iparm[59] = 2) in a
        new folder of ``scratch``, at most half the available memory (and at least the
        analysis' out-of-core working set, with a margin) of factor held in memory."""
        folder = tempfile.mkdtemp(prefix="flexfem-pardiso-", dir=scratch)
        self._finalizer.detach()
        self._finalizer = weakref.finalize(self, pardiso_release, self._pt, self._mtype, self.n,
                                          self._iparm, folder)
        self._iparm[59] = 2
        core = max(FACTOR_SHARE * available_memory_bytes(), 1.25 * self.memory[1] + 2**24)
        with memory.ooc_environment(folder + os.sep, core):
            try:
                pardiso_call(self._pt, self._mtype, 22, self.n, self._data, self._indptr,
                             self._indices, self._iparm, np.zeros(self.n), np.zeros(self.n))
            except BaseException:
                # MKL crashed releasing a failed out-of-core factorization: its handle is
                # dropped (what it holds leaks) and free() removes its files
                self._pt[:] = 0
                self.free()
                raise
        self.backend = "mkl-pardiso-ooc"

    def solve(self, b) -> np.ndarray:
        """x of A x = b, b of shape (n,) or (n, k)."""
        b = np.asarray(b, dtype=self.dtype)
        if b.shape[0] != self.n:
            raise ValueError(f"right-hand side has {b.shape[0]} rows, the matrix {self.n}")
        if self.backend.startswith("mkl-pardiso"):
            if not np.any(self._pt):
                raise RuntimeError("this factorization was freed")
            b = np.asfortranarray(b)
            x = np.zeros_like(b, order="F")
            pardiso_call(self._pt, self._mtype, 33, self.n, self._data, self._indptr,
                          self._indices, self._iparm, b, x)
            return np.ascontiguousarray(x)
        if self.backend == "cholmod":
            return self._factor(b)
        return self._factor.solve(b)

    def free(self) -> None:
        """Release the factor's memory (PARDISO's lives outside Python); idempotent."""
        if self._finalizer is not None:
            self._finalizer()
        self._factor = None


@functools.cache
def _spd_solve_reads_matrix() -> bool:
    """Whether this MKL's PARDISO reads the matrix (values, column indices) when it solves
    with an SPD factorization: a small SPD system is solved twice, the second time with
    the matrix overwritten (NaN values, zero column indices); True unless both solutions
    are bitwise equal."""
    n = 30  # nodes of 3 DOFs each, coupled as in a 3-D mesh, so the block format is used
    A = sp.diags([-np.ones(n - 1), 6.0 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1])
    A = A + sp.diags(np.ones(n - 5), 5) + sp.diags(np.ones(n - 5), -5)
    A = sp.kron(A, np.array([[2.0, 1.0, 0.0], [1.0, 2.0, 1.0], [0.0, 1.0, 2.0]]), format="csr")
    b = np.arange(1.0, A.shape[0] + 1.0)
    fact = Factorization.__new__(Factorization)
    fact.kind, fact.n, fact._finalizer, fact.backend = "spd", A.shape[0], None, "mkl-pardiso"
    fact.dtype = float
    with fact:
        fact._init_pardiso(sp.triu(A, format="csr"), keep_matrix=True)
        x = fact(b)
        fact._data[:] = np.nan
        fact._indices[:] = 0
        return not np.array_equal(x, fact(b))


def _is_upper(A) -> bool:
    """Whether the CSR matrix ``A`` (sorted indices) holds its upper triangle only: every
    row's first column is on or right of the diagonal (O(n), no copy)."""
    if not A.has_sorted_indices:
        return False
    rows = np.flatnonzero(np.diff(A.indptr))
    return bool(np.all(A.indices[A.indptr[rows]] >= rows))


def block_to_factorize(A, I: np.ndarray, kind: str = "spd", upper: bool = False):
    """What a :class:`Factorization` of ``kind`` needs of ``A[I][:, I]`` (CSR; ``I``
    sorted): for PARDISO's symmetric kinds the upper triangle only, taken before the rows
    and columns so that every copy is half-size; the whole block otherwise. ``upper``:
    ``A`` is symmetric and holds its upper triangle only (``Model.stiffness_upper``)."""
    if kind != "general" and direct_backend(kind) == "mkl-pardiso":
        A = A if upper else sp.triu(A, format="csr")
    elif upper:
        return symmetric_from_upper(A[I][:, I].tocsr())
    return A[I][:, I].tocsr()


def _cholmod():
    try:
        from sksparse import cholmod
    except ImportError:
        return None
    return cholmod


def direct_backend(kind: str = "spd") -> str:
    """The direct solver a factorization of ``kind`` uses here: 'mkl-pardiso' where MKL is
    installed (flexfem's default on x86-64), else 'cholmod' for SPD matrices where
    scikit-sparse is, else 'superlu' (SciPy's, single-threaded: ~16x slower on 3-D P2)."""
    if mkl_pardiso() is not None:
        return "mkl-pardiso"
    if kind == "spd" and _cholmod() is not None:
        return "cholmod"
    return "superlu"


def solve_direct(A, b, kind: str = "general") -> np.ndarray:
    """One direct solve of ``A x = b``; the factor is freed before returning."""
    with Factorization(A, kind) as F:
        return F.solve(b)


def solve_and_check(A, b, kind: str = "spd", what: str = "static solve",
                    rtol: float = 1e-6, factor=None) -> np.ndarray:
    """Direct solve of ``A x = b`` with :func:`refine_and_check`; the factor is freed.
    ``factor``: the matrix factorized, when not ``A`` itself (e.g. ``A`` a
    :class:`Restriction` and ``factor`` its :func:`block_to_factorize`)."""
    with Factorization(A if factor is None else factor, kind) as solve:
        del factor  # the factorization keeps what it needs
        return refine_and_check(A, b, solve, what, rtol)


def solve_amg(A, b, near_null_space: np.ndarray, tol: float = 1e-10) -> np.ndarray:
    """Solve the SPD system with CG preconditioned by smoothed-aggregation AMG (fem/factor.py's
    'amg-cg' backend: ``near_null_space`` (n, k) the rigid-body modes on the unknowns)."""
    return AmgFactor(A, "spd", near_null_space, tol).solve(b)


def factor_memory(A, kind: str = "spd") -> tuple[int, int] | None:
    """(in core, out of core): the peak memory (bytes) of PARDISO's factorization of ``A``
    (upper triangle if symmetric) from its analysis phase alone (:func:`pardiso_memory`);
    None where PARDISO is not the backend."""
    if direct_backend(kind) != "mkl-pardiso":
        return None
    with Factorization(A, kind, analysis_only=True) as probe:
        return probe.memory


def factor_bytes(A, kind: str = "spd") -> int | None:
    """The in-core peak (bytes) of :func:`factor_memory`; None where PARDISO is not the
    backend."""
    both = factor_memory(A, kind)
    return None if both is None else both[0]
