"""The result of an incremental linearised buckling analysis about a converged state
(:class:`StateBuckling`), the continuum's and both beam models' alike; numpy only."""
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True, eq=False)
class StateBuckling:
    """Incremental linearised buckling about a converged state
    (:func:`flexfem.fem.analyses.solve_incremental_buckling`), the continuum's and both beam
    models' alike.

    Attributes
    ----------
    model : Model, BeamModel or Beam3DModel
        The model solved.
    load_factors : ndarray
        (k,) the lowest positive multiples lambda (-) of the added loads P at which
        K_T(state) + lambda K_G(state, P) is singular, ascending.
    shapes : ndarray
        The buckling shapes, scaled to a largest translation of 1 (m per m; arbitrary sign):
        (k, n_dofs) on the continuum, (k, n_nodes, dofs per node) on a beam model.
    increment : ndarray
        The state's linear response to P at lambda = 1 (m, rad): a DOF vector on the
        continuum, (n_nodes, dofs per node) on a beam model.
    step : int or None
        The step of the path the state is (None: a DOF vector or a linear state).
    """

    model: object
    load_factors: np.ndarray
    shapes: np.ndarray
    increment: np.ndarray
    step: int | None = None
