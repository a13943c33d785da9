"""A problem made numeric: the stiffness system, load vector, filter, design map and the
responses with their gradients (one factorisation per design, state and adjoints together)."""
from functools import cached_property

import numpy as np
import scipy.sparse as sp

from .element import element_mass, element_stiffness, von_mises_matrix
from .fea import System
from .large_displacement import LargeDisplacement
from .filters import Filter
from .problem import Problem
from .projection import project, project_derivative
from .evaluation import DesignResponses
from .responses import RESPONSES, State
from .robust_model import robust_evaluate

AXIS = {"x": 0, "y": 1}


def design_map(grid, symmetry: tuple) -> sp.csr_matrix:
    """P (n_elements x n_variables): element densities = P @ design variables, one variable
    per orbit of the mirror symmetries ('x': about the vertical mid-line x = lx/2, 'y':
    about the horizontal one)."""
    ix, iy = np.divmod(np.arange(grid.n_elements), grid.nely)
    rep = np.arange(grid.n_elements)
    if "x" in symmetry:
        rep = np.minimum(rep, (grid.nelx - 1 - ix) * grid.nely + iy)
    if "y" in symmetry:
        rep = np.minimum(rep, ix * grid.nely + (grid.nely - 1 - iy))
    if "x" in symmetry and "y" in symmetry:
        rep = np.minimum(rep, (grid.nelx - 1 - ix) * grid.nely + (grid.nely - 1 - iy))
    _, column = np.unique(rep, return_inverse=True)
    return sp.csr_matrix((np.ones(grid.n_elements), (np.arange(grid.n_elements), column.ravel())))


class Discrete:
    """The numeric form of a :class:`Problem`."""

    def __init__(self, problem: Problem):
        self.problem = p = problem
        g = p.grid
        self.grid = g
        KE = element_stiffness(g.dx, g.dy, 1.0, p.nu, p.thickness)
        fixed = [2 * n + AXIS[d] for s in p.supports for n in s.where.nodes(g) for d in s.fix]
        springs, self.spring_vectors = {}, {}
        for s in p.springs:
            dofs = 2 * s.where.nodes(g) + AXIS[s.dof]
            for dof in dofs:
                springs[dof] = springs.get(dof, 0.0) + s.stiffness / dofs.size
            self.spring_vectors[s.name] = np.bincount(dofs, minlength=g.n_dofs) / dofs.size
        self.system = System(g, KE, np.array(fixed, dtype=int), springs)
        self.forces = np.zeros((g.n_dofs, p.n_cases))
        for load in p.loads:
            nodes = load.where.nodes(g)
            for axis in (0, 1):
                np.add.at(self.forces[:, load.case - 1], 2 * nodes + axis,
                          load.force[axis] / nodes.size)
        self.force = self.forces[:, 0]
        self.filter = Filter(g, p.filter_kind, p.radius)
        self.P = design_map(g, p.symmetry)
        self.lower, self.upper = self._bounds()
        self.beta = p.projection.beta if p.projection else None
        self.large = LargeDisplacement(self, p.nonlinear) if p.nonlinear else None
        self.volume_ratio = 1.0   # robust: the intermediate over the dilated volume

    def _bounds(self):
        """Bounds of the design variables: passive elements pinned at 0 or 1."""
        lo, hi = np.zeros(self.grid.n_elements), np.ones(self.grid.n_elements)
        self.solid = np.zeros(self.grid.n_elements, dtype=bool)
        self.void = np.zeros(self.grid.n_elements, dtype=bool)
        for region in self.problem.passive:
            e = region.where.elements(self.grid)
            (self.solid if region.value == "solid" else self.void)[e] = True
        lo[self.solid], hi[self.void] = 1.0, 0.0
        hi[self.solid], lo[self.void] = 1.0, 0.0
        count = np.asarray(self.P.sum(axis=0)).ravel()
        return (self.P.T @ lo) / count, (self.P.T @ hi) / count

    @cached_property
    def ME(self) -> np.ndarray:
        """The element mass matrix of unit mass density (8 x 8, kg per kg/m^3)."""
        g = self.grid
        return element_mass(g.dx, g.dy, self.problem.thickness)

    @cached_property
    def mass_map(self):
        """Element mass factors to the reduced mass matrix's values (System.element_map)."""
        return self.system.element_map(self.ME)

    @cached_property
    def S(self) -> np.ndarray:
        """u_e^T S u_e: the squared von Mises stress (Pa^2) at a solid element's centre."""
        p = self.problem
        return von_mises_matrix(self.grid.dx, self.grid.dy, p.interpolation.E0, p.nu)

    @property
    def n_variables(self) -> int:
        return self.P.shape[1]

    def initial(self) -> np.ndarray:
        """top88's start: every variable at the volume limit (0.5 without one)."""
        p = self.problem
        start = p.initial or p.volume_limit or 0.5
        return np.clip(np.full(self.n_variables, float(start)), self.lower, self.upper)

    def physical(self, z: np.ndarray, filtered: np.ndarray | None = None,
                 eta: float | None = None) -> np.ndarray:
        """Physical densities of the elements from design variables z (filtered, then
        projected at ``self.beta`` where the problem has a projection, at the threshold
        ``eta``, default the problem's); ``filtered``: the filtered densities of z, if
        known."""
        rho = self.filter.physical(self.P @ z) if filtered is None else filtered.copy()
        if self.beta is not None:
            rho = project(rho, self.beta, self.problem.projection.eta if eta is None else eta)
        rho[self.solid], rho[self.void] = 1.0, 0.0
        return rho

    @cached_property
    def _volume_weights(self):
        """(w, c): the volume fraction is w @ z + c where the filter is linear and there is
        no projection."""
        free = ~(self.solid | self.void)
        w = self.P.T @ self.filter.back(None, free / free.size)
        return w, float(np.sum(self.solid)) / free.size

    def volume(self, z: np.ndarray) -> float:
        """The volume fraction (mean physical density) of design variables z."""
        if self.beta is not None:
            return float(self.physical(z).mean())
        w, c = self._volume_weights
        return float(w @ z) + c

    def back(self, x: np.ndarray, g: np.ndarray, objective: bool = False,
             filtered: np.ndarray | None = None, eta: float | None = None) -> np.ndarray:
        """The gradient with respect to the design variables of a function whose gradient
        with respect to the physical densities is g (x: the element design densities;
        ``filtered``: their filtered values, if known; ``eta``: the projection's threshold,
        default the problem's)."""
        if self.beta is not None:
            filtered = self.filter.physical(x) if filtered is None else filtered
            eta = self.problem.projection.eta if eta is None else eta
            g = g * project_derivative(filtered, self.beta, eta)
        return self.P.T @ self.filter.back(x, g, objective=objective)

    def _linear_state(self, rho, E, dE) -> State:
        """The displacements of every load case and the adjoints of the springs named by
        a displacement response, one factorisation for all; where a displacement response
        is without the springs, those of the structure alone first, by a factorisation of
        its own (the one with springs stays the last, for the modes' and stress adjoints)."""
        p = self.problem
        responses = [p.objective] + [c.response for c in p.constraints]
        cases = self.forces.shape[1]
        free = sorted({r.spring for r in responses if r.kind == "displacement"
                       and not r.springs})
        free_U = free_adjoints = None
        if free:
            rhs = np.column_stack([self.forces] + [self.spring_vectors[n] for n in free])
            sol = self.system.solve_without_springs(E, rhs)
            free_U, free_adjoints = sol[:, :cases], dict(zip(free, sol[:, cases:].T))
        names = sorted({r.spring for r in responses if r.kind == "displacement"
                        and r.springs})
        rhs = np.column_stack([self.forces] + [self.spring_vectors[n] for n in names])
        sol = self.system.solve(E, rhs)
        return State(rho, E, dE, sol[:, :cases], dict(zip(names, sol[:, cases:].T)),
                     free_U, free_adjoints)

    def _large_response(self, large, state: State, r):
        """A response of the large-displacement state: l.u with l a spring's vector
        (displacement) or the load (end compliance f.u), by its adjoint; the stress norm; or
        the volume."""
        if r.kind == "volume":
            return RESPONSES["volume"](self, state, r)
        if r.kind == "stress":
            return self.large.stress(large, state.rho, self.problem.interpolation.E0, r)
        l = self.spring_vectors[r.spring] if r.kind == "displacement" else self.forces[:, 0]
        return float(l @ large.u), self.large.gradient(large, l)

    def responses(self, rho: np.ndarray) -> tuple:
        """(state, displacements, objective, its gradient, constraint values, their
        gradients) of physical densities ``rho``, the gradients with respect to rho (pinned
        elements 0), the objective's of sign * objective (sign 1 for 'min', -1 for 'max')."""
        p = self.problem
        interp = p.interpolation
        E, dE = interp.modulus(rho), interp.derivative(rho)
        large = None if self.large is None else self.large.equilibrium(E, rho, dE)
        state = (self._linear_state(rho, E, dE) if large is None else
                 State(rho, E, dE, large.u[:, None], {}))
        pinned = self.solid | self.void
        u = state.U[:, 0]
        disp = {n: float(v @ u) for n, v in self.spring_vectors.items()}

        def value_grad(r):
            value, g = (RESPONSES[r.kind](self, state, r) if large is None
                        else self._large_response(large, state, r))
            g[pinned] = 0.0
            return value, g

        f0, g0 = value_grad(p.objective)
        g0 = (1.0 if p.sense == "min" else -1.0) * g0
        pairs = [value_grad(c.response) for c in p.constraints]
        return (state, disp, f0, g0, [v for v, _ in pairs], [g for _, g in pairs])

    def evaluate(self, z: np.ndarray) -> DesignResponses:
        """All responses at z, one factorisation for the states of every load case and
        every adjoint (three, one a design, with the robust formulation)."""
        if self.problem.robust is not None:
            return robust_evaluate(self, z)
        x = self.P @ z
        filtered = self.filter.physical(x)
        rho = self.physical(z, filtered)
        state, disp, f0, g0, values, grads = self.responses(rho)
        g0 = self.back(x, g0, objective=True, filtered=filtered)
        grads = np.array([self.back(x, g, filtered=filtered) for g in grads])
        grads = grads.reshape(len(values), self.n_variables)
        compliances = np.einsum("ik,ik->k", self.forces, state.U)
        return DesignResponses(f0, g0, np.array(values), grads, rho, state.U[:, 0], disp,
                               compliances)
