"""Modal analysis of a spatial beam model: ``solve_beam3d_modes(model, supports, n)``.

Consistent mass (translational, rotary and torsional inertia, element.py), supports and
rigid links eliminated; about the undeformed state, or about a converged nonlinear state
(``about=``: its tangent, stress stiffening included, and the masses turned with it).
"""
from dataclasses import dataclass

import numpy as np
import scipy.sparse.linalg as spla

from ..assembly import DENSE_EIGEN_LIMIT
from ..modal import dense_lowest_modes, negative_shift
from .assembly import Assembler, mass_matrix, symmetric_tangent
from .model import Beam3DModel


@dataclass(frozen=True, eq=False)
class Beam3DModes:
    """frequencies_hz : (n,) ascending (Hz); shapes : (n, n_nodes, 6) mass-normalised mode
    shapes (u_x, u_y, u_z, r_x, r_y, r_z per node); effective_mass : (n, 3) effective modal
    mass (kg) in x, y and z; total_mass : kg."""

    model: Beam3DModel
    frequencies_hz: np.ndarray
    shapes: np.ndarray
    effective_mass: np.ndarray
    total_mass: float

    @property
    def effective_mass_fraction(self) -> np.ndarray:
        """(n, 3) effective mass over the total mass."""
        return self.effective_mass / self.total_mass

    solver = "beam3d"

    def dominant_direction(self, k: int) -> int:
        """Translation axis (0 = x, 1 = y, 2 = z) with the largest effective mass of mode k."""
        return int(np.argmax(self.effective_mass[k]))

    def vertex_shape(self, k: int) -> np.ndarray:
        """(n_nodes, 3) translations of mode k at the nodes."""
        return self.shapes[k][:, :3].copy()


def solve_beam3d_modes(model: Beam3DModel, supports, n: int = 6, about=None,
                       loads=()) -> Beam3DModes:
    """The ``n`` lowest natural frequencies (Hz) and mode shapes; supports: Fixed/Prescribed
    (held); about: a Beam3DState from solve_beam3d_nonlinear with the same supports and
    ``loads`` (default: undeformed; see assembly.symmetric_tangent)."""
    if not (isinstance(n, (int, np.integer)) and not isinstance(n, bool) and n >= 1):
        raise ValueError(f"n = {n!r} must be an integer >= 1")
    asm = Assembler(model, supports, loads)
    if n > asm.space.n:
        raise ValueError(f"n = {n} modes asked for but the model has {asm.space.n} free DOFs")
    K, T, u, R = symmetric_tangent(asm, about)
    M_full = mass_matrix(model) if about is None else mass_matrix(model, u, R)
    M = (T.T @ M_full @ T).tocsr()
    if asm.space.n <= DENSE_EIGEN_LIMIT:
        w2, phi = dense_lowest_modes(K.toarray(), M.toarray(), n)
    else:
        shift = negative_shift(K.diagonal(), M.diagonal())
        w2, phi = spla.eigsh(K.tocsc(), k=n, M=M.tocsc(), sigma=shift, which="LM")
        order = np.argsort(w2)
        w2, phi = w2[order], phi[:, order]
    full = np.asarray(T @ phi).T  # (n, n_dofs)
    trans = np.zeros((model.n_dofs, 3))
    for k in range(3):
        trans[k::6, k] = 1.0
    gamma = full @ (M_full @ trans)
    total = float(trans[:, 0] @ (M_full @ trans[:, 0]))
    freq = np.sqrt(np.clip(w2, 0.0, None)) / (2.0 * np.pi)
    return Beam3DModes(model=model, frequencies_hz=freq, shapes=full.reshape(n, -1, 6),
                       effective_mass=gamma**2, total_mass=total)
