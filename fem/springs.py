"""Springs outside the mesh: a linear spring between the mean displacements of two groups,
such as an actuator rod between two pads, as a stiffness matrix to add to a model's
(:meth:`~flexfem.fem.model.Model.with_stiffness`)."""
import numpy as np
import scipy.sparse as sp

from .harmonic import mean_weights
from .model import Model

_AXES = {"x": 0, "y": 1, "z": 2}


def group_spring(model: Model, group_a: str, group_b: str, stiffness: float,
                 component: str = "x") -> sp.csr_matrix:
    """Stiffness matrix (N/m) of a spring of ``stiffness`` (N/m) between the mean
    ``component`` displacements of ``group_a`` and ``group_b``: k w w^T, with w . u the
    stretch (mean of ``group_b`` minus mean of ``group_a``)."""
    if not (isinstance(stiffness, (int, float)) and np.isfinite(stiffness) and stiffness > 0):
        raise ValueError(f"stiffness = {stiffness!r} must be a finite number > 0 (N/m)")
    if _AXES.get(component, model.dim) >= model.dim:
        raise ValueError(f"component = {component!r} must be one of "
                         f"{list(_AXES)[:model.dim]} for a {model.dim}-D model")
    i = _AXES[component]
    w = mean_weights(model, group_b)[i] - mean_weights(model, group_a)[i]
    idx = np.flatnonzero(w)
    values = stiffness * np.outer(w[idx], w[idx]).ravel()
    rows, cols = np.repeat(idx, len(idx)), np.tile(idx, len(idx))
    return sp.coo_matrix((values, (rows, cols)), shape=(model.n_dofs, model.n_dofs)).tocsr()
