"""How far a density design's spring displacement (or compliance) may differ from its
body-fitted shape's, from first-order perturbation of the stiffness: changing element moduli
by dE changes the spring displacement l.u by -sum_e dE_e lam_e^T k_e u_e (lam: the spring's
adjoint, k_e: the unit-modulus element stiffness; with large displacements lam_e . g_e, g_e
the element's internal force at unit modulus, lam the adjoint of the tangent) and the
compliance f.u likewise with lam = u. Two changes separate the models: every element
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


def _sensitivity(d, density, spring, case):
    """(l.u (m or J), d(l.u)/dE_e (m/Pa or J/Pa)) for l the spring's vector, or the
    load of ``case`` where ``spring`` is None (the compliance): with small displacements
    -lam_e^T k_e u_e; with large ones -lam_e . g_e(u_e), g_e the element's unit-modulus
    internal force at the converged state and lam the adjoint of its tangent
    (large_displacement.py)."""
    interp = d.problem.interpolation
    E = interp.modulus(density)
    l = d.forces[:, case - 1] if spring is None else d.spring_vectors[spring]
    if d.large is None:
        sol = d.system.solve(E, np.column_stack([d.forces[:, case - 1], l]))
        return float(l @ sol[:, 0]), -d.system.element_products(sol[:, 1], sol[:, 0])
    state = d.large.equilibrium(E, density, interp.derivative(density))
    return float(l @ state.u), d.large.gradient(state, l, by_modulus=True)


def body_fitted_tolerance(problem, density: np.ndarray, spring: str | None = "output",
                          case: int = 1) -> dict:
    """For the physical ``density`` (by element) of ``problem``: ``u`` (the density model's
    spring displacement in load case ``case``, m; with ``spring`` None its compliance, J, and
    so the units below), ``threshold_shift`` (m, the predicted change on thresholding),
    ``boundary`` (m, the outline's half-element uncertainty), ``tolerance`` (m: |shift| +
    boundary), ``grey_fraction`` (elements with 0.05 < rho < 0.95) and ``boundary_share``
    (the boundary elements' share of sum E_e |s_e|, s_e = du/dE_e)."""
    d = Discrete(problem)
    interp = problem.interpolation
    u, s = _sensitivity(d, density, spring, case)
    solid = density > 0.5
    shift = float(np.sum((interp.modulus(solid.astype(float)) - interp.modulus(density)) * s))
    band = _boundary(solid, problem.grid)
    boundary = float(0.5 * (interp.E0 - interp.Emin) * np.sum(np.abs(s[band])))
    weight = interp.modulus(density) * np.abs(s)
    return {"u": u, "threshold_shift": shift,
            "boundary": boundary, "tolerance": abs(shift) + boundary,
            "grey_fraction": float(np.mean((density > 0.05) & (density < 0.95))),
            "boundary_share": float(weight[band].sum() / weight.sum()) if weight.sum() else 0.0}
