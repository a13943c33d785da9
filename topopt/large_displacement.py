"""Large-displacement equilibrium of a density design and the adjoint gradients of the
responses that are linear in its displacements (a spring's displacement, the end compliance
f.u). Geometric nonlinearity only: St. Venant-Kirchhoff, exact for large rotations with small
strains, as in flexure mechanisms.

Residual R(u, rho) = sum_e E(rho_e) g_e(u, gamma(rho_e)) + K_springs u - f = 0, solved by Newton
with the consistent tangent, from the state of the nearest of the last designs (a design
changes little per iteration; the robust formulation's three designs each find their own)
or, where that fails, in load increments from zero. For a response c = l.u the
adjoint K_T lambda = l, with the converged state's factorised tangent, gives
dc/drho_e = -lambda_e . dR_e/drho_e (Buhl, Pedersen & Sigmund 2000, Struct Multidisc Optim
19:93-104).
"""
from dataclasses import dataclass

import numpy as np

from ..fem.newton import newton
from ..fem.stepping import StepFailed, march
from .element import element_stiffness
from .large_strain import LargeStrainQ4, centre_stress, energy_gamma, interpolated
from .responses import pnorm

# converged states kept as Newton's starts: one for each of the robust formulation's designs
WARM_STARTS = 3


class EquilibriumFailed(ValueError):
    """Newton found no equilibrium down to the smallest load increment (a ValueError, as
    the solvers' NonConvergenceError: the command reports it in one line; the iterations
    before it stay in state.npz)."""


@dataclass(frozen=True)
class Nonlinear:
    """Large-displacement analysis: ``steps`` load increments when a state is computed from
    zero, at most ``max_iterations`` Newton iterations per increment, converged when the
    residual is below ``tolerance`` times the applied force."""

    steps: int = 10
    max_iterations: int = 25
    tolerance: float = 1e-8

    def __post_init__(self):
        if isinstance(self.steps, bool) or not isinstance(self.steps, int) or \
                not 1 <= self.steps <= 1000:
            raise ValueError(f"nonlinear.steps = {self.steps!r}: must be an integer, 1 to 1000")
        if isinstance(self.max_iterations, bool) or not isinstance(self.max_iterations, int) \
                or not 2 <= self.max_iterations <= 200:
            raise ValueError(f"nonlinear.max_iterations = {self.max_iterations!r}: must be an "
                             "integer, 2 to 200")
        if not (isinstance(self.tolerance, (int, float)) and 1e-14 <= self.tolerance <= 1e-2):
            raise ValueError(f"nonlinear.tolerance = {self.tolerance!r}: must be in "
                             "[1e-14, 1e-2]")


@dataclass
class LargeState:
    """A converged state: ``u`` (n_dofs; m), ``dR`` (n_elements, 8; N) the derivative of each
    element's residual with respect to its density, ``g`` (n_elements, 8; N/Pa) that with
    respect to its modulus (the unit-modulus internal force), ``increments`` (0: from the previous
    state) and ``iterations`` (Newton iterations in all)."""

    u: np.ndarray
    dR: np.ndarray
    g: np.ndarray
    increments: int
    iterations: int


class LargeDisplacement:
    """The nonlinear states of the designs of a :class:`~.model.Discrete` problem (load case
    1); the tangent of the last converged state stays factorised in the problem's system."""

    def __init__(self, discrete, settings: Nonlinear):
        g, p = discrete.grid, discrete.problem
        self.system, self.settings = discrete.system, settings
        self.edofs = g.edofs
        self.element = LargeStrainQ4(g.dx, g.dy, p.nu, p.thickness)
        self.KL = element_stiffness(g.dx, g.dy, 1.0, p.nu, p.thickness)
        self.force = discrete.forces[:, 0]
        self.recent = []      # [(rho, u)] of the last WARM_STARTS designs solved

    def _warm_start(self, rho: np.ndarray):
        """The converged u of the recent design nearest to ``rho`` (largest density
        difference), None before the first."""
        if not self.recent:
            return None
        return min(self.recent, key=lambda s: float(np.max(np.abs(s[0] - rho))))[1]

    def _remember(self, rho: np.ndarray, u: np.ndarray) -> None:
        """Keep (rho, u) as the warm start of the designs near rho, replacing the nearest
        recent one where it is as near as the designs of one iteration are (a move)."""
        if self.recent:
            gaps = [float(np.max(np.abs(s[0] - rho))) for s in self.recent]
            j = int(np.argmin(gaps))
            if len(self.recent) >= WARM_STARTS or gaps[j] == 0.0:
                self.recent.pop(j)
        self.recent.append((rho.copy(), u))

    def _residual(self, u, E, gamma, factor):
        """(R (n_dofs; N, zero at fixed DOFs), the tangent's element matrices, the elements'
        unit-modulus forces g and dg/dgamma)."""
        g, Kt, dg = interpolated(self.element, self.KL, u[self.edofs], gamma)
        n = self.system.grid.n_dofs
        r = np.bincount(self.edofs.ravel(), weights=(E[:, None] * g).ravel(), minlength=n)
        r += self.system.spring_diagonal * u - factor * self.force
        r[self.system.fixed] = 0.0
        return r, E[:, None, None] * Kt, g, dg

    def _newton(self, u, E, gamma, factor):
        """(u, iterations, g, dg/dgamma at u) at load ``factor``, the tangent at u
        factorised; None on failure (fem/newton.py's driver and divergence rule)."""
        s = self.settings

        def residual(u):
            r, K, g, dg = self._residual(u, E, gamma, factor)
            if np.all(np.isfinite(r)):
                self.system.factor_elements(K)  # kept: the adjoint solves use it
            return r, max(np.linalg.norm(factor * self.force), 1e-300), (g, dg)

        try:
            found = newton(u, residual, lambda u, r, state: -self.system.resolve(r)[:, 0],
                           tol=s.tolerance, max_iterations=s.max_iterations)
        except StepFailed:   # diverged, or the tangent lost definiteness: a limit point
            return None
        return found.x, found.iterations, *found.state

    def equilibrium(self, E: np.ndarray, rho: np.ndarray, dE: np.ndarray) -> LargeState:
        """The state of the design of moduli ``E`` (Pa), densities ``rho``, dE/drho ``dE``."""
        gamma, d_gamma = energy_gamma(rho)
        start = self._warm_start(rho)
        found = self._newton(start, E, gamma, 1.0) if start is not None else None
        increments, iterations = 0, 0
        if found is None:
            found, increments, iterations = self._stepped(E, gamma)
        u, it, g, dg = found
        self._remember(rho, u)
        dR = dE[:, None] * g + (E * d_gamma)[:, None] * dg
        return LargeState(u, dR, g, increments, iterations + it)

    def _stepped(self, E, gamma):
        """Load increments from zero by fem/stepping.py's driver: a failed increment halved
        down to 1/64 of the first, a cut one doubled back after two good ones."""
        steps = self.settings.steps
        done = {"u": np.zeros(self.system.grid.n_dofs), "found": None, "count": 0,
                "iterations": 0}

        def advance(t, dt, cuts_here):
            target = 1.0 if t + dt >= 1.0 - 1e-12 else t + dt
            found = self._newton(done["u"], E, gamma, target)
            if found is None:
                raise StepFailed("Newton failed", [])
            done.update(u=found[0], found=found, count=done["count"] + 1,
                        iterations=done["iterations"] + found[1])
            return False

        def failed(t, dt, cuts, failure):
            return EquilibriumFailed(
                f"nonlinear: no equilibrium beyond load factor {t:.4g} (Newton failed down to "
                "1/64 of a load step); the design may snap through or the load is too large "
                "for it; try more nonlinear.steps or a smaller load")

        march(advance, steps, 1.0 / (64 * steps), failed)
        u, _, g, dg = done["found"]
        return (u, 0, g, dg), done["count"], done["iterations"]

    def gradient(self, state: LargeState, l: np.ndarray, by_modulus: bool = False):
        """d(l.u)/drho_e for a fixed vector l (n_dofs), by one adjoint solve with the
        factorised tangent of ``state`` (the last computed); with ``by_modulus``
        d(l.u)/dE_e (m/Pa per unit of l) at fixed gamma."""
        lam = self.system.resolve(l)[:, 0]
        return -np.einsum("ei,ei->e", lam[self.edofs], state.g if by_modulus else state.dR)

    def stress(self, state: LargeState, rho: np.ndarray, E0: float, r):
        """The p-norm (Pa) of the elements' relaxed von Mises stresses rho^q sigma_vm of the
        large-displacement state (second Piola-Kirchhoff, at the element centres, of the
        solid of modulus ``E0``), and its gradient by one adjoint solve."""
        vm, d_vm = centre_stress(self.element, E0, state.u[self.edofs])
        q, t = r.relaxation, rho**r.relaxation * vm
        value, weights = pnorm([t], r.pnorm)
        if value == 0.0:
            return 0.0, np.zeros(rho.size)
        w = weights[0]
        g = np.where(rho > 0, w * q * t / np.where(rho > 0, rho, 1.0), 0.0)
        dP_du = np.bincount(self.edofs.ravel(), weights=((w * rho**q)[:, None] * d_vm).ravel(),
                            minlength=self.system.grid.n_dofs)
        return value, g + self.gradient(state, dP_du)
