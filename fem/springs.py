"""Springs outside the mesh: a linear spring between the mean displacements of two groups,
such as an actuator rod between two pads, as a stiffness matrix to add to a model's
(:meth:`~flexfem.fem.model.Model.with_stiffness`)."""
import numpy as np
import scipy.sparse as sp

from .harmonic import mean_weights
from .model import Model

_AXES = {"x": 0, "y": 1, "z": 2}


def _axis(model: Model, stiffness, component: str) -> int:
    if not (isinstance(stiffness, (int, float)) and np.isfinite(stiffness) and stiffness > 0):
        raise ValueError(f"stiffness = {stiffness!r} must be a finite number > 0 (N/m)")
    if _AXES.get(component, model.dim) >= model.dim:
        raise ValueError(f"component = {component!r} must be one of "
                         f"{list(_AXES)[:model.dim]} for a {model.dim}-D model")
    return _AXES[component]


def _matrix(model: Model, w: np.ndarray, stiffness: float) -> sp.csr_matrix:
    """k w w^T (N/m) as a sparse n_dofs x n_dofs matrix."""
    idx = np.flatnonzero(w)
    values = stiffness * np.outer(w[idx], w[idx]).ravel()
    rows, cols = np.repeat(idx, len(idx)), np.tile(idx, len(idx))
    return sp.coo_matrix((values, (rows, cols)), shape=(model.n_dofs, model.n_dofs)).tocsr()


def group_spring(model: Model, group_a: str, group_b: str, stiffness: float,
                 component: str = "x") -> sp.csr_matrix:
    """Stiffness matrix (N/m) of a spring of ``stiffness`` (N/m) between the mean
    ``component`` displacements of ``group_a`` and ``group_b``: k w w^T, with w . u the
    stretch (mean of ``group_b`` minus mean of ``group_a``)."""
    i = _axis(model, stiffness, component)
    return _matrix(model, mean_weights(model, group_b)[i] - mean_weights(model, group_a)[i],
                   stiffness)


def ground_spring(model: Model, group: str, stiffness: float,
                  component: str = "x") -> sp.csr_matrix:
    """Stiffness matrix (N/m) of a spring of ``stiffness`` (N/m) from the ground to the mean
    ``component`` displacement of ``group``: k w w^T, with w . u that mean."""
    return _matrix(model, mean_weights(model, group)[_axis(model, stiffness, component)],
                   stiffness)
