"""Linear static analysis of a spatial beam model (its compliance matrix: the beam models'
one :func:`flexfem.fem.beam.compliance.compliance`, by its spatial name ``compliance3d``).

    res = solve_beam3d_static(model, [NodeFixed(0)], [NodalLoad(tip, fz=-1.0)])
"""
from dataclasses import dataclass, field

import numpy as np

from ..assembly import Factor
from .assembly import SpatialAssembler
from .corotational import kinematics
from .model import Beam3DModel
from .rotations import expm, logm
from .stress import peak_stress, section_stresses


@dataclass(frozen=True, eq=False)
class Beam3DState:
    """One equilibrium state. u : (n_nodes, 3) displacement (m); R : (n_nodes, 3, 3) nodal
    rotation matrices; reactions : {node: (F_x, F_y, F_z N, M_x, M_y, M_z N m)} at
    supported nodes; local_forces : (n_e, 7) N (N, tension > 0) and the two ends' moments
    (N m, element axes: torsion, bending about y, about z) acting on the element."""

    model: Beam3DModel
    u: np.ndarray
    R: np.ndarray
    reactions: dict
    local_forces: np.ndarray
    load_factor: float = 1.0
    info: dict = field(default_factory=dict)

    @property
    def rotation(self) -> np.ndarray:
        """(n_nodes, 3) rotation vectors (rad; angle <= pi) of the nodal rotations."""
        return logm(self.R)

    @property
    def q(self) -> np.ndarray:
        """(n_nodes, 6): displacement (m) and rotation vector (rad) per node."""
        return np.hstack([self.u, self.rotation])

    @property
    def axial_force(self) -> np.ndarray:
        """(n_e,) N, tension > 0."""
        return self.local_forces[:, 0]

    def stresses(self, n_points: int = 5) -> dict:
        """Normal, torsion and von Mises-bound stresses (Pa) along every element
        (:func:`.stress.section_stresses`)."""
        return section_stresses(self.model, self.local_forces, n_points)

    @property
    def max_stress(self) -> float:
        """Largest von Mises bound (Pa) over the rectangular sections: the largest normal
        stress (axial + both bendings, at a corner) with the largest torsion shear."""
        return peak_stress(self.model, self.local_forces)[0]


def make_state(asm: SpatialAssembler, u, R, r, lam, fl, T, Tp, info=None) -> Beam3DState:
    """Package a state: reactions from the residual r = f_int - lam f_ext."""
    space = asm.space
    rr = np.zeros(asm.model.n_dofs)
    rr[space.free], rr[space.held] = T.T @ r, Tp.T @ r
    rr = rr.reshape(-1, 6)
    reactions = {int(k): rr[k].copy() for k in np.unique(space.held // 6)}
    return Beam3DState(model=asm.model, u=u.copy(), R=R.copy(), reactions=reactions,
                       local_forces=fl.copy(), load_factor=float(lam), info=dict(info or {}))


def solve_beam3d_static(model: Beam3DModel, supports, loads=()) -> Beam3DState:
    """Linear (small-displacement) static solve for the loads (NodalLoad) and the supports'
    values (NodeFixed, NodePrescribed) at load factor 1. Element forces are the linear ones; R is
    exp of the linear rotation vector."""
    return linear_solution(model, supports, loads)[0]


def linear_solution(model: Beam3DModel, supports, loads=()) -> tuple:
    """(Beam3DState, q (n_dofs,) the linear DOFs (m, rad), r (n_dofs,) = K q - f_ext (N,
    N m), the reduced K (CSC), T, the SpatialAssembler) of :func:`solve_beam3d_static`."""
    asm = SpatialAssembler(model, supports, loads)
    space = asm.space
    u0, R0 = space.reference()
    _, _, K, T, Tp, Kfull, _ = asm.evaluate(u0, R0, 0.0)
    p = space.p_hat
    rhs = T.T @ (asm.f_ext - Kfull @ (Tp @ p))
    z = Factor(K).solve(rhs)
    q = T @ z + Tp @ p
    r = Kfull @ q - asm.f_ext
    q6 = q.reshape(-1, 6)
    _, _, Bg, _ = kinematics(model, model.nodes, R0)
    qe = q6[model.elements].reshape(-1, 12)
    fl = np.einsum("eij,ej->ei", asm.Kb, np.einsum("eij,ej->ei", Bg, qe))
    state = make_state(asm, q6[:, :3], expm(q6[:, 3:]), r, 1.0, fl, T, Tp,
                       {"n_unknowns": space.n})
    return state, q, r, K, T, asm
