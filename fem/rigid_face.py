"""Rigid faces (2-D and 3-D) and the reduced unknowns of a nonlinear solve.

A :class:`RigidFace` makes a boundary group move as a rigid body about its centroid Xc
(length-weighted in 2-D, area-weighted in 3-D): node a goes to
``x_a = R (X_a - Xc) + Xc + c``, R the rotation by theta (2-D) or by the rotation vector psi
(3-D, :mod:`.rigid_face3d`). The face's DOFs are eliminated in favour of its generalised
coordinates, (c_x, c_y, theta) in 2-D and (c_x, c_y, c_z, psi_x, psi_y, psi_z) in 3-D; those
that are prescribed follow the load factor, the others are unknowns whose generalised loads
(force, moment) are applied. :class:`ReducedSpace` maps the unknowns ``z`` (free DOFs, then
free face coordinates) to the DOF vector ``u``: ``u = u(z, load_factor)``, with the
Jacobian ``T = du/dz`` and the second-derivative (geometric) term of the rotation.

A face rotation is carried as ``s = ell * theta`` (m), with ``ell`` the face's RMS arm
(m), so that all unknowns are lengths and all residuals forces (N).
"""
import math

import numpy as np
import scipy.sparse as sp
import skfem

from .boundary import group_dofs
from .model import rigid_body_modes
from .rigid_face_input import RigidFace  # noqa: F401  (the public name lives here)


class FaceKinematics:
    """A rigid face on a 2-D model: its x and y DOFs (2, n), arms ``X_a - Xc`` (2, n) in m,
    centroid (2,) m and RMS arm ``ell`` (m). Coordinates q = (c_x, c_y, theta) (m, rad)."""

    dim = 2
    rotations = (2,)

    def __init__(self, face, dofs, arms, centroid, ell):
        self.face, self.dofs, self.arms, self.centroid, self.ell = face, dofs, arms, centroid, ell

    @property
    def scale(self) -> np.ndarray:
        """Unknown per coordinate: the rotation carried as ell * theta (m)."""
        return np.array([1.0, 1.0, self.ell])

    def rotated_arms(self, theta: float) -> np.ndarray:
        """(2, n) current arms R(theta) (X_a - Xc), m."""
        c, s = math.cos(theta), math.sin(theta)
        ax, ay = self.arms
        return np.array([c * ax - s * ay, s * ax + c * ay])

    def displacement(self, q: np.ndarray) -> np.ndarray:
        """(2, n) displacement (m) of the face nodes."""
        return self.rotated_arms(q[2]) - self.arms + q[:2, None]

    def linear_displacement(self, q: np.ndarray) -> np.ndarray:
        """(2, n) displacement (m) of the linearised motion c + theta e_z x (X_a - Xc)."""
        ax, ay = self.arms
        return np.array([q[0] - q[2] * ay, q[1] + q[2] * ax])

    def columns(self, q: np.ndarray) -> np.ndarray:
        """(3, 2, n): du/dq_k of the face nodes (m/m, m/rad)."""
        vx, vy = self.rotated_arms(q[2])
        one, zero = np.ones_like(vx), np.zeros_like(vx)
        return np.array([[one, zero], [zero, one], [-vy, vx]])

    def second(self, q: np.ndarray, r: np.ndarray) -> np.ndarray:
        """(3, 3) sum_a r_a . d2u_a/dq dq: -sum_a r_a . R(theta)(X_a - Xc) on the rotation."""
        vx, vy = self.rotated_arms(q[2])
        H = np.zeros((3, 3))
        H[2, 2] = -np.sum(r[self.dofs[0]] * vx + r[self.dofs[1]] * vy)
        return H

    def generalised_force(self, r: np.ndarray, q: np.ndarray) -> np.ndarray:
        """(3,) force (N, N) and moment about the current centroid (N m) of the nodal forces
        ``r`` (full DOF vector) on the face at coordinates ``q``."""
        rx, ry = r[self.dofs[0]], r[self.dofs[1]]
        vx, vy = self.rotated_arms(q[2])
        return np.array([rx.sum(), ry.sum(), float(np.sum(vx * ry - vy * rx))])

    def applied(self, q: np.ndarray, loads: np.ndarray) -> np.ndarray:
        """(3,) generalised loads: in 2-D the force and moment themselves."""
        return np.array(loads, dtype=float)

    def applied_derivative(self, q: np.ndarray, loads: np.ndarray) -> np.ndarray:
        """(3, 3) d applied / dq: zero (a planar moment is conservative)."""
        return np.zeros((3, 3))

    def rigid_fit(self, u: np.ndarray) -> np.ndarray:
        """(3,) (c_x, c_y, theta) of the rigid motion closest to the face's displacement."""
        x = self.arms + u[self.dofs]  # current position relative to the reference centroid
        a = self.arms - self.arms.mean(axis=1, keepdims=True)
        b = x - x.mean(axis=1, keepdims=True)
        theta = math.atan2(np.sum(a[0] * b[1] - a[1] * b[0]), np.sum(a[0] * b[0] + a[1] * b[1]))
        c = x.mean(axis=1) - self.rotated_arms(theta).mean(axis=1)
        return np.array([c[0], c[1], theta])


def face_kinematics(model, face: RigidFace):
    """The kinematics of ``face`` on ``model`` (2-D or 3-D)."""
    face.check_dim(model.dim)
    if model.dim == 3:
        from .rigid_face3d import face_kinematics_3d
        return face_kinematics_3d(model, face)
    dofs = group_dofs(model, face.group)
    if face.group not in model.mesh.boundaries:
        raise ValueError(f"RigidFace({face.group!r}) needs a boundary group, not a subdomain")
    pair = np.array([dofs[0], dofs[1]])
    X = model.basis.doflocs[:, pair[0]]
    fb = skfem.FacetBasis(model.cell_mesh, model.basis.elem, facets=model.mesh.facets(face.group),
                          intorder=2)
    length = float(np.sum(fb.dx))
    centroid = np.array([np.sum(np.asarray(fb.global_coordinates())[i] * fb.dx) for i in range(2)]) / length
    arms = X - centroid[:, None]
    ell = float(np.sqrt(np.mean(np.sum(arms ** 2, axis=0))))
    if not ell > 0:
        raise ValueError(f"RigidFace({face.group!r}) has a single node; it cannot rotate")
    return FaceKinematics(face, pair, arms, centroid, ell)


class ReducedSpace:
    """Unknowns z = (u at free DOFs, free face coordinates [c, ell * rotation]) and the
    map u(z, load_factor). D, xD: constrained DOFs and their full-load values (m)."""

    def __init__(self, model, D: np.ndarray, xD: np.ndarray, faces):
        self.n_dofs, self.dim = model.n_dofs, model.dim
        self.D, self.xD = D, xD
        self.faces = [face_kinematics(model, f) for f in faces]
        taken = np.zeros(self.n_dofs, dtype=int)
        taken[D] = 1
        for fk in self.faces:
            clash = taken[fk.dofs.ravel()] > 0
            if np.any(clash):
                raise ValueError(f"RigidFace({fk.face.group!r}) shares {int(clash.sum())} DOFs with a "
                                 "support or another rigid face; a node can have one constraint")
            taken[fk.dofs.ravel()] = 2
        self.I = np.flatnonzero(taken == 0)
        self.free = [np.flatnonzero(~fk.face.prescribed(self.dim)) for fk in self.faces]
        offsets = np.cumsum([len(self.I)] + [len(f) for f in self.free])
        self.slots = [np.arange(a - len(f), a) for a, f in zip(offsets[1:], self.free)]
        self.n = int(offsets[-1])

    @property
    def symmetric(self) -> bool:
        """False when a 3-D face carries a dead moment on a free rotation (its load stiffness
        is not symmetric)."""
        return not any(fk.dim == 3 and np.any(fk.face.loads(3)[free[free >= 3]] != 0)
                       for fk, free in zip(self.faces, self.free))

    def coordinates(self, z: np.ndarray, load_factor: float) -> list[np.ndarray]:
        """Coordinates q of each face: (c_x, c_y, theta) in 2-D, (c, psi) in 3-D (m, rad)."""
        qs = []
        for fk, free, slot in zip(self.faces, self.free, self.slots):
            q = load_factor * fk.face.values(self.dim)
            q[free] = z[slot] / fk.scale[free]
            qs.append(q)
        return qs

    def displacement(self, z: np.ndarray, load_factor: float) -> np.ndarray:
        """DOF vector u (m)."""
        u = np.zeros(self.n_dofs)
        u[self.I] = z[:len(self.I)]
        u[self.D] = load_factor * self.xD
        for fk, q in zip(self.faces, self.coordinates(z, load_factor)):
            u[fk.dofs] = fk.displacement(q)
        return u

    def jacobian(self, z: np.ndarray, load_factor: float) -> sp.csr_matrix:
        """T = du/dz, (n_dofs, n) sparse."""
        rows, cols, vals = [self.I], [np.arange(len(self.I))], [np.ones(len(self.I))]
        for fk, q, free, slot in zip(self.faces, self.coordinates(z, load_factor), self.free, self.slots):
            columns = fk.columns(q)
            for k, col in zip(free, slot):
                for comp in range(self.dim):
                    rows.append(fk.dofs[comp])
                    cols.append(np.full(fk.dofs.shape[1], col))
                    vals.append(columns[k][comp] / fk.scale[k])
        return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                             shape=(self.n_dofs, self.n))

    def geometric_matrix(self, z, load_factor, r: np.ndarray) -> sp.csr_matrix:
        """(n, n) sum_a r_a . d2u_a/dz2 minus the derivative of the applied face loads
        (N/m): nonzero between free rotations only."""
        n = self.n
        rows, cols, vals = [], [], []
        for fk, q, free, slot in zip(self.faces, self.coordinates(z, load_factor), self.free, self.slots):
            if not any(k in free for k in fk.rotations):
                continue
            block = fk.second(q, r) - load_factor * fk.applied_derivative(q, fk.face.loads(self.dim))
            block = (block / np.outer(fk.scale, fk.scale))[np.ix_(free, free)]
            rows.append(np.repeat(slot, len(slot)))
            cols.append(np.tile(slot, len(slot)))
            vals.append(block.ravel())
        if not vals:
            return sp.csr_matrix((n, n))
        return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                             shape=(n, n))

    def applied(self, load_factor: float, z=None) -> np.ndarray:
        """Generalised loads on the free face coordinates (N), scaled by the load factor, at
        the unknowns ``z`` (None: the reference configuration, as the linear solve takes it)."""
        g = np.zeros(self.n)
        qs = (self.coordinates(z, load_factor) if z is not None
              else [np.zeros(len(fk.scale)) for fk in self.faces])
        for fk, q, free, slot in zip(self.faces, qs, self.free, self.slots):
            loads = fk.applied(q, fk.face.loads(self.dim)) / fk.scale
            g[slot] = load_factor * loads[free]
        return g

    def held_mode_rows(self, model) -> np.ndarray:
        """Rows of the rigid-body modes that the constraints hold: modes at D and the
        prescribed face coordinates they would move, (n_rows, n_modes)."""
        points = model.basis.doflocs
        modes = rigid_body_modes(points)  # (n_modes, n_dofs, dim): per DOF location
        comp = np.empty(self.n_dofs, dtype=int)
        for i, idx in enumerate(model.basis.split_indices()):
            comp[idx] = i
        rows = [modes[:, self.D, comp[self.D]].T]
        centre = points.mean(axis=1)
        for fk in self.faces:
            # each mode's motion of the face centroid and rotation (scaled by ell to match a
            # length): the modes are rigid, so they move the face as one body
            q_of_mode = np.array([_mode_coordinates(fk, k, centre) for k in range(len(modes))]).T
            rows.append(q_of_mode[fk.face.prescribed(self.dim)])
        return np.vstack(rows)


def _mode_coordinates(fk, mode: int, centre: np.ndarray) -> np.ndarray:
    """Face coordinates (c, ell * rotation) moved by rigid-body mode ``mode`` of
    :func:`.model.rigid_body_modes` about ``centre``: translations first, then rotations."""
    dim = fk.dim
    q = np.zeros(len(fk.scale))
    if mode < dim:
        q[mode] = 1.0
        return q
    d = fk.centroid - centre
    if dim == 2:
        q[:2], q[2] = (-d[1], d[0]), fk.ell
        return q
    i, j = [(0, 1), (1, 2), (2, 0)][mode - 3]  # the mode rotates about axis k, i -> j
    axis = np.cross(np.eye(3)[i], np.eye(3)[j])
    q[:3], q[3:] = np.cross(axis, d), fk.ell * axis
    return q
