"""Compliance of a rigid face: ``compliance_matrix(model, supports, face) -> Compliance``.

The face (a boundary group, 2-D) is made rigid with all three coordinates free and loaded by
unit generalised loads; the 3 x 3 compliance relates the face's (u_x, u_y, theta) at a
reference point (m, m, rad) to a force (F_x, F_y) (N) applied there and a moment M (N m):
[u_x, u_y, theta] = C [F_x, F_y, M]. About a converged nonlinear state it is the tangent
(incremental) compliance: material and geometric stiffness, the face's rotation included.
"""
from dataclasses import dataclass
import math

import numpy as np
import scipy.sparse as sp

from . import linsolve
from .boundary import constrained_dofs
from .hyperelastic import Assembler
from .rigid_face import ReducedSpace, RigidFace
from .rigid_static import check_held, linear_map
from .stability import state_displacement, tangent_stiffness


@dataclass(frozen=True, eq=False)
class Compliance:
    """matrix : (3, 3) compliance (m/N, 1/N, rad/(N m)) in the frame rotated by ``angle``
    (rad) from the global one, about ``point`` (m, current coordinates); face : the group."""

    face: str
    matrix: np.ndarray
    point: np.ndarray
    angle: float

    @property
    def stiffness(self) -> np.ndarray:
        """(3, 3) stiffness matrix (N/m, N, N m/rad): the inverse of ``matrix``."""
        return np.linalg.inv(self.matrix)

    def principal(self) -> tuple[np.ndarray, np.ndarray]:
        """(compliances (2,) m/N ascending, directions (2, 2) as columns, in the frame) of the
        translational block: the force directions that translate the point along themselves."""
        return np.linalg.eigh(self.matrix[:2, :2])

    @property
    def centre_of_compliance(self) -> np.ndarray:
        """(2,) global coordinates (m) of the point where a force causes no rotation (the
        elastic centre): force and rotation decouple about it."""
        C = self.matrix
        local = np.array([-C[2, 1] / C[2, 2], C[2, 0] / C[2, 2]])
        return self.point + _rotation(self.angle) @ local

    def _along(self, direction) -> np.ndarray:
        d = np.asarray(direction, dtype=float)
        if d.shape != (2,) or not np.all(np.isfinite(d)) or not np.linalg.norm(d) > 0:
            raise ValueError(f"direction = {direction!r} must be 2 finite numbers, not both 0")
        d = d / np.linalg.norm(d)
        Q = np.array([[d[0], d[1], 0.0], [-d[1], d[0], 0.0], [0.0, 0.0, 1.0]])
        return Q @ self.matrix @ Q.T  # coordinates (along d, across d, theta)

    def support_stiffness(self, direction) -> tuple[float, float]:
        """(motion stiffness (N/m), support stiffness (N/m)) for motion along ``direction``
        (frame components): the motion stiffness with the other coordinates free, the
        support stiffness across the motion with the motion held and the rotation free."""
        C = self._along(direction)
        K = np.linalg.inv(C)
        support = np.linalg.inv(K[1:, 1:])[0, 0]
        return 1.0 / C[0, 0], 1.0 / support

    def support_stiffness_ratio(self, direction) -> float:
        """Support stiffness over motion stiffness (-) for motion along ``direction``."""
        motion, support = self.support_stiffness(direction)
        return support / motion

    def parasitic(self, direction) -> tuple[float, float]:
        """(motion across (m/m), rotation (rad/m)) per unit motion along ``direction`` when
        the point is pushed along it; 'across' is ``direction`` turned by +90 degrees."""
        C = self._along(direction)
        return C[1, 0] / C[0, 0], C[2, 0] / C[0, 0]


def _rotation(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s], [s, c]])


def _rigid_fit(fk, u: np.ndarray) -> np.ndarray:
    """(c_x, c_y, theta) of the rigid motion closest to the face's displacement ``u``."""
    arms = fk.arms
    x = arms + u[fk.dofs]  # current position relative to the reference centroid
    a, b = arms - arms.mean(axis=1, keepdims=True), x - x.mean(axis=1, keepdims=True)
    theta = math.atan2(np.sum(a[0] * b[1] - a[1] * b[0]), np.sum(a[0] * b[0] + a[1] * b[1]))
    c = x.mean(axis=1) - _rotation(theta) @ arms.mean(axis=1)
    return np.array([c[0], c[1], theta])


def _reduced_tangent(model, space: ReducedSpace, state):
    """(K_zz (N/m), face coordinates q) about ``state`` (None: the reference)."""
    fk = space.faces[0]
    if state is None:
        T, _ = linear_map(space)
        return (T.T @ model.stiffness @ T).tocsr(), np.zeros(3)
    u, kind = state_displacement(model, state)
    if kind == "linear":
        T, _ = linear_map(space)
        return (T.T @ tangent_stiffness(model, state) @ T).tocsr(), np.zeros(3)
    q = _rigid_fit(fk, u)
    z = np.zeros(space.n)
    z[:len(space.I)] = u[space.I]
    z[space.slots[0]] = q * np.array([1.0, 1.0, fk.ell])
    assembler = Assembler(model)
    F, S = assembler.state(u)
    r = assembler.internal_force(F, S)
    if isinstance(state, tuple):
        r = r - state[0].load_factors[state[1]] * state[0].applied
    elif hasattr(state, "applied"):
        r = r - state.load_factors[-1] * state.applied
    T = space.jacobian(z, 1.0)
    K = T.T @ assembler.tangent(F, S) @ T
    return (K + sp.diags(space.geometric_term(z, 1.0, r))).tocsr(), q


def compliance_matrix(model, supports, face, point=None, state=None,
                      angle: float = 0.0) -> Compliance:
    """Compliance of the rigid ``face`` (a group name or RigidFace; its prescribed values are
    ignored: all three coordinates are freed) under ``supports`` (Fixed, Prescribed).

    point : (2,) reference point (m), in the current configuration; default the face's
    centroid. state : None (the unloaded reference), a StaticResult (prestressed:
    K + K_sigma), or a converged nonlinear state (NonlinearResult, (NonlinearResult, step) or
    DOF vector, m): the tangent compliance there. angle : frame rotation (rad, counter-
    clockwise) of the returned matrix's axes. Raises UnderConstrainedError if the supports
    alone do not hold the body with the face free.
    """
    group = face.group if isinstance(face, RigidFace) else face
    if not isinstance(group, str):
        raise ValueError(f"face = {face!r} must be a boundary group name or a RigidFace")
    if not (isinstance(angle, (int, float)) and math.isfinite(angle)):
        raise ValueError(f"angle = {angle!r} must be a finite number (rad)")
    D, xD, _ = constrained_dofs(model, supports)
    space = ReducedSpace(model, D, xD, [RigidFace(group)])
    check_held(model, space)
    K, q = _reduced_tangent(model, space, state)
    fk = space.faces[0]
    slots = space.slots[0]
    E = np.zeros((space.n, 3))
    E[slots, [0, 1, 2]] = 1.0
    with linsolve.Factorization(K, "symmetric") as solve:
        X = solve(E)
    scale = np.array([1.0, 1.0, 1.0 / fk.ell])
    C = scale[:, None] * X[slots] * scale[None, :]  # (c_x, c_y, theta) per (F_x, F_y, M)
    C = 0.5 * (C + C.T)
    centre = fk.centroid + q[:2]
    P = centre if point is None else np.asarray(point, dtype=float)
    if P.shape != (2,) or not np.all(np.isfinite(P)):
        raise ValueError(f"point = {point!r} must be 2 finite coordinates (m)")
    d = P - centre
    A = np.array([[1.0, 0.0, -d[1]], [0.0, 1.0, d[0]], [0.0, 0.0, 1.0]])
    R = np.eye(3)
    R[:2, :2] = _rotation(angle).T
    return Compliance(group, R @ A @ C @ A.T @ R.T, P, float(angle))
