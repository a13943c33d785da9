"""Superelements of the planar beam model: a linear part given by its stiffness and mass on
beam nodes, assembled as pairs of nodes so that it rides with the two-node elements."""
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True, eq=False)
class Superelement:
    """A linear part condensed onto the DOFs (x, y, theta) of ``nodes`` (two or more, in that
    order): ``stiffness`` and ``mass`` (3k x 3k, symmetric; N/m, N/rad, N m/rad and kg, kg m,
    kg m^2), e.g. a 2-D continuum patch of a block too deep for a beam
    (:mod:`flexfem.reduced.patch2d`). It is linear: a model with one takes linear statics,
    compliance and modes; the nonlinear solver refuses it."""

    nodes: tuple
    stiffness: np.ndarray
    mass: np.ndarray

    def __post_init__(self):
        nodes = tuple(int(n) for n in np.atleast_1d(self.nodes))
        if len(nodes) < 2 or len(set(nodes)) != len(nodes):
            raise ValueError(f"Superelement: nodes = {self.nodes!r} must be two or more "
                             "distinct nodes")
        object.__setattr__(self, "nodes", nodes)
        for name in ("stiffness", "mass"):
            m = np.array(getattr(self, name), dtype=float)
            if m.shape != (3 * len(nodes),) * 2 or not np.all(np.isfinite(m)):
                raise ValueError(f"Superelement: {name} must be a finite {3 * len(nodes)} x "
                                 f"{3 * len(nodes)} matrix (3 DOFs a node), got {m.shape}")
            if np.abs(m - m.T).max() > 1e-9 * np.abs(m).max():
                raise ValueError(f"Superelement: {name} must be symmetric")
            m.setflags(write=False)
            object.__setattr__(self, name, m)

    def pairs(self) -> tuple:
        """(pairs (m, 2) node indices, stiffness (m, 6, 6), mass (m, 6, 6)) that sum to the
        superelement: each pair of its nodes carries their off-diagonal blocks and a share
        of each node's own block, so that it assembles as two-node elements do."""
        k = len(self.nodes)
        idx = [(i, j) for i in range(k) for j in range(i + 1, k)]
        blocks = lambda M: np.array([_pair_block(M, i, j, k) for i, j in idx])
        pairs = np.array([(self.nodes[i], self.nodes[j]) for i, j in idx])
        return pairs, blocks(self.stiffness), blocks(self.mass)


def _pair_block(M, i, j, k) -> np.ndarray:
    """6 x 6 block of nodes i, j of M: their coupling and 1 / (k - 1) of each one's own."""
    dofs = [3 * i, 3 * i + 1, 3 * i + 2, 3 * j, 3 * j + 1, 3 * j + 2]
    out = M[dofs][:, dofs]
    out[:3, :3] /= k - 1
    out[3:, 3:] /= k - 1
    return out
