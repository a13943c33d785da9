"""Compliance matrix of a node: its (x, y, theta) motion per unit (F_x, F_y, M) load.

    C = compliance(model, [Fixed(0)], node=tip)               # linear, undeformed
    C = compliance(model, supports, node=tip, about=state)    # tangent at a converged state
"""
import numpy as np

from .assembly import Assembler, solve
from .model import BeamModel


def compliance(model: BeamModel, supports, node: int, about=None, loads=()) -> np.ndarray:
    """3x3 compliance (m/N, m/(N m) = 1/N, rad/(N m)) of ``node``'s (x, y, theta) under
    (F_x, F_y, M) with the supports held; about : a converged BeamState of the same supports
    and ``loads`` (tangent compliance, stress stiffening included), default undeformed. The
    node may be a rigid-link slave; its DOFs must not be held."""
    if not (isinstance(node, (int, np.integer)) and 0 <= node < model.n_nodes):
        raise ValueError(f"node = {node!r} must be a node index in 0..{model.n_nodes - 1}")
    asm = Assembler(model, supports, loads)
    if about is None:
        z, lam = np.zeros(asm.space.n), 0.0
    else:
        z, lam = about.q.ravel()[asm.space.free], about.load_factor
    ev = asm.evaluate(z, lam)
    rows = asm.space.rows(int(node), ev.w)  # d(node DOFs)/dz, (3, n)
    if np.any(np.abs(rows).sum(axis=1) == 0):
        raise ValueError(f"node = {node}: a DOF of it is held by a support; its compliance "
                         "is zero there")
    X = solve(ev.K, rows.T)
    return rows @ X
