"""Modal analysis of a spatial beam model: ``solve_beam3d_modes(model, supports, n)``.

Consistent mass (translational, rotary and torsional inertia, element.py), supports and
rigid links eliminated; about the undeformed state, or about a converged nonlinear state
(``about=``: its tangent, stress stiffening included, and the masses turned with it).
"""
import numpy as np
import scipy.sparse.linalg as spla

from ..assembly import DENSE_EIGEN_LIMIT
from ..modal import BeamModes, dense_lowest_modes, negative_shift
from .assembly import SpatialAssembler, mass_matrix, symmetric_tangent
from .model import Beam3DModel


def solve_beam3d_modes(model: Beam3DModel, supports, n: int = 6, about=None,
                       loads=()) -> BeamModes:
    """The ``n`` lowest natural frequencies (Hz) and mode shapes; supports: NodeFixed/NodePrescribed
    (held); about: a Beam3DState from solve_beam3d_nonlinear with the same supports and
    ``loads`` (default: undeformed; see assembly.symmetric_tangent)."""
    if not (isinstance(n, (int, np.integer)) and not isinstance(n, bool) and n >= 1):
        raise ValueError(f"n = {n!r} must be an integer >= 1")
    asm = SpatialAssembler(model, supports, loads)
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
    return BeamModes(model=model, frequencies_hz=freq, shapes=full.reshape(n, -1, 6),
                       masses=(gamma**2, total))
