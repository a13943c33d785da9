"""Where a spatial beam model stores the strain energy of its mode shapes (or of any
displacements): per element, linearised about the undeformed state.

    share = strain_energy_share(model, modes.shapes, elements=range(100, 200))
"""
import numpy as np

from .element import local_matrices, to_global


def element_energies(model, shapes) -> np.ndarray:
    """(n, n_e) strain energy (J) of every element under each of ``shapes`` ((n, n_nodes,
    6) or (n, n_dofs): displacements m, rotations rad), u_e^T K_e u_e / 2 with the linear
    element stiffness."""
    u = np.asarray(shapes, dtype=float).reshape(len(shapes), -1)
    if u.shape[1] != model.n_dofs:
        raise ValueError(f"shapes: {u.shape[1]} values each, the model has {model.n_dofs} DOFs")
    K, _ = local_matrices(model)
    E = to_global(model.frames)
    dofs = (6 * model.elements[:, :, None] + np.arange(6)).reshape(-1, 12)
    local = np.einsum("eji,nej->nei", E, u[:, dofs])  # element DOFs in local axes
    return 0.5 * np.einsum("nei,eij,nej->ne", local, K, local)


def strain_energy_share(model, shapes, elements) -> np.ndarray:
    """(n,) share (0-1) of each shape's strain energy in ``elements`` (indices)."""
    e = element_energies(model, shapes)
    return e[:, np.asarray(elements, dtype=int)].sum(axis=1) / e.sum(axis=1)
