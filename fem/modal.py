"""Modal analysis: ``solve_modes(model, n, supports) -> Modes``.

The supported DOFs are eliminated (condensed), not kept with unit diagonals, which would add
spurious eigenvalues. The eigenproblem K phi = omega^2 M phi is solved by shift-invert Lanczos
with one sparse factorization of K - sigma M.
"""
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from . import linsolve, memory, symmetric
from .block_factor import BlockFactorization
from .boundary import component_indices, constrained_dofs
from .model import Model
from .solved import Solved
from .static import check_supports, vertex_displacement
from .symmetric import symmetric_matvec

SHIFT = 1e-10  # the default shift, relative to the mean stiffness/mass diagonal ratio


@dataclass(frozen=True, eq=False)
class Modes(Solved):
    """The natural modes of a model (:func:`flexfem.fem.solve_modes`): ``model``
    (:class:`~.solved.Solved`) and

    Attributes
    ----------
    frequencies_hz : ndarray
        (n,) natural frequencies (Hz), ascending.
    shapes : ndarray
        (n, n_dofs) mass-normalised mode shapes (phi.M.phi = 1, m/sqrt(kg)).
    effective_mass : ndarray
        (n, dim) effective modal mass (kg) per translation direction.
    total_mass : float
        The mass of the body (kg).
    solver : str
        The factorization's backend: 'mkl-pardiso', 'cholmod' or 'superlu'.
    """

    frequencies_hz: np.ndarray
    shapes: np.ndarray
    effective_mass: np.ndarray
    total_mass: float
    solver: str = ""

    @property
    def effective_mass_fraction(self) -> np.ndarray:
        """(n, dim) effective mass as a fraction of the total mass."""
        return self.effective_mass / self.total_mass

    def dominant_direction(self, k: int) -> int:
        """Translation axis (0 = x, 1 = y, 2 = z) with the largest effective mass of mode k."""
        return int(np.argmax(self.effective_mass[k]))

    def vertex_shape(self, k: int) -> np.ndarray:
        """(n_vertices, dim) shape of mode k at the mesh vertices."""
        return vertex_displacement(self.model, self.shapes[k])


def solve_modes(model: Model, n: int = 6, supports=(), shift_hz: float | None = None,
                prestress=None) -> Modes:
    """The ``n`` lowest natural frequencies and mass-normalised shapes.

    supports : Fixed/Prescribed supports; their DOFs are held at zero (prescribed values are
    ignored: modes are free vibrations about the supported state). With no supports the
    rigid-body modes come first, at ~0 Hz; supports that leave a rigid-body motion (of any
    disconnected part) free raise UnderConstrainedError, as in solve_static. shift_hz :
    shift-invert centre (default a small negative shift, so that a free body's singular K
    is factorizable). prestress : vibrations about a loaded state: a StaticResult (K plus
    the geometric stiffness of its stress), a NonlinearResult (last step), a
    (NonlinearResult, step) pair or a converged DOF vector (m) (the consistent tangent
    there); see :func:`.stability.tangent_stiffness`. A state beyond buckling has negative
    eigenvalues: reported as 0 Hz.
    """
    if not (isinstance(n, (int, np.integer)) and 1 <= n):
        raise ValueError(f"number of modes n = {n} must be a positive integer")
    D, _, _ = constrained_dofs(model, supports)
    if len(D):
        check_supports(model, D)
    I = np.setdiff1d(np.arange(model.n_dofs), D)
    if n >= len(I):
        raise ValueError(f"n = {n} modes asked for but only {len(I)} free DOFs exist")
    M_upper = model.mass_upper
    if prestress is None:  # the model keeps K and M as their upper triangles
        K_full, owned = model.__dict__.get("stiffness_upper"), False
        if K_full is None:  # assembled for this solve: changed in place, then dropped
            K_full, owned = model.assemble_stiffness_upper(), True
    else:
        from .stability import tangent_stiffness
        K_full, owned = symmetric.upper(tangent_stiffness(model, prestress)), True
    M = linsolve.Restriction(M_upper, I, upper=True)  # an operator on M: no copy
    if shift_hz is None:
        # -(scale of the stiffness/mass ratio) * 1e-10: below the elastic modes of any
        # flexure, and keeps K - sigma M positive definite for a free body (its condition
        # ~1e10); a shift much farther below the lowest modes than they lie apart would
        # cluster them for Lanczos (a 1 m leaf's 0.3 Hz modes took ARPACK ~1e4 steps at 1e-6)
        diagonal = K_full.diagonal()[I]
        sigma = -SHIFT * float(diagonal.mean() / M.diagonal().mean())
    else:
        sigma = (2 * np.pi * shift_hz) ** 2 * np.sign(shift_hz)
    # one factorization of K - sigma M for every Lanczos step; SPD for sigma < 0 (Cholesky),
    # indefinite for a positive shift
    kind = "spd" if sigma < 0 and prestress is None else "symmetric"
    shifted = _shifted(K_full, M_upper, sigma, owned)
    del K_full  # shift-invert Lanczos multiplies by M and (K - sigma M)^-1 only
    with BlockFactorization(shifted, I, kind) as solve:
        del shifted  # the factorization keeps what it needs
        op = spla.LinearOperator(M.shape, matvec=solve, matmat=solve, dtype=float)
        eigvals, vectors = spla.eigsh(_shape_only(M.shape), k=n, M=M, sigma=sigma, which="LM",
                                      OPinv=op, tol=1e-10)
    order = np.argsort(eigvals)
    eigvals, vectors = eigvals[order], vectors[:, order]
    # normalise phi.M.phi = 1 exactly (eigsh returns M-orthonormal vectors up to its tolerance)
    vectors = vectors / np.sqrt(np.einsum("ij,ij->j", vectors, M @ vectors))

    shapes = np.zeros((n, model.n_dofs))
    shapes[:, I] = vectors.T
    influence = np.zeros((model.dim, model.n_dofs))
    for i, idx in enumerate(component_indices(model)):
        influence[i, idx] = 1.0
    M_influence = symmetric_matvec(model.mass_upper, influence.T)  # (n_dofs, dim)
    participation = shapes @ M_influence  # (n, dim)
    total_mass = float(influence[0] @ M_influence[:, 0])
    frequencies = np.sqrt(np.clip(eigvals, 0.0, None)) / (2 * np.pi)
    memory.release_freed()  # the factorization's leftovers
    return Modes(model, frequencies, shapes, participation ** 2, total_mass, solve.backend)


def _shifted(K, M, sigma: float, owned: bool):
    """K - sigma M, both upper triangles (CSR, sorted); on ``K``'s arrays when ``owned`` and
    K and M share their pattern (as the model assembles them), indices then shared with M."""
    same = (K.shape == M.shape and np.array_equal(K.indptr, M.indptr)
            and np.array_equal(K.indices, M.indices))
    if not same:
        return symmetric.upper(K - sigma * M)
    data = K.data if owned else K.data.copy()
    data -= sigma * M.data
    return sp.csr_matrix((data, M.indices, M.indptr), shape=K.shape)


def _shape_only(shape) -> spla.LinearOperator:
    """The operator K for eigsh's shift-invert mode, which reads its shape only (ARPACK's
    mode 3 multiplies by M and by OPinv = (K - sigma M)^-1); a product with it is an error."""
    def refuse(x):
        raise RuntimeError("shift-invert Lanczos does not multiply by K")
    return spla.LinearOperator(shape, matvec=refuse, dtype=float)
