"""The beam solvers' node-addressed supports and loads, planar or spatial alike.

A user supports and loads a beam model by its groups with :mod:`flexfem.fem.boundary`'s
``Fixed``, ``Prescribed`` and ``Force`` (the analysis face, :mod:`.face`, turns them into
these); the solvers of :mod:`flexfem.fem.beam` take these node-addressed ones. A planar node
has 3 DOFs (u_x, u_y, theta), a spatial node 6 (u_x, u_y, u_z, r_x, r_y, r_z): the planar
ones are the spatial in-plane DOFs (theta = r_z). ``NodeFixed``, ``NodePrescribed`` and
``NodalLoad`` name DOFs and components without knowing the model; the model's assembly asks
for them per node (``prescribed(per_node)``, ``NodalLoad.vector(per_node)``).

    NodeFixed(0)                     # every DOF of node 0 (3 planar, 6 spatial)
    NodeFixed([0, 5], ("x", "y"))    # the translations in the plane
    NodePrescribed(20, "y", -1e-3)   # m, times the load factor
    NodalLoad(20, fy=-1.0, m=0.1)    # N, N m (m: the in-plane moment, also called mz)
"""
from dataclasses import KW_ONLY, dataclass

import numpy as np

PLANAR_DOFS = {"x": 0, "u": 0, "y": 1, "v": 1, "theta": 2, "t": 2, "rz": 2}
SPATIAL_DOFS = {"x": 0, "y": 1, "z": 2, "rx": 3, "ry": 4, "rz": 5}
DOF_NAMES = {3: PLANAR_DOFS, 6: SPATIAL_DOFS}  # by the DOFs per node


def dof_index(dof, per_node: int = 3) -> int:
    """Index of a DOF given by number (0..per_node - 1) or name: planar (per_node 3) 'x',
    'y', 'theta' (also 'u', 'v', 'rz'); spatial (per_node 6) 'x', 'y', 'z', 'rx', 'ry', 'rz'."""
    names = DOF_NAMES[per_node]
    if isinstance(dof, np.generic):
        dof = dof.item()
    if isinstance(dof, str) and dof.lower() in names:
        return names[dof.lower()]
    if isinstance(dof, int) and not isinstance(dof, bool) and 0 <= dof < per_node:
        return dof
    known = "'x', 'y', 'theta'" if per_node == 3 else ", ".join(f"'{n}'" for n in SPATIAL_DOFS)
    raise ValueError(f"dof = {dof!r} must be 0..{per_node - 1} or one of {known}")


@dataclass(frozen=True)
class NodeFixed:
    """Hold ``dofs`` (default: all of each node's) of ``nodes`` at zero."""

    nodes: tuple
    dofs: tuple | None = None

    def prescribed(self, per_node: int = 3):
        """(node, DOF index, 0.0) of every held DOF of a model with ``per_node`` DOFs a node."""
        nodes = np.atleast_1d(self.nodes).tolist()
        if not nodes:
            return
        if self.dofs is None:
            dofs = list(range(per_node))
        else:
            dofs = [dof_index(d, per_node) for d in np.atleast_1d(self.dofs).tolist()]
        for n in nodes:
            for d in dofs:
                yield int(n), d, 0.0


@dataclass(frozen=True)
class NodePrescribed:
    """Prescribe DOF ``dof`` of ``node`` to ``value`` (m or rad) times the load factor. A
    prescribed rotation of a spatial model is a rotation about that fixed global axis."""

    node: int
    dof: object
    value: float

    def prescribed(self, per_node: int = 3):
        yield int(self.node), dof_index(self.dof, per_node), float(self.value)


@dataclass(frozen=True)
class NodalLoad:
    """Dead force (fx, fy, fz) in N and moment (mx, my, mz) in N m about the global axes on
    ``node``, times the load factor; ``m`` is the in-plane moment mz by its planar name (give
    one of them). A planar model takes fx, fy and m (mz). All but node, fx and fy are given
    by name (NodalLoad(7, 0.0, -1.0, m=0.2)), so that no planar and spatial order can mix."""

    node: int
    fx: float = 0.0
    fy: float = 0.0
    _: KW_ONLY
    fz: float = 0.0
    mx: float = 0.0
    my: float = 0.0
    mz: float = 0.0
    m: float = 0.0

    def __post_init__(self):
        if self.m and self.mz:
            raise ValueError(f"NodalLoad({self.node}): give the in-plane moment as m or as mz, "
                             "not both")

    def vector(self, per_node: int = 3) -> np.ndarray:
        """(per_node,) the load on the node's DOFs: (fx, fy, m) planar, (fx, ..., mz) spatial."""
        if per_node == 3:
            if self.fz or self.mx or self.my:
                raise ValueError(f"NodalLoad({self.node}): fz, mx and my act out of the plane; "
                                 "the planar beam model takes fx, fy and m")
            return np.array([self.fx, self.fy, self.m + self.mz], dtype=float)
        return np.array([self.fx, self.fy, self.fz, self.mx, self.my, self.mz + self.m],
                        dtype=float)


def load_vector(model, loads) -> np.ndarray:
    """Full-load vector (N, N m) of a planar or spatial ``model`` from NodalLoad objects."""
    per_node = model.n_dofs // model.n_nodes
    f = np.zeros(model.n_dofs)
    for load in loads:
        if not isinstance(load, NodalLoad):
            raise ValueError(f"loads: {load!r} is not a NodalLoad")
        if not 0 <= int(load.node) < model.n_nodes:
            raise ValueError(f"loads: node {load.node} outside 0..{model.n_nodes - 1}")
        f[per_node * int(load.node):per_node * (int(load.node) + 1)] += load.vector(per_node)
    return f
