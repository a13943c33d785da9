"""Finite rotations: rotation vectors, rotation matrices and the tangent operators of the
rotation vector (all vectorised over leading axes).

A rotation vector theta (rad) is the axis times the angle; exp(theta) its rotation matrix
(Rodrigues). Rotations are composed multiplicatively, R <- exp(dw) R with dw a spatial spin
(rad), never added as vectors. T_s^-1(theta) maps a spin dw of the rotated frame to the
change of its rotation vector, d theta = T_s^-1(theta) dw (Battini & Pacoste 2002).
"""
import numpy as np

SMALL = 1e-4  # rad, below which the series of the tangent coefficients are used


def skew(v) -> np.ndarray:
    """(..., 3, 3) skew matrices S(v) with S(v) a = v x a."""
    v = np.asarray(v, dtype=float)
    S = np.zeros(v.shape[:-1] + (3, 3))
    S[..., 0, 1], S[..., 0, 2] = -v[..., 2], v[..., 1]
    S[..., 1, 0], S[..., 1, 2] = v[..., 2], -v[..., 0]
    S[..., 2, 0], S[..., 2, 1] = -v[..., 1], v[..., 0]
    return S


def expm(theta) -> np.ndarray:
    """(..., 3, 3) rotation matrices of rotation vectors theta (..., 3), rad (Rodrigues)."""
    theta = np.asarray(theta, dtype=float)
    t = np.linalg.norm(theta, axis=-1)[..., None, None]
    small = t < SMALL
    ts = np.where(small, 1.0, t)
    a = np.where(small, 1.0 - t**2 / 6.0, np.sin(ts) / ts)
    b = np.where(small, 0.5 - t**2 / 24.0, (1.0 - np.cos(ts)) / ts**2)
    S = skew(theta)
    return np.eye(3) + a * S + b * (S @ S)


def logm(R) -> np.ndarray:
    """(..., 3) rotation vectors (angle in [0, pi], rad) of rotation matrices R (..., 3, 3),
    through the unit quaternion (Shepperd's method: accurate up to pi)."""
    R = np.asarray(R, dtype=float)
    d = np.stack([R[..., 0, 0] + R[..., 1, 1] + R[..., 2, 2],
                  R[..., 0, 0], R[..., 1, 1], R[..., 2, 2]], axis=-1)
    k = np.argmax(d, axis=-1)
    q = np.zeros(R.shape[:-2] + (4,))  # (w, x, y, z)
    dk = np.take_along_axis(d, k[..., None], axis=-1)[..., 0]
    a = np.sqrt(np.maximum(np.where(k == 0, 1.0 + d[..., 0], 1.0 + 2.0 * dk - d[..., 0]),
                           0.0)) / 2.0  # the largest quaternion component
    w21, w02 = R[..., 2, 1] - R[..., 1, 2], R[..., 0, 2] - R[..., 2, 0]
    w10 = R[..., 1, 0] - R[..., 0, 1]
    s01, s02 = R[..., 0, 1] + R[..., 1, 0], R[..., 0, 2] + R[..., 2, 0]
    s12 = R[..., 1, 2] + R[..., 2, 1]
    f = 1.0 / (4.0 * a)
    cases = [np.stack([a, w21 * f, w02 * f, w10 * f], -1),
             np.stack([w21 * f, a, s01 * f, s02 * f], -1),
             np.stack([w02 * f, s01 * f, a, s12 * f], -1),
             np.stack([w10 * f, s02 * f, s12 * f, a], -1)]
    for j, value in enumerate(cases):
        q = np.where((k == j)[..., None], value, q)
    q = np.where(q[..., 0:1] < 0, -q, q)
    v = q[..., 1:]
    s = np.linalg.norm(v, axis=-1)
    angle = 2.0 * np.arctan2(s, q[..., 0])
    factor = np.where(s > 1e-12, angle / np.where(s > 1e-12, s, 1.0), 2.0 / q[..., 0])
    return factor[..., None] * v


def ts_inv(theta) -> np.ndarray:
    """(..., 3, 3) T_s^-1(theta) = a I + (1 - a) e e^T - S(theta) / 2, a = (t/2) / tan(t/2),
    e = theta / t."""
    theta = np.asarray(theta, dtype=float)
    t = np.linalg.norm(theta, axis=-1)[..., None, None]
    small = t < SMALL
    ts = np.where(small, 1.0, t)
    a = np.where(small, 1.0 - t**2 / 12.0, (ts / 2.0) / np.tan(ts / 2.0))
    c = np.where(small, 1.0 / 12.0 + t**2 / 720.0, (1.0 - a) / ts**2)
    outer = theta[..., :, None] * theta[..., None, :]
    return a * np.eye(3) + c * outer - 0.5 * skew(theta)


def ts_inv_tangent(theta, m) -> np.ndarray:
    """(..., 3, 3) K_h = d(T_s^-T(theta) m)/d theta . T_s^-1(theta): the stiffness from
    the variation of T_s^-1 under the moment m (..., 3), N m (Battini & Pacoste 2002)."""
    theta, m = np.asarray(theta, dtype=float), np.asarray(m, dtype=float)
    t = np.linalg.norm(theta, axis=-1)[..., None, None]
    small = t < SMALL
    ts = np.where(small, 1.0, t)
    s, c, s2 = np.sin(ts), np.cos(ts), np.sin(ts / 2.0) ** 2
    eta = np.where(small, 1.0 / 12.0 + t**2 / 720.0,
                   (2.0 * s - ts * (1.0 + c)) / (2.0 * ts**2 * s))
    mu = np.where(small, 1.0 / 360.0 + t**2 / 7560.0,
                  (ts * (ts + s) - 8.0 * s2) / (4.0 * ts**4 * s2))
    th_m = np.einsum("...i,...j->...ij", theta, m)
    m_th = np.einsum("...i,...j->...ij", m, theta)
    dot = np.einsum("...i,...i->...", theta, m)[..., None, None]
    St = skew(theta)
    K = (eta * (th_m - 2.0 * m_th + dot * np.eye(3)) + mu * (St @ St @ m_th)
         - 0.5 * skew(m))
    return K @ ts_inv(theta)
