"""Kinematics of a rigid face in 3-D: six master coordinates q = (c, psi) about the face's
area centroid Xc, node a moving to ``x_a = R(psi) (X_a - Xc) + Xc + c`` with R(psi) =
exp([psi]x) the rotation of the rotation vector psi (rad; Rodrigues' formula).

The first and second derivatives of R(psi) come from the exponential of block-triangular
matrices (exact to rounding at every psi, psi = 0 included): the upper-right block of
exp([[X, E], [0, X]]) is the derivative of exp at X in the direction E, the corner block of
exp([[X, E_j, 0], [0, X, E_k], [0, 0, X]]) the part of the mixed second derivative with E_j
before E_k. Moments are spatial (global axes, about the current centroid); a moment applied
on the face is dead (fixed direction), its generalised load on psi is T(psi)^T M with the
tangent operator T_j = axial(dR/dpsi_j R^T).
"""
from dataclasses import dataclass

import numpy as np
import scipy.linalg

from .compliance3d import face_geometry

_E = np.array([[[0, 0, 0], [0, 0, -1], [0, 1, 0]], [[0, 0, 1], [0, 0, 0], [-1, 0, 0]],
               [[0, -1, 0], [1, 0, 0], [0, 0, 0]]], dtype=float)  # [e_j]x


def skew(v) -> np.ndarray:
    """[v]x, the (3, 3) matrix of the cross product v x ."""
    return np.tensordot(np.asarray(v, dtype=float), _E, axes=1)


def axial(W: np.ndarray) -> np.ndarray:
    """The vector w of the skew part of W ((..., 3, 3)): [w]x = (W - W^T) / 2."""
    return 0.5 * np.stack([W[..., 2, 1] - W[..., 1, 2], W[..., 0, 2] - W[..., 2, 0],
                           W[..., 1, 0] - W[..., 0, 1]], axis=-1)


def rotation_derivatives(psi) -> tuple:
    """(R (3, 3), dR (3, 3, 3): dR/dpsi_j, d2R (3, 3, 3, 3): d2R/dpsi_j dpsi_k) at the
    rotation vector ``psi`` (rad)."""
    X = skew(psi)
    dR = np.empty((3, 3, 3))
    corner = np.empty((3, 3, 3, 3))
    block = np.zeros((9, 9))
    for i in range(3):
        block[3 * i:3 * i + 3, 3 * i:3 * i + 3] = X
    for j in range(3):
        block[0:3, 3:6] = _E[j]
        for k in range(3):
            block[3:6, 6:9] = _E[k]
            expm = scipy.linalg.expm(block)
            corner[j, k] = expm[0:3, 6:9]
        dR[j] = expm[0:3, 3:6]
    R = expm[0:3, 0:3]
    return R, dR, corner + np.swapaxes(corner, 0, 1)


@dataclass(frozen=True, eq=False)
class FaceKinematics3D:
    """A rigid face on a 3-D model: its DOFs (3, n), arms ``X_a - Xc`` (3, n) m, centroid
    (3,) m and RMS arm ``ell`` (m). Coordinates q = (c_x, c_y, c_z, psi_x, psi_y, psi_z)
    (m, rad)."""

    face: object
    dofs: np.ndarray
    arms: np.ndarray
    centroid: np.ndarray
    ell: float
    dim = 3
    rotations = (3, 4, 5)

    @property
    def scale(self) -> np.ndarray:
        """Unknown per coordinate: rotations carried as ell * psi (m)."""
        return np.array([1.0, 1.0, 1.0, self.ell, self.ell, self.ell])

    def displacement(self, q: np.ndarray) -> np.ndarray:
        """(3, n) displacement (m) of the face nodes."""
        R = rotation_derivatives(q[3:])[0]
        return (R - np.eye(3)) @ self.arms + q[:3, None]

    def linear_displacement(self, q: np.ndarray) -> np.ndarray:
        """(3, n) displacement (m) of the linearised motion c + psi x (X_a - Xc)."""
        return np.cross(q[3:], self.arms, axis=0) + q[:3, None]

    def columns(self, q: np.ndarray) -> np.ndarray:
        """(6, 3, n): du/dq_k of the face nodes (m/m, m/rad)."""
        dR = rotation_derivatives(q[3:])[1]
        out = np.zeros((6, 3, self.arms.shape[1]))
        out[:3] = np.eye(3)[:, :, None]
        out[3:] = dR @ self.arms
        return out

    def second(self, q: np.ndarray, r: np.ndarray) -> np.ndarray:
        """(6, 6) sum_a r_a . d2u_a/dq dq (N/m, N, N m) for nodal forces ``r`` (full DOF
        vector): nonzero in the rotation block only."""
        B = r[self.dofs] @ self.arms.T  # sum_a r_a A_a^T, (3, 3)
        H = np.zeros((6, 6))
        H[3:, 3:] = np.einsum("jkpq,pq->jk", rotation_derivatives(q[3:])[2], B)
        return H

    def generalised_force(self, r: np.ndarray, q: np.ndarray) -> np.ndarray:
        """(6,) force (N) and moment about the current centroid (N m) of the nodal forces
        ``r`` (full DOF vector) on the face at coordinates ``q``."""
        rf = r[self.dofs]
        current = rotation_derivatives(q[3:])[0] @ self.arms
        return np.concatenate([rf.sum(axis=1), np.cross(current, rf, axis=0).sum(axis=1)])

    def applied(self, q: np.ndarray, loads: np.ndarray) -> np.ndarray:
        """(6,) generalised loads (N, N m) of the dead force and moment ``loads`` (6,)."""
        R, dR, _ = rotation_derivatives(q[3:])
        T = axial(dR @ R.T)  # (3 j, 3): T_j
        return np.concatenate([loads[:3], T @ loads[3:]])

    def applied_derivative(self, q: np.ndarray, loads: np.ndarray) -> np.ndarray:
        """(6, 6) d applied / dq: the dead moment's load stiffness (not symmetric)."""
        R, dR, d2R = rotation_derivatives(q[3:])
        W = d2R @ R.T + np.einsum("jpm,kqm->jkpq", dR, dR)
        D = np.zeros((6, 6))
        D[3:, 3:] = axial(W) @ loads[3:]
        return D

    def rigid_fit(self, u: np.ndarray) -> np.ndarray:
        """(6,) coordinates of the rigid motion closest (least squares) to the face's
        displacement in ``u`` (full DOF vector, m): Kabsch's rotation about the mean."""
        from scipy.spatial.transform import Rotation

        x = self.arms + u[self.dofs]
        a = self.arms - self.arms.mean(axis=1, keepdims=True)
        b = x - x.mean(axis=1, keepdims=True)
        U, _, Vt = np.linalg.svd(b @ a.T)
        R = U @ np.diag([1.0, 1.0, np.linalg.det(U @ Vt)]) @ Vt
        c = x.mean(axis=1) - R @ self.arms.mean(axis=1)
        return np.concatenate([c, Rotation.from_matrix(R).as_rotvec()])


def face_kinematics_3d(model, face) -> FaceKinematics3D:
    """Kinematics of the RigidFace ``face`` on a 3-D model."""
    dofs, arms, centroid, ell = face_geometry(model, face.group)
    return FaceKinematics3D(face, dofs, arms, centroid, ell)
