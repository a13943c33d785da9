"""How far a density design's spring displacement may differ from its body-fitted shape's,
from first-order perturbation of the stiffness: changing element moduli by dE changes the
spring displacement u = l.u by du = -sum_e dE_e lam_e^T k_e u_e (lam: the spring's adjoint,
k_e: the unit-modulus element stiffness). Two changes separate the models: every element
thresholded at 0.5 (grey elements become solid or void: a signed shift), and the outline
crossing the boundary elements of the thresholded design (each one's solid share uncertain
by a half: a magnitude)."""
import numpy as np

from .model import Discrete


def _boundary(solid: np.ndarray, grid) -> np.ndarray:
    """Elements whose thresholded state differs from one of their four neighbours."""
    s = solid.reshape(grid.nelx, grid.nely)
    edge = np.zeros_like(s)
    edge[1:, :] |= s[1:, :] != s[:-1, :]
    edge[:-1, :] |= s[:-1, :] != s[1:, :]
    edge[:, 1:] |= s[:, 1:] != s[:, :-1]
    edge[:, :-1] |= s[:, :-1] != s[:, 1:]
    return edge.ravel()


def body_fitted_tolerance(problem, density: np.ndarray, spring: str = "output") -> dict:
    """For the physical ``density`` (by element) of ``problem``: ``u`` (the density model's
    spring displacement, m), ``threshold_shift`` (m, the predicted change on thresholding),
    ``boundary`` (m, the outline's half-element uncertainty), ``tolerance`` (m: |shift| +
    boundary), ``grey_fraction`` (elements with 0.05 < rho < 0.95) and ``boundary_share``
    (the boundary elements' share of sum E_e |s_e|, s_e = du/dE_e)."""
    d = Discrete(problem)
    interp = problem.interpolation
    rhs = np.column_stack([d.force, d.spring_vectors[spring]])
    sol = d.system.solve(interp.modulus(density), rhs)
    s = -d.system.element_products(sol[:, 1], sol[:, 0])  # du / dE_e, m/Pa
    solid = density > 0.5
    shift = float(np.sum((interp.modulus(solid.astype(float)) - interp.modulus(density)) * s))
    band = _boundary(solid, problem.grid)
    boundary = float(0.5 * (interp.E0 - interp.Emin) * np.sum(np.abs(s[band])))
    weight = interp.modulus(density) * np.abs(s)
    return {"u": float(d.spring_vectors[spring] @ sol[:, 0]), "threshold_shift": shift,
            "boundary": boundary, "tolerance": abs(shift) + boundary,
            "grey_fraction": float(np.mean((density > 0.05) & (density < 0.95))),
            "boundary_share": float(weight[band].sum() / weight.sum()) if weight.sum() else 0.0}
