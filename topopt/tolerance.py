"""How far a density design's spring displacement may differ from its body-fitted shape's,
from first-order perturbation of the stiffness: changing element moduli by dE changes the
spring displacement u = l.u by du = -sum_e dE_e lam_e^T k_e u_e (lam: the spring's adjoint,
k_e: the unit-modulus element stiffness; with large displacements lam_e . g_e, g_e the
element's internal force at unit modulus, lam the adjoint of the tangent). Two changes separate the models: every element
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


def _sensitivity(d, density, spring):
    """(u (n_dofs; m), du_spring/dE_e (m/Pa)): with small displacements -lam_e^T k_e u_e;
    with large ones -lam_e . g_e(u_e), g_e the element's unit-modulus internal force at the
    converged state and lam the adjoint of its tangent (large_displacement.py)."""
    interp = d.problem.interpolation
    E = interp.modulus(density)
    if d.large is None:
        sol = d.system.solve(E, np.column_stack([d.force, d.spring_vectors[spring]]))
        return sol[:, 0], -d.system.element_products(sol[:, 1], sol[:, 0])
    state = d.large.equilibrium(E, density, np.ones_like(density))
    return state.u, d.large.gradient(state, d.spring_vectors[spring], by_modulus=True)


def body_fitted_tolerance(problem, density: np.ndarray, spring: str = "output") -> dict:
    """For the physical ``density`` (by element) of ``problem``: ``u`` (the density model's
    spring displacement, m), ``threshold_shift`` (m, the predicted change on thresholding),
    ``boundary`` (m, the outline's half-element uncertainty), ``tolerance`` (m: |shift| +
    boundary), ``grey_fraction`` (elements with 0.05 < rho < 0.95) and ``boundary_share``
    (the boundary elements' share of sum E_e |s_e|, s_e = du/dE_e)."""
    d = Discrete(problem)
    interp = problem.interpolation
    u, s = _sensitivity(d, density, spring)
    solid = density > 0.5
    shift = float(np.sum((interp.modulus(solid.astype(float)) - interp.modulus(density)) * s))
    band = _boundary(solid, problem.grid)
    boundary = float(0.5 * (interp.E0 - interp.Emin) * np.sum(np.abs(s[band])))
    weight = interp.modulus(density) * np.abs(s)
    return {"u": float(d.spring_vectors[spring] @ u), "threshold_shift": shift,
            "boundary": boundary, "tolerance": abs(shift) + boundary,
            "grey_fraction": float(np.mean((density > 0.05) & (density < 0.95))),
            "boundary_share": float(weight[band].sum() / weight.sum()) if weight.sum() else 0.0}
