"""One factorisation protocol for every linear solve: ``factor(A, kind, backend) -> LinearFactor``
whose ``solve(b)`` takes b of shape (n,) or (n, k), and one error, :class:`SingularStiffness`,
where A is singular.

Backends (:data:`BACKENDS`, name -> constructor ``(A, kind, **options) -> LinearFactor``):
'mkl-pardiso', 'cholmod', 'superlu' (fem/linsolve.py's direct factorisations), 'banded' (LAPACK's
banded Cholesky of an SPD matrix of narrow band, fem/beam/banded.py), 'amg-cg' (CG
preconditioned by smoothed-aggregation AMG, ``near_null_space`` its option) and 'pmg-cg'
(p-multigrid CG of a quadratic model's free-DOF stiffness, fem/pmultigrid.py: ``model`` and
``free`` its options, ``needs_model``); 'auto' is the
direct backend of :func:`.linsolve.direct_backend`. A new backend is one more entry.

Usage::

    with factor(K, "spd") as F:        # free() at the end (PARDISO's factor is outside Python)
        x = F.solve(b)                 # or F(b)

Where the matrix is singular the error says what is free: with ``labels`` (one name per
unknown: a group, a node, a DOF) the unknowns that move in the free motion (found by inverse
iteration on a slightly shifted matrix) are named.
"""
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .amg import AmgFactor
from .factor_protocol import LinearFactor, SingularStiffness, checked_rhs
from .linsolve import Factorization, direct_backend, refine_and_check

__all__ = ["BACKENDS", "AmgFactor", "BandedFactor", "CheckedFactor", "LinearFactor",
           "SingularStiffness", "factor", "free_motion"]

KINDS = ("spd", "symmetric", "general")


def _direct(name):
    def make(A, kind, **options):
        return Factorization(A, kind, backend=name, **options)
    return make


class BandedFactor(LinearFactor):
    """LAPACK's banded Cholesky of an SPD matrix (fem/beam/banded.py's, after a reverse
    Cuthill-McKee ordering); SingularStiffness where it is not positive definite or its band
    is too wide."""

    backend = "banded"

    def __init__(self, A, kind: str = "spd"):
        from .beam.assembly import SingularBeamError
        from .beam.banded import BandedCholesky
        if kind != "spd":
            raise ValueError(f"the banded Cholesky factorises SPD matrices, not kind = {kind!r}")
        self.n = A.shape[0]
        try:
            self._factor = BandedCholesky(A)
        except SingularBeamError as error:
            raise SingularStiffness(f"banded Cholesky: {error}") from None

    def solve(self, b) -> np.ndarray:
        return self._factor.solve(checked_rhs(b, self.n))


def _pmultigrid(A, kind, **options):
    """fem/pmultigrid.py's PMultigridFactor, imported when it is asked for (its bases are
    scikit-fem's: a beam model's solve does not import them)."""
    from .pmultigrid import PMultigridFactor

    return PMultigridFactor(A, kind, **options)


_pmultigrid.needs_model = True  # as PMultigridFactor: model= and free= are required


#: name -> constructor (A, kind, **options) -> LinearFactor; 'auto' resolves to a direct one
BACKENDS = {
    "mkl-pardiso": _direct("mkl-pardiso"),
    "cholmod": _direct("cholmod"),
    "superlu": _direct("superlu"),
    "banded": BandedFactor,
    "amg-cg": AmgFactor,
    "pmg-cg": _pmultigrid,  # needs model= and free= (fem/pmultigrid.py)
}


def factor(A, kind: str = "spd", backend: str = "auto", labels=None, check: bool = False,
           **options) -> LinearFactor:
    """Factorise the square matrix ``A`` once for many solves (see the module's docstring).

    kind : 'spd', 'symmetric' (indefinite; the upper triangle is read) or 'general'.
    backend : a name of :data:`BACKENDS`, or 'auto' (PARDISO where MKL is installed, else
    CHOLMOD for SPD where scikit-sparse is, else SuperLU). labels : one name per unknown
    (group, node or DOF), used to name the free motion when ``A`` is singular. check : test
    every solution against ``A`` (the whole matrix, not a triangle: one step of iterative
    refinement, then fem/linsolve.py's ``check_solution``), so that a singular ``A`` that a
    backend factorises anyway (PARDISO's perturbed pivots) is refused too.
    options : passed to the backend (``near_null_space``, ``tol`` for 'amg-cg'; ``out_of_core``
    (None: by memory, True, False) and ``scratch`` (the folder of its files) for PARDISO, whose
    factor out of core reads ``backend`` 'mkl-pardiso-ooc': fem/linsolve.py).
    Raises SingularStiffness where A is singular, ValueError on a bad argument.
    """
    if kind not in KINDS:
        raise ValueError(f"kind = {kind!r}; choose one of {list(KINDS)}")
    if backend == "auto":
        backend = direct_backend(kind)
    if backend not in BACKENDS:
        raise ValueError(f"backend = {backend!r}; choose 'auto' or one of {sorted(BACKENDS)}")
    if labels is not None and len(labels) != A.shape[0]:
        raise ValueError(f"labels has {len(labels)} names for {A.shape[0]} unknowns")
    try:
        made = BACKENDS[backend](A, kind, **options)
    except SingularStiffness as error:
        raise _named(error, A, labels) from None
    return CheckedFactor(made, A, labels, check) if check or labels is not None else made


class CheckedFactor(LinearFactor):
    """A factor whose solves are checked against ``A`` when ``check`` (see :func:`factor`)
    and whose SingularStiffness names the free motion by ``labels``."""

    def __init__(self, inner: LinearFactor, A, labels=None, check: bool = True,
                 rtol: float = 1e-6):
        self.inner, self.A, self.labels, self.check, self.rtol = inner, A, labels, check, rtol
        self.backend, self.n = inner.backend, inner.n

    def solve(self, b) -> np.ndarray:
        try:
            if not self.check:
                return self.inner.solve(b)
            return refine_and_check(self.A, np.asarray(b, dtype=float), self.inner.solve,
                                    f"{self.backend} solve", self.rtol)
        except SingularStiffness as error:
            raise _named(error, self.A, self.labels) from None

    def free(self) -> None:
        self.inner.free()


def _named(error: SingularStiffness, A, labels) -> SingularStiffness:
    """``error`` with the free motion named by ``labels`` (as it is where they are None or it
    names one already)."""
    if labels is None or error.free is not None:
        return error
    return SingularStiffness(str(error), free_motion(A, labels))


def free_motion(A, labels, moving: float = 0.5, shown: int = 4) -> str:
    """Words naming the unknowns that move in the (near) null vector of the symmetric ``A``:
    the labels of those whose amplitude is at least ``moving`` times the largest (at most
    ``shown`` distinct ones). The vector: three steps of inverse iteration with A shifted by
    1e-8 of its mean diagonal (SuperLU)."""
    A = sp.csc_matrix(A, dtype=float)
    n = A.shape[0]
    diagonal = np.abs(A.diagonal())
    shift = 1e-8 * (diagonal.mean() if diagonal.any() else 1.0)
    try:
        lu = spla.splu((A + shift * sp.identity(n, format="csc")).tocsc(),
                       permc_spec="MMD_AT_PLUS_A")
    except RuntimeError:
        return "unknown (the shifted matrix is singular too)"
    v = np.random.default_rng(0).standard_normal(n)
    for _ in range(3):
        v = lu.solve(v)
        v /= np.abs(v).max()
    names = list(dict.fromkeys(str(labels[i]) for i in np.argsort(-np.abs(v))
                               if abs(v[i]) >= moving))
    more = f" (and {len(names) - shown} more)" if len(names) > shown else ""
    return ", ".join(names[:shown]) + more
