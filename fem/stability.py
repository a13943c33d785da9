"""Stability of an equilibrium and tangent stiffness about a (pre)stressed state.

An equilibrium is stable when the tangent stiffness of the free unknowns is positive definite
(the potential energy has a strict minimum there). :func:`count_negative_eigenvalues` reads
the number of negative eigenvalues from the signs of the pivots of a symmetric LDL^T
factorization (Sylvester's law of inertia): one factorization, the cost of a Newton step.
"""

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .factor import SingularStiffness
from .hyperelastic import Assembler, geometric_stiffness
from .model import Model
from .nonlinear_result import NonlinearResult
from .static_result import StaticResult


def count_negative_eigenvalues(K) -> int:
    """Number of negative eigenvalues of the symmetric sparse matrix ``K``: the negative
    pivots of K = P^T L D L^T P with diagonal pivots (SuperLU in symmetric mode, no pivoting
    threshold). A zero pivot (K singular: a critical state) raises SingularStiffness;
    where SuperLU leaves the diagonal (non-symmetric permutation) the count falls back to
    shift-invert Lanczos about 0 (the 6 eigenvalues nearest 0). Without 2 x 2 pivots the
    factorization of a strongly indefinite matrix may be inaccurate; tangents of
    structures near their stability limit, the case of interest, are nearly definite."""

    K = sp.csc_matrix(K, dtype=float)
    try:
        lu = spla.splu(K, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                       options=dict(SymmetricMode=True))
    except RuntimeError as error:
        raise SingularStiffness(f"the tangent is singular ({error}): a critical state") from None
    if np.array_equal(lu.perm_r, lu.perm_c):
        d = lu.U.diagonal()
        if np.all(np.isfinite(d)):
            return int(np.sum(d < 0))
    op = spla.LinearOperator(K.shape, matvec=lu.solve, dtype=float)
    # eigenvalues nearest 0 first; a negative one among the 6 nearest is the first to appear
    k = min(6, K.shape[0] - 1)
    values = spla.eigsh(K, k=k, sigma=0.0, which="LM", OPinv=op, return_eigenvectors=False)
    return int(np.sum(values < 0))


def state_displacement(model: Model, state) -> tuple:
    """(u (m), kind) of a state: 'linear' for a StaticResult, 'nonlinear' for a
    NonlinearResult (last step), a (NonlinearResult, step) pair or a DOF vector."""
    if isinstance(state, StaticResult):
        u, kind = state.u, "linear"
    elif isinstance(state, NonlinearResult):
        u, kind = state.u[-1], "nonlinear"
    elif isinstance(state, tuple) and len(state) == 2 and isinstance(state[0], NonlinearResult):
        result, step = state
        if not (isinstance(step, (int, np.integer)) and -len(result.u) <= step < len(result.u)):
            raise ValueError(f"state step = {step!r} must index one of the {len(result.u)} steps")
        u, kind = result.u[step], "nonlinear"
    else:
        u, kind = np.asarray(state, dtype=float), "nonlinear"
    if u.shape != (model.n_dofs,) or not np.all(np.isfinite(u)):
        raise ValueError(f"state must be a StaticResult, a NonlinearResult, (NonlinearResult, "
                         f"step) or a finite DOF vector of {model.n_dofs} entries (m)")
    return u, kind


def tangent_stiffness(model: Model, state) -> sp.csr_matrix:
    """Tangent stiffness (N/m) about ``state`` (see :func:`state_displacement`): for a
    StaticResult K + K_sigma(sigma of u) (linearised prestress, the classical buckling and
    prestressed-modal operator); otherwise the consistent total-Lagrangian tangent at u
    (material + initial stress + initial displacement)."""
    u, kind = state_displacement(model, state)
    if kind == "linear":
        return (model.stiffness + geometric_stiffness(model, u)).tocsr()
    assembler = Assembler(model)
    return assembler.tangent(*assembler.state(u))
