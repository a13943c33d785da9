"""One design's responses and their gradients, as the optimiser takes them."""
from dataclasses import dataclass

import numpy as np


@dataclass
class DesignResponses:
    """Responses of one design: values and gradients with respect to the design variables."""

    objective: float
    objective_grad: np.ndarray
    constraints: np.ndarray       # each response's value, in its own units
    constraint_grads: np.ndarray  # (n_constraints, n_variables)
    physical: np.ndarray
    u: np.ndarray                 # load case 1's displacements (m)
    displacements: dict           # each spring's, load case 1
    compliances: np.ndarray       # f_k.u_k of every load case (J)
    designs: dict | None = None   # robust: each design's objective and volume
