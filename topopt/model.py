"""A problem made numeric: the stiffness system, load vector, filter, design map and the
responses with their gradients (one factorisation per design, state and adjoints together)."""
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from .element import element_stiffness
from .fea import System
from .filters import Filter
from .problem import Problem
from .projection import project, project_derivative

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


@dataclass
class Evaluation:
    """Responses of one design: values and gradients with respect to the design variables."""

    objective: float
    objective_grad: np.ndarray
    constraints: np.ndarray       # each response's value, in its own units
    constraint_grads: np.ndarray  # (n_constraints, n_variables)
    physical: np.ndarray
    u: np.ndarray
    displacements: dict


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
        self.force = np.zeros(g.n_dofs)
        for load in p.loads:
            nodes = load.where.nodes(g)
            for axis in (0, 1):
                np.add.at(self.force, 2 * nodes + axis, load.force[axis] / nodes.size)
        self.filter = Filter(g, p.filter_kind, p.radius)
        self.P = design_map(g, p.symmetry)
        self.lower, self.upper = self._bounds()
        self.beta = p.projection.beta if p.projection else None

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

    @property
    def n_variables(self) -> int:
        return self.P.shape[1]

    def initial(self) -> np.ndarray:
        """top88's start: every variable at the volume limit (0.5 without one)."""
        p = self.problem
        start = p.initial or p.volume_limit or 0.5
        return np.clip(np.full(self.n_variables, float(start)), self.lower, self.upper)

    def physical(self, z: np.ndarray) -> np.ndarray:
        """Physical densities of the elements from design variables z (filtered, then
        projected at ``self.beta`` where the problem has a projection)."""
        rho = self.filter.physical(self.P @ z)
        if self.beta is not None:
            rho = project(rho, self.beta, self.problem.projection.eta)
        rho[self.solid], rho[self.void] = 1.0, 0.0
        return rho

    def back(self, x: np.ndarray, g: np.ndarray, objective: bool = False) -> np.ndarray:
        """The gradient with respect to the design variables of a function whose gradient
        with respect to the physical densities is g (x: the element design densities)."""
        if self.beta is not None:
            g = g * project_derivative(self.filter.physical(x), self.beta,
                                       self.problem.projection.eta)
        return self.P.T @ self.filter.back(x, g, objective=objective)

    def evaluate(self, z: np.ndarray) -> Evaluation:
        """All responses at z, one factorisation for the state and every adjoint."""
        p, x = self.problem, self.P @ z
        rho = self.physical(z)
        interp = p.interpolation
        responses = [p.objective] + [c.response for c in p.constraints]
        adjoint = {r.spring for r in responses if r.kind == "displacement"}
        names = sorted(adjoint)
        rhs = np.column_stack([self.force] + [self.spring_vectors[n] for n in names])
        sol = self.system.solve(interp.modulus(rho), rhs)
        u = sol[:, 0]
        dE = interp.derivative(rho)
        pinned = self.solid | self.void
        disp = {n: float(v @ u) for n, v in self.spring_vectors.items()}

        def value_grad(r):
            if r.kind == "volume":
                g = np.full(rho.size, 1.0 / rho.size)
                g[pinned] = 0.0
                return float(rho.mean()), g
            lam = u if r.kind == "compliance" else sol[:, 1 + names.index(r.spring)]
            value = float(self.force @ u) if r.kind == "compliance" else disp[r.spring]
            g = -dE * self.system.element_products(lam, u)
            g[pinned] = 0.0
            return value, g

        f0, g0 = value_grad(p.objective)
        sign = 1.0 if p.sense == "min" else -1.0
        g0 = self.back(x, sign * g0, objective=True)
        values, grads = [], []
        for c in p.constraints:
            v, g = value_grad(c.response)
            values.append(v)
            grads.append(self.back(x, g))
        grads = np.array(grads).reshape(len(values), self.n_variables)
        return Evaluation(f0, g0, np.array(values), grads, rho, u, disp)
