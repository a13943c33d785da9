"""Compliance matrix of a node of a planar or spatial beam model: its motion per unit load
on its DOFs ((x, y, theta) planar, (x, y, z, r_x, r_y, r_z) spatial).

    C = compliance(model, [NodeFixed(0)], node=tip)           # linear, undeformed
    C = compliance(model, supports, node=tip, about=state)    # tangent at a converged state
    C = shared_compliance(model, [NodeFixed(0)], node=tip)    # planar, the model's own factor
"""
import numpy as np
import scipy.sparse as sp

from .assembly import BeamAssembler, solve
from .linear import linear_system
from .model import BeamModel


def compliance(model, supports, node: int, about=None, loads=()) -> np.ndarray:
    """Compliance of ``node``'s DOFs under unit loads on them, the supports held: 3x3 (x, y,
    theta under F_x, F_y, M) planar, 6x6 (x, y, z, r_x, r_y, r_z under F_x, ..., M_z)
    spatial; m/N, m/(N m) = 1/N, rad/(N m). about : a converged state (BeamState or
    Beam3DState) of the same supports and ``loads`` (tangent compliance, stress stiffening
    included; spatial rotations as spins about the global axes), default undeformed. The
    node may be a rigid-link slave; its DOFs must not be held."""
    _check_node(model, node)
    K, rows = (_planar_tangent if model.dim == 2 else _spatial_tangent)(
        model, supports, int(node), about, loads)
    if np.any(abs(rows).sum(axis=1) == 0):
        raise ValueError(f"node = {node}: a DOF of it is held by a support; its compliance "
                         "is zero there")
    return np.asarray(rows @ solve(K, rows.T.toarray() if sp.issparse(rows) else rows.T))


def _planar_tangent(model: BeamModel, supports, node: int, about, loads) -> tuple:
    """(reduced tangent, d(node DOFs)/dz (3, n)) of a planar model about ``about``."""
    asm = BeamAssembler(model, supports, loads)
    if about is None:
        z, lam = np.zeros(asm.space.n), 0.0
    else:
        z, lam = about.q.ravel()[asm.space.free], about.load_factor
    ev = asm.evaluate(z, lam)
    return ev.K, asm.space.rows(node, ev.w)


def _spatial_tangent(model, supports, node: int, about, loads) -> tuple:
    """(symmetric reduced tangent, sparse d(node DOFs)/dz (6, n)) of a spatial model."""
    from .spatial.assembly import SpatialAssembler, symmetric_tangent  # the package imports this
    K, T, _, _ = symmetric_tangent(SpatialAssembler(model, supports, loads), about)
    return K, T[6 * node:6 * node + 6]


def shared_compliance(model: BeamModel, supports, node: int) -> np.ndarray:
    """The undeformed :func:`compliance` by the model's cached linear system (fem/beam/
    linear.py: its K and factor, shared with the static solves and the modes): the same
    matrix to roundoff (1e-11 relative), without a second assembly and factorisation.
    :func:`compliance` keeps its own: the notch patch's fit (reduced/hinge_patch.py) takes
    differences of its compliances, which would carry a new roundoff into the factors."""
    _check_node(model, node)
    system = linear_system(model, supports)
    rows = _rows(system.space, node, system.ev.w)
    return rows @ system.factor.solve(rows.T)


def _check_node(model: BeamModel, node) -> None:
    if not (isinstance(node, (int, np.integer)) and 0 <= node < model.n_nodes):
        raise ValueError(f"node = {node!r} must be a node index in 0..{model.n_nodes - 1}")


def _rows(space, node, w) -> np.ndarray:
    """d(node DOFs)/dz (3, n); ValueError where a support holds one of them."""
    rows = space.rows(int(node), w)
    if np.any(np.abs(rows).sum(axis=1) == 0):
        raise ValueError(f"node = {node}: a DOF of it is held by a support; its compliance "
                         "is zero there")
    return rows
