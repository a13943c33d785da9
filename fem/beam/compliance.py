"""Compliance matrix of a node: its (x, y, theta) motion per unit (F_x, F_y, M) load.

    C = compliance(model, [NodeFixed(0)], node=tip)               # linear, undeformed
    C = compliance(model, supports, node=tip, about=state)    # tangent at a converged state
    C = shared_compliance(model, [NodeFixed(0)], node=tip)        # linear, the model's own factor
"""
import numpy as np

from .assembly import BeamAssembler, solve
from .linear import linear_system
from .model import BeamModel


def compliance(model: BeamModel, supports, node: int, about=None, loads=()) -> np.ndarray:
    """3x3 compliance (m/N, m/(N m) = 1/N, rad/(N m)) of ``node``'s (x, y, theta) under
    (F_x, F_y, M) with the supports held; about : a converged BeamState of the same supports
    and ``loads`` (tangent compliance, stress stiffening included), default undeformed. The
    node may be a rigid-link slave; its DOFs must not be held."""
    _check_node(model, node)
    asm = BeamAssembler(model, supports, loads)
    if about is None:
        z, lam = np.zeros(asm.space.n), 0.0
    else:
        z, lam = about.q.ravel()[asm.space.free], about.load_factor
    ev = asm.evaluate(z, lam)
    rows = _rows(asm.space, node, ev.w)
    X = solve(ev.K, rows.T)
    return rows @ X


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
