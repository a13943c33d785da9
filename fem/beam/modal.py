"""Modal analysis of a beam model: ``solve_beam_modes(model, supports, n)``.

Consistent mass (translational and rotary inertia, same shape functions as the stiffness),
supports and rigid links eliminated; about the undeformed state, or about a converged
nonlinear state (``about=``, its tangent stiffness: stress stiffening included).
"""
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.linalg as sla
import scipy.sparse.linalg as spla

from .assembly import (DENSE_EIGEN_LIMIT, ORDERING, BeamAssembler, SingularBeamError,
                       element_mass, load_vector, mass_matrix, point_mass_diagonal)
from .eigen import lowest_modes
from .linear import held_at_zero, linear_system, modal_system
from .model import BeamModel

# unknowns from which the undeformed modes are found by block Lanczos on the cached factor:
# the dense solver's cost grows as N^3 (measured, 6 modes of a cantilever: 7 ms against 2 ms
# at 300 unknowns, 62 against 3.6 ms at 900; about equal at 100)
KRYLOV_FROM = 100


@dataclass(frozen=True, eq=False)
class BeamModes:
    """Modes of a planar or spatial beam model. frequencies_hz : (n,) ascending (Hz);
    shapes : (n, n_nodes, DOFs a node) mass-normalised mode shapes (planar u, v, theta;
    spatial u_x, u_y, u_z, r_x, r_y, r_z); effective_mass : (n, dim) effective modal mass
    (kg) along the axes; total_mass : kg (planar: these two on first use, most analyses read
    the frequencies; ``masses`` (effective_mass, total_mass) where computed with the modes)."""

    model: object
    frequencies_hz: np.ndarray
    shapes: np.ndarray
    masses: tuple | None = None

    @cached_property
    def _masses(self) -> tuple:
        if self.masses is not None:
            return self.masses
        MT = _mass_translations(self.model)
        gamma = self.shapes.reshape(len(self.shapes), -1) @ MT
        return gamma**2, float(MT[0::3, 0].sum())

    @property
    def effective_mass(self) -> np.ndarray:
        return self._masses[0]

    @property
    def total_mass(self) -> float:
        return self._masses[1]

    @property
    def effective_mass_fraction(self) -> np.ndarray:
        """(n, dim) effective mass over the total mass."""
        return self.effective_mass / self.total_mass

    @property
    def solver(self) -> str:
        return "beam" if self.model.dim == 2 else "beam3d"

    def dominant_direction(self, k: int) -> int:
        """Translation axis (0 = x, 1 = y, 2 = z) with the largest effective mass of mode k."""
        return int(np.argmax(self.effective_mass[k]))

    def vertex_shape(self, k: int) -> np.ndarray:
        """(n_nodes, dim) translations of mode k at the nodes."""
        return self.shapes[k][:, :self.model.dim].copy()



def _state_z(asm, about):
    """Unknowns z and load factor of a converged state (BeamState) ``about``."""
    if about is None:
        return np.zeros(asm.space.n), 0.0
    return about.q.ravel()[asm.space.free], about.load_factor


def negative_shift(k_diag, m_diag) -> float:
    """A shift slightly below zero, (rad/s)^2, from the diagonals of K and M: K - sigma M is
    positive definite where K is semi-definite (a free body)."""
    return -1e-6 * abs(k_diag).max() / max(abs(m_diag).max(), 1e-300)


def dense_lowest_modes(K: np.ndarray, M: np.ndarray, n: int) -> tuple:
    """(w2 (n,) in (rad/s)^2, M-normalised shapes (N, n)): the ``n`` lowest eigenpairs of
    K phi = w2 M phi, solved inverted, M phi = mu (K - sigma M) phi with sigma slightly
    negative, whose largest mu stay accurate where M is nearly singular (a beam's tiny rotary
    inertias: the direct form lost 5e-5 of f1 there). Where K - sigma M is not positive
    definite (a state past buckling) the direct form."""
    size = K.shape[0]
    sigma = negative_shift(np.diag(K), np.diag(M))
    try:
        mu, phi = sla.eigh(M, K - sigma * M, subset_by_index=[size - n, size - 1])
    except np.linalg.LinAlgError:
        return sla.eigh(K, M, subset_by_index=[0, n - 1])
    phi = phi[:, ::-1]
    phi = phi / np.sqrt(np.einsum("ij,ij->j", phi, M @ phi))
    return sigma + 1.0 / mu[::-1], phi


def _mass_translations(model: BeamModel) -> np.ndarray:
    """M [1_x 1_y] (n_dofs, 2): the consistent mass times the unit translations along x and
    y, summed element by element (no global mass matrix)."""
    me = element_mass(model)  # (n_e + n_pairs, 6, 6) global order: u, v, theta at each end
    cols = np.stack([me[:, :, 0] + me[:, :, 3], me[:, :, 1] + me[:, :, 4]], axis=-1)
    dofs = (3 * model.connectivity[:, [0, 0, 0, 1, 1, 1]]
            + np.array([0, 1, 2, 0, 1, 2])).ravel()
    diag = point_mass_diagonal(model)
    out = np.column_stack([np.bincount(dofs, cols[:, :, k].ravel(), model.n_dofs)
                           for k in (0, 1)])
    out[0::3, 0] += diag[0::3]
    out[1::3, 1] += diag[1::3]
    return out


def _check_count(n, n_free):
    if n > n_free:
        raise ValueError(f"n = {n} modes asked for but the model has {n_free} free DOFs")


def _krylov(system, n, j) -> tuple:
    """(w2, phi) by block Lanczos on the cached factor of K (fem/beam/eigen.py), the
    unknowns ``j`` held at zero, or (None, None) where K is singular (a free body: the
    shifted ARPACK below) or it did not converge."""
    try:
        solve = held_at_zero(system, j) if len(j) else system.factor.solve
        out = lowest_modes(solve, system.mass, n, held=j)
    except SingularBeamError:
        return None, None
    return (None, None) if out is None else out


def _modes(K, M, n, n_free) -> tuple:
    """(w2, phi): dense up to DENSE_EIGEN_LIMIT unknowns, else ARPACK shift-inverted about a
    slightly negative shift (K may be singular)."""
    if n_free <= DENSE_EIGEN_LIMIT:
        return dense_lowest_modes(K.toarray(), M.toarray(), n)
    sigma = negative_shift(K.diagonal(), M.diagonal())
    lu = spla.splu((K - sigma * M).tocsc(), permc_spec=ORDERING)
    # plain operators: ARPACK calls them ~200 times, a sparse matrix's wrapper costs more
    shift_invert = spla.LinearOperator(K.shape, matvec=lu.solve, dtype=float)
    mass = spla.LinearOperator(K.shape, matvec=M.tocsr().dot, dtype=float)
    w2, phi = spla.eigsh(K, k=n, M=mass, sigma=sigma, which="LM", OPinv=shift_invert)
    order = np.argsort(w2)
    return w2[order], phi[:, order]


def solve_beam_modes(model: BeamModel, supports, n: int = 6, about=None, loads=()) -> BeamModes:
    """The ``n`` lowest natural frequencies (Hz) and shapes. supports : NodeFixed/NodePrescribed
    (held at their values at ``about``); about : a BeamState from solve_beam_nonlinear (with
    the same supports and ``loads``) to linearise about (default: undeformed)."""
    if not (isinstance(n, (int, np.integer)) and n >= 1):
        raise ValueError(f"n = {n!r} must be an integer >= 1")
    w2 = None
    if about is None:  # the undeformed system, shared with the static solves of the model
        load_vector(model, loads)  # checked only: the undeformed K holds no load
        system, j = modal_system(model, supports)  # j: held unknowns of a larger system
        _check_count(n, system.space.n - len(j))
        if system.space.n - len(j) > KRYLOV_FROM:
            w2, phi = _krylov(system, n, j)
        if w2 is None and len(j):
            system = linear_system(model, supports)
        space, ev, K = system.space, system.ev, system.ev.K
    else:
        asm = BeamAssembler(model, supports, loads)
        ev = asm.evaluate(*_state_z(asm, about))
        space, K = asm.space, ev.K
        _check_count(n, space.n)
    if w2 is None:
        M = space.condense_global(mass_matrix(model), ev.w)
        w2, phi = _modes(K, M, n, space.n)
    full = space.expand(phi, np.zeros(len(space.held)), ev.w).T  # (n, n_dofs)
    freq = np.sqrt(np.maximum(w2, 0.0)) / (2.0 * np.pi)
    return BeamModes(model=model, frequencies_hz=freq, shapes=full.reshape(n, -1, 3))
