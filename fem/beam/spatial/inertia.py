"""Mass properties of a spatial beam model (or of some of its elements) from its consistent
mass matrix: the kinetic energy of its rigid-body motions.

    m, c, J = mass_properties(model, elements=range(10, 20))
"""
import numpy as np

from .element import local_matrices, to_global
from .rotations import skew


def rigid_body_mass(model, point, elements=None) -> np.ndarray:
    """(6, 6) mass matrix (kg, kg m, kg m^2) of the rigid-body motions of ``elements``
    (indices; default all, with the point masses): translations and rotations about
    ``point`` (3,) m; Phi^T M Phi with Phi the rigid-body modes."""
    point = np.asarray(point, dtype=float)
    chosen = np.arange(model.n_elements) if elements is None else np.asarray(elements, int)
    _, M = local_matrices(model)
    E = to_global(model.frames[chosen])
    Mg = np.einsum("eij,ejk,elk->eil", E, M[chosen], E)
    phi = np.zeros((len(chosen), 12, 6))
    for k in range(2):
        arm = model.nodes[model.elements[chosen, k]] - point
        phi[:, 6 * k:6 * k + 3, :3] = np.eye(3)
        phi[:, 6 * k:6 * k + 3, 3:] = -skew(arm)  # u = theta x arm = -S(arm) theta
        phi[:, 6 * k + 3:6 * k + 6, 3:] = np.eye(3)
    out = np.einsum("eia,eij,ejb->ab", phi, Mg, phi)
    if elements is None:
        for node, (m, jx, jy, jz) in model.point_masses.items():
            p = np.zeros((6, 6))
            p[:3, :3], p[:3, 3:], p[3:, 3:] = np.eye(3), -skew(model.nodes[node] - point), np.eye(3)
            block = np.diag([m, m, m, jx, jy, jz])
            out += p.T @ block @ p
    return out


def mass_properties(model, elements=None) -> tuple:
    """(mass kg, centroid (3,) m, inertia tensor (3, 3) kg m^2 about the centroid) of
    ``elements`` (default the whole model, point masses included): :func:`rigid_body_mass`."""
    M0 = rigid_body_mass(model, np.zeros(3), elements)
    m = M0[0, 0]
    c = np.array([M0[1, 5], M0[2, 3], M0[0, 4]]) / m  # M0[:3, 3:] = -m S(c)
    S = skew(c)
    J = M0[3:, 3:] + m * S @ S  # parallel axes: J_0 = J_c - m S(c)^2
    return float(m), c, J
