"""The responses of a design and their gradients with respect to the physical densities:
compliance (several load cases), volume, a spring's displacement, the lowest eigenfrequency
and the p-norm of the relaxed von Mises stresses. Each function takes the numeric problem
``d`` (model.Discrete), the design's :class:`State` and the :class:`Response`."""
from dataclasses import dataclass

import numpy as np
from scipy.sparse.linalg import LinearOperator, eigsh

from ..fem.symmetric import symmetric_from_upper
from .interpolation import mass_factor, mass_factor_derivative


@dataclass
class State:
    """A design's physical densities ``rho``, moduli ``E`` and dE/drho (Pa), the
    displacements ``U`` (n_dofs, n_cases; m) and the displacement adjoints by spring."""

    rho: np.ndarray
    E: np.ndarray
    dE: np.ndarray
    U: np.ndarray
    adjoints: dict


def volume(d, s: State, r):
    """The solid fraction and its gradient."""
    return float(s.rho.mean()), np.full(s.rho.size, 1.0 / s.rho.size)


def compliance(d, s: State, r):
    """sum_k w_k f_k.u_k (J) and its gradient -dE sum_k w_k u_k^T KE u_k (self-adjoint)."""
    weights = r.weights or (1.0,) * s.U.shape[1]
    value, g = 0.0, np.zeros(s.rho.size)
    for w, f, u in zip(weights, d.forces.T, s.U.T):
        if w:
            value += w * float(f @ u)
            g -= w * s.dE * d.system.element_products(u, u)
    return value, g


def displacement(d, s: State, r):
    """The spring's mean displacement l.u (m) in load case r.case, and its gradient."""
    u, lam = s.U[:, r.case - 1], s.adjoints[r.spring]
    return float(d.spring_vectors[r.spring] @ u), -s.dE * d.system.element_products(lam, u)


def _full(system, A):
    """The whole symmetric matrix of the system's stored pattern (maybe its upper half)."""
    return symmetric_from_upper(A) if system.upper else A


def lowest_mode(d, s: State):
    """(eigenvalue omega^2 in (rad/s)^2, full-length mode shape normalised to unit modal
    mass) of K(E) phi = omega^2 M phi, by ARPACK's shift-invert about 0 with the static
    solve's factorisation of K."""
    system = d.system
    M = _full(system, system.matrix(d.problem.mass_density * mass_factor(s.rho),
                                    element_map=d.mass_map))
    n = M.shape[0]
    OPinv = LinearOperator((n, n), matvec=lambda b: system.solver.solve(b), dtype=float)
    K = _full(system, system.matrix(s.E))
    vals, vecs = eigsh(K, k=min(2, n - 1), M=M, sigma=0.0, OPinv=OPinv, which="LM",
                       v0=np.ones(n))
    j = int(np.argmin(vals))
    phi = vecs[:, j] / np.sqrt(vecs[:, j] @ (M @ vecs[:, j]))
    out = np.zeros(system.grid.n_dofs)
    out[system.free] = phi
    return float(vals[j]), out


def frequency(d, s: State, r):
    """The lowest eigenfrequency f = omega / 2 pi (Hz) and its gradient, that of a single
    eigenvalue: d omega^2 = dE phi^T KE phi - omega^2 dm phi^T ME phi."""
    lam, phi = lowest_mode(d, s)
    dm = d.problem.mass_density * mass_factor_derivative(s.rho)
    dlam = (s.dE * d.system.element_products(phi, phi)
            - lam * dm * d.system.element_products(phi, phi, d.ME))
    f = np.sqrt(max(lam, 0.0)) / (2.0 * np.pi)
    return f, dlam / (8.0 * np.pi**2 * max(f, 1e-300))


def pnorm(t: list, P: float):
    """(||t||_P over the arrays of ``t``, [d value / d t_k for each array]), computed
    without overflow; (0, []) where every t is 0."""
    top = max(float(np.max(tk)) for tk in t)
    if top == 0.0:
        return 0.0, []
    value = top * float(sum(np.sum((tk / top) ** P) for tk in t)) ** (1.0 / P)
    return value, [(tk / value) ** (P - 1) for tk in t]


def stress(d, s: State, r):
    """The p-norm (Pa) over elements and load cases of t_e = rho_e^q sigma_vm(u_e) (the
    solid's von Mises stress at the element centre, q = r.relaxation: void carries none),
    and its gradient by one adjoint solve a load case with the static factorisation."""
    P, q, rho = r.pnorm, r.relaxation, s.rho
    edofs = d.system.grid.edofs
    Su = [np.einsum("ij,ej->ei", d.S, u[edofs]) for u in s.U.T]
    vm = [np.sqrt(np.maximum(np.einsum("ei,ei->e", su, u[edofs]), 0.0))
          for su, u in zip(Su, s.U.T)]
    t = [rho**q * v for v in vm]
    value, weights = pnorm(t, P)
    if value == 0.0:
        return 0.0, np.zeros(rho.size)
    g, rhs = np.zeros(rho.size), np.zeros((d.system.grid.n_dofs, len(t)))
    positive = rho > 0
    for k, (tk, vk, su, w) in enumerate(zip(t, vm, Su, weights)):
        g[positive] += w[positive] * q * tk[positive] / rho[positive]
        dvm = np.where(vk > 0, w * rho**q / np.where(vk > 0, vk, 1.0), 0.0)
        np.add.at(rhs[:, k], edofs, dvm[:, None] * su)
    lam = d.system.resolve(rhs)
    for k, u in enumerate(s.U.T):
        g -= s.dE * d.system.element_products(lam[:, k], u)
    return value, g


RESPONSES = {"volume": volume, "compliance": compliance, "displacement": displacement,
             "frequency": frequency, "stress": stress}
