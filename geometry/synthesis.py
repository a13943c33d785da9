"""Five-position synthesis of RR constraints (eight-bar thesis, Chapters 3-4).

Positions are planar homogeneous transforms ([T] of Eq. 3.12, 3x3, lengths in m). The RR dyad
of a four-bar (Eqs. 3.20-3.28) is the special case of the RR constraint between two moving
links (Eqs. 4.3-4.6) where the first link is the ground, so one solver serves both: the first of
the five equations is subtracted from the others (as the thesis does), and the four bilinear
equations in G1 = (u, v), W1 = (x, y) are solved from many starting points by Newton
(pseudo-inverse steps, clipped to the box size);
converged roots are de-duplicated and the length R follows from Eq. 3.24 / 4.6 with j = 1.
"""
from dataclasses import dataclass

import numpy as np


def planar_transform(phi: float, dx: float, dy: float) -> np.ndarray:
    """Homogeneous transform [T(phi, d)] (Eq. 3.12): rotation phi (rad), translation d (m)."""
    c, s = np.cos(phi), np.sin(phi)
    return np.array([[c, -s, dx], [s, c, dy], [0.0, 0.0, 1.0]])


def joint_transform(theta: float, a: float) -> np.ndarray:
    """Z(theta, a) of Eq. 4.1: translate a (m) along x, then rotate theta (rad) (Eq. 3.15's
    [X(a)][Z(theta)])."""
    return planar_transform(0.0, a, 0.0) @ planar_transform(theta, 0.0, 0.0)


@dataclass(frozen=True)
class RRConstraint:
    """An RR link: joint G1 on the first link and W1 on the second (m, fixed-frame coordinates
    in the first task position) and its length R (m). For a four-bar dyad, G1 is the ground
    pivot and W1 the moving pivot (Eqs. 3.20-3.28)."""

    g1: tuple
    w1: tuple
    length: float


def relative_displacements(poses) -> np.ndarray:
    """[D_1j] = [T_j][T_1]^-1 (Eqs. 3.23, 4.4) for a sequence of 3x3 poses; shape (n, 3, 3)."""
    poses = np.asarray(poses, float)
    return poses @ np.linalg.inv(poses[0])


def rr_constraint_residual(z, rel_l, rel_k) -> np.ndarray:
    """Eq. 4.6 minus its first row, for unknowns z = (u, v, x, y) (m), shape (..., n - 1);
    rel_l, rel_k: relative displacements of the two links (n, 3, 3)."""
    g, w = z[..., None, :2], z[..., None, 2:]
    e = (np.einsum("jab,...jb->...ja", rel_l[:, :2, :2], g) + rel_l[:, :2, 2]
         - np.einsum("jab,...jb->...ja", rel_k[:, :2, :2], w) - rel_k[:, :2, 2])
    sq = np.sum(e**2, axis=-1)
    return sq[..., 1:] - sq[..., :1]


def _residual_and_jacobian(z, rel_l, rel_k):
    g, w = z[:, None, :2], z[:, None, 2:]
    al, ak = rel_l[:, :2, :2], rel_k[:, :2, :2]
    e = (np.einsum("jab,njb->nja", al, g) + rel_l[:, :2, 2]
         - np.einsum("jab,njb->nja", ak, w) - rel_k[:, :2, 2])
    sq = np.sum(e**2, axis=-1)
    d_g = 2 * np.einsum("nja,jab->njb", e, al)      # d|e_j|^2 / dG
    d_w = -2 * np.einsum("nja,jab->njb", e, ak)     # d|e_j|^2 / dW
    jac = np.concatenate([d_g, d_w], axis=-1)       # (n, J, 4)
    return sq[:, 1:] - sq[:, :1], jac[:, 1:] - jac[:, :1]


def rr_constraint_synthesis(poses_l, poses_k, *, n_starts=400, seed=0, box=None,
                            min_length=None) -> list:
    """All RR links found between two bodies moving through five positions (Eqs. 4.3-4.6).

    poses_l, poses_k: five 3x3 transforms of each body (the identity five times for the ground).
    box: (xmin, xmax, ymin, ymax) in m for the random starts (default: three times the span of
    the bodies' origins around their centre). Solutions with R < min_length (default 1e-6 of
    the box size) are dropped: they are the joint the two bodies may already share.
    """
    poses_l, poses_k = np.asarray(poses_l, float), np.asarray(poses_k, float)
    if poses_l.shape != (5, 3, 3) or poses_k.shape != (5, 3, 3):
        raise ValueError(f"poses: shapes {poses_l.shape}, {poses_k.shape}, must be (5, 3, 3)")
    rel_l, rel_k = relative_displacements(poses_l), relative_displacements(poses_k)
    if box is None:
        origins = np.concatenate([poses_l[:, :2, 2], poses_k[:, :2, 2]])
        centre = origins.mean(axis=0)
        half = 1.5 * max(np.ptp(origins, axis=0).max(), 1e-3)
        box = (centre[0] - 2 * half, centre[0] + 2 * half, centre[1] - 2 * half, centre[1] + 2 * half)
    scale = max(box[1] - box[0], box[3] - box[2])
    min_length = 1e-6 * scale if min_length is None else min_length
    rng = np.random.default_rng(seed)
    lo, hi = np.array([box[0], box[2]] * 2), np.array([box[1], box[3]] * 2)
    z = lo + (hi - lo) * rng.random((n_starts, 4))
    for _ in range(60):
        f, jac = _residual_and_jacobian(z, rel_l, rel_k)
        step = -np.einsum("nij,nj->ni", np.linalg.pinv(jac, rcond=1e-12), f)
        z = z + np.clip(step, -scale, scale)
        z = np.where(np.isfinite(z), z, lo + (hi - lo) * rng.random(z.shape))
    f = rr_constraint_residual(z, rel_l, rel_k)
    converged = np.max(np.abs(f), axis=1) < 1e-10 * scale**2
    found = []
    for zi in z[converged]:
        g, w = zi[:2], zi[2:]
        length = float(np.hypot(*(g - w)))
        if length < min_length or np.max(np.abs(zi)) > 1e3 * scale:
            continue
        if all(np.max(np.abs(zi - np.r_[s.g1, s.w1])) > 1e-7 * scale for s in found):
            found.append(RRConstraint(tuple(g), tuple(w), length))
    return sorted(found, key=lambda s: s.g1)


def rr_dyad_synthesis(task_poses, **options) -> list:
    """RR dyads (ground pivot G, moving pivot W1, crank length R) guiding a body through five
    task positions (Eqs. 3.20-3.28): at most four real solutions; any two form a four-bar."""
    task_poses = np.asarray(task_poses, float)
    return rr_constraint_synthesis(np.broadcast_to(np.eye(3), task_poses.shape), task_poses,
                                   **options)


# -- 3R chains of the eight-bar synthesis (Section 3.3, Chapter 4) -------------------------------
@dataclass(frozen=True)
class ThreeRChain:
    """Planar 3R chain: base frame [G], link lengths a1, a2 (m), task-to-end-effector [H]
    (Eq. 4.1), and the elbow branch (+1 or -1)."""

    base: np.ndarray
    a1: float
    a2: float
    tool: np.ndarray
    elbow: int = 1

    def __post_init__(self):
        for key in ("a1", "a2"):
            if not getattr(self, key) > 0:
                raise ValueError(f"{key} = {getattr(self, key)} m, must be > 0")
        if self.elbow not in (1, -1):
            raise ValueError(f"elbow = {self.elbow}, must be +1 or -1")


def three_r_inverse_kinematics(chain: ThreeRChain, task) -> tuple:
    """Joint angles (theta1, theta2, theta3), rad, reaching the task frame [D] (Eq. 4.2)."""
    wrist_frame = np.linalg.inv(chain.base) @ np.asarray(task, float) @ np.linalg.inv(chain.tool)
    px, py = wrist_frame[:2, 2]
    c2 = (px**2 + py**2 - chain.a1**2 - chain.a2**2) / (2 * chain.a1 * chain.a2)
    if abs(c2) > 1:
        raise ValueError(f"task position at distance {np.hypot(px, py):.6g} m from the base is "
                         f"out of reach of the 3R chain (a1 + a2 = {chain.a1 + chain.a2:.6g} m)")
    t2 = chain.elbow * np.arccos(c2)
    t1 = np.arctan2(py, px) - np.arctan2(chain.a2 * np.sin(t2), chain.a1 + chain.a2 * np.cos(t2))
    t3 = np.arctan2(wrist_frame[1, 0], wrist_frame[0, 0]) - t1 - t2
    return t1, t2, t3


def three_r_link_poses(chain: ThreeRChain, tasks) -> np.ndarray:
    """Frames [B_1j], [B_2j], [B_3j] of the three moving links for each task position:
    shape (3, n, 3, 3); B1 = G Z(t1, 0), B2 = B1 Z(t2, a1), B3 = B2 Z(t3, a2) (Eq. 4.1)."""
    out = np.empty((3, len(tasks), 3, 3))
    for j, task in enumerate(tasks):
        t1, t2, t3 = three_r_inverse_kinematics(chain, task)
        out[0, j] = chain.base @ joint_transform(t1, 0.0)
        out[1, j] = out[0, j] @ joint_transform(t2, chain.a1)
        out[2, j] = out[1, j] @ joint_transform(t3, chain.a2)
    return out


def eightbar_constraint_synthesis(chain_a: ThreeRChain, chain_b: ThreeRChain, tasks, pairs,
                                  **options) -> dict:
    """RR constraints between links of two 3R chains reaching five task positions (Ch. 4).

    Links are named ("ground",), ("a", i) or ("b", i), i = 1, 2, 3 (3 is the end-effector);
    pairs: the (link, link) pairs to constrain. Returns {pair: [RRConstraint, ...]}.
    """
    tasks = np.asarray(tasks, float)
    poses = {("ground",): np.broadcast_to(np.eye(3), tasks.shape)}
    for tag, chain in (("a", chain_a), ("b", chain_b)):
        for i, frames in enumerate(three_r_link_poses(chain, tasks), start=1):
            poses[(tag, i)] = frames
    return {pair: rr_constraint_synthesis(poses[pair[0]], poses[pair[1]], **options)
            for pair in pairs}
