"""Kinematics of a rigid face in 3-D: six master coordinates q = (c, psi) about the face's
area centroid Xc, node a moving to ``x_a = R(psi) (X_a - Xc) + Xc + c`` with R(psi) =
exp([psi]x) the rotation of the rotation vector psi (rad; Rodrigues' formula).

The first and second derivatives of R(psi) are those of Rodrigues' R = I + a X + b X^2
(X = [psi]x), with the coefficients' Taylor series near psi = 0. Moments are spatial
(global axes, about the current centroid); a moment applied on the face is dead (fixed
direction), its generalised load on psi is T(psi)^T M with the tangent operator
T_j = axial(dR/dpsi_j R^T).
"""
import math
from dataclasses import dataclass

import numpy as np

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


def _coefficients(theta: float) -> tuple:
    """(a, a1, a2, b, b1, b2) of R = I + a X + b X^2, X = [psi]x, theta = |psi|:
    a = sin(theta) / theta, b = (1 - cos(theta)) / theta^2, f1 = f' / theta and
    f2 = f1' / theta; their Taylor series below theta = 1 (no cancellation at 0)."""
    if theta < 1.0:
        n = np.arange(12)
        t2n = theta ** (2 * n)
        sign = (-1.0) ** n
        fa = np.array([math.factorial(2 * k + 1) for k in n], dtype=float)
        fb = np.array([math.factorial(2 * k + 2) for k in n], dtype=float)
        up1 = np.concatenate([t2n[:-1], [0.0]])  # theta^(2n - 2) at index n
        up2 = np.concatenate([t2n[:-2], [0.0, 0.0]])
        a, b = np.sum(sign * t2n / fa), np.sum(sign * t2n / fb)
        a1 = np.sum((sign * 2 * n / fa)[1:] * up1[:-1])
        b1 = np.sum((sign * 2 * n / fb)[1:] * up1[:-1])
        a2 = np.sum((sign * 2 * n * (2 * n - 2) / fa)[2:] * up2[:-2])
        b2 = np.sum((sign * 2 * n * (2 * n - 2) / fb)[2:] * up2[:-2])
        return a, a1, a2, b, b1, b2
    s, c, t = math.sin(theta), math.cos(theta), theta
    return (s / t, (t * c - s) / t ** 3, (3 * s - 3 * t * c - t * t * s) / t ** 5,
            (1 - c) / t ** 2, (t * s - 2 * (1 - c)) / t ** 4,
            (t * t * c - 5 * t * s + 8 * (1 - c)) / t ** 6)


def rotation_derivatives(psi) -> tuple:
    """(R (3, 3), dR (3, 3, 3): dR/dpsi_j, d2R (3, 3, 3, 3): d2R/dpsi_j dpsi_k) at the
    rotation vector ``psi`` (rad), differentiating R = I + a X + b X^2 (Rodrigues)."""
    psi = np.asarray(psi, dtype=float)
    X = skew(psi)
    X2 = X @ X
    a, a1, a2, b, b1, b2 = _coefficients(float(np.linalg.norm(psi)))
    R = np.eye(3) + a * X + b * X2
    EX = _E @ X + X @ _E  # d(X^2)/dpsi_j
    dR = (a1 * X + b1 * X2)[None] * psi[:, None, None] + a * _E + b * EX
    pp, eye = np.outer(psi, psi)[:, :, None, None], np.eye(3)[:, :, None, None]
    d2R = ((a2 * pp + a1 * eye) * X + (b2 * pp + b1 * eye) * X2
           + a1 * (psi[:, None, None, None] * _E[None] + psi[None, :, None, None] * _E[:, None])
           + b1 * (psi[:, None, None, None] * EX[None] + psi[None, :, None, None] * EX[:, None])
           + b * (np.einsum("jpm,kmq->jkpq", _E, _E) + np.einsum("kpm,jmq->jkpq", _E, _E)))
    return R, dR, d2R


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
