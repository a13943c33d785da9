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
    displacements ``U`` (n_dofs, n_cases; m) and the displacement adjoints by spring;
    ``free_U`` and ``free_adjoints`` those of the structure without its springs (where a
    response asks for them)."""

    rho: np.ndarray
    E: np.ndarray
    dE: np.ndarray
    U: np.ndarray
    adjoints: dict
    free_U: np.ndarray | None = None
    free_adjoints: dict | None = None


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
    """The spring's mean displacement l.u (m) in load case r.case (of the structure without
    its springs where r.springs is False), and its gradient."""
    if r.springs:
        u, lam = s.U[:, r.case - 1], s.adjoints[r.spring]
    else:
        u, lam = s.free_U[:, r.case - 1], s.free_adjoints[r.spring]
    return float(d.spring_vectors[r.spring] @ u), -s.dE * d.system.element_products(lam, u)


def _full(system, A):
    """The whole symmetric matrix of the system's stored pattern (maybe its upper half)."""
    return symmetric_from_upper(A) if system.upper else A


def lowest_modes(d, s: State, n: int = 1):
    """(eigenvalues omega^2 in (rad/s)^2 ascending (n,), full-length mode shapes (n_dofs, n)
    normalised to unit modal mass) of the ``n`` lowest modes of K(E) phi = omega^2 M phi, by
    ARPACK's shift-invert about 0 with the static solve's factorisation of K."""
    system = d.system
    M = _full(system, system.matrix(d.problem.mass_density * mass_factor(s.rho),
                                    element_map=d.mass_map))
    size = M.shape[0]
    OPinv = LinearOperator((size, size), matvec=lambda b: system.solver.solve(b), dtype=float)
    K = _full(system, system.matrix(s.E))
    vals, vecs = eigsh(K, k=min(n + 1, size - 1), M=M, sigma=0.0, OPinv=OPinv, which="LM",
                       v0=np.ones(size))
    order = np.argsort(vals)[:n]
    vecs = vecs[:, order] / np.sqrt(np.einsum("ij,ij->j", vecs[:, order], M @ vecs[:, order]))
    out = np.zeros((system.grid.n_dofs, len(order)))
    out[system.free] = vecs
    return vals[order], out


# the exponent of the aggregate of several eigenvalues: a double one reads 2^(-1/32), 2.2 %
# low in omega^2 (1.1 % in frequency)
MODES_EXPONENT = 32.0


def frequency(d, s: State, r):
    """The lowest eigenfrequency f = omega / 2 pi (Hz) and its gradient, that of a single
    eigenvalue: d omega^2 = dE phi^T KE phi - omega^2 dm phi^T ME phi. With ``r.modes`` = n
    > 1, f of the aggregate (sum_j lam_j^-p)^(-1/p) of the n lowest eigenvalues lam_j
    (p = MODES_EXPONENT): at most lam_1, and a symmetric function of the eigenvalues, so
    differentiable where lam_1 is repeated (the gradient of a cluster's sum does not depend
    on the basis its eigenvectors are drawn in), where a single eigenvalue is not."""
    vals, vecs = lowest_modes(d, s, r.modes)
    dm = d.problem.mass_density * mass_factor_derivative(s.rho)
    vals = np.maximum(vals, 1e-300)
    if r.modes == 1:
        lam, weights = float(vals[0]), np.ones(1)
    else:
        lam = float(vals[0] * np.sum((vals[0] / vals) ** MODES_EXPONENT)
                    ** (-1.0 / MODES_EXPONENT))
        weights = (lam / vals) ** (MODES_EXPONENT + 1.0)
    dlam = np.zeros(s.rho.size)
    for w, val, phi in zip(weights, vals, vecs.T):
        dlam += w * (s.dE * d.system.element_products(phi, phi)
                     - val * dm * d.system.element_products(phi, phi, d.ME))
    f = np.sqrt(lam) / (2.0 * np.pi)
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
