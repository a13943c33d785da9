"""Rigid faces (2-D) and the reduced unknowns of a nonlinear solve.

A :class:`RigidFace` makes a boundary group move as a rigid body about its centroid Xc
(length-weighted): node a goes to ``x_a = R(theta) (X_a - Xc) + Xc + c``. The face's DOFs
are eliminated in favour of its generalised coordinates (c_x, c_y, theta); those that are
prescribed follow the load factor, the others are unknowns whose generalised loads
(force, moment) are applied. :class:`ReducedSpace` maps the unknowns ``z`` (free DOFs, then
free face coordinates) to the DOF vector ``u``: ``u = u(z, load_factor)``, with the
Jacobian ``T = du/dz`` and the second-derivative (geometric) term of the rotation.

A face rotation is carried as ``s = ell * theta`` (m), with ``ell`` the face's RMS arm
(m), so that all unknowns are lengths and all residuals forces (N).
"""
import math
import numbers
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import skfem

from .boundary import group_dofs
from .model import rigid_body_modes

_COORDS = ("x", "y", "rotation")


def _finite_or_none(value, name):
    if value is None:
        return
    if not (isinstance(value, numbers.Real) and not isinstance(value, bool) and math.isfinite(value)):
        raise ValueError(f"{name} = {value!r} must be a finite number or None (free)")


@dataclass(frozen=True)
class RigidFace:
    """Boundary group ``group`` (2-D) held rigid. ``rotation`` (rad, counter-clockwise) and
    centroid translations ``x``, ``y`` (m) are prescribed at full load (scaled by the load
    factor) or None (free). A free coordinate carries the applied ``force`` (N, (Fx, Fy))
    or ``moment`` (N m, about the current centroid); both default to zero."""

    group: str
    rotation: float | None = None
    x: float | None = None
    y: float | None = None
    moment: float = 0.0
    force: tuple = (0.0, 0.0)

    def __post_init__(self):
        for name in _COORDS:
            _finite_or_none(getattr(self, name), f"RigidFace({self.group!r}).{name}")
        _finite_or_none(self.moment, f"RigidFace({self.group!r}).moment")
        try:
            force = tuple(float(c) for c in self.force)
        except (TypeError, ValueError):
            raise ValueError(f"RigidFace({self.group!r}).force = {self.force!r} must be (Fx, Fy) "
                             "in N") from None
        if len(force) != 2 or not all(math.isfinite(c) for c in force):
            raise ValueError(f"RigidFace({self.group!r}).force = {self.force!r} must be 2 finite "
                             "numbers (Fx, Fy) in N")
        object.__setattr__(self, "force", force)
        for name, load in (("x", force[0]), ("y", force[1]), ("rotation", self.moment)):
            if getattr(self, name) is not None and load != 0.0:
                raise ValueError(f"RigidFace({self.group!r}) prescribes {name} and applies a load "
                                 f"{load} on it; a prescribed coordinate takes a reaction: leave "
                                 f"{name}=None to apply the load")

    def prescribed(self) -> np.ndarray:
        """(3,) bool: which of (x, y, rotation) are prescribed."""
        return np.array([getattr(self, n) is not None for n in _COORDS])

    def values(self) -> np.ndarray:
        """(3,) full-load values (m, m, rad) of the prescribed coordinates (0 where free)."""
        return np.array([getattr(self, n) or 0.0 for n in _COORDS], dtype=float)

    def loads(self) -> np.ndarray:
        """(3,) full-load generalised loads (N, N, N m)."""
        return np.array([self.force[0], self.force[1], self.moment])


@dataclass(frozen=True, eq=False)
class FaceKinematics:
    """A rigid face on a model: its x and y DOFs, arms ``X_a - Xc`` (2, n) in m, centroid
    (2,) m and RMS arm ``ell`` (m)."""

    face: RigidFace
    dofs: np.ndarray  # (2, n): x DOFs, y DOFs of the same nodes
    arms: np.ndarray
    centroid: np.ndarray
    ell: float

    def displacement(self, q: np.ndarray) -> np.ndarray:
        """(2, n) displacement (m) of the face nodes for q = (c_x, c_y, theta)."""
        c, s = math.cos(q[2]), math.sin(q[2])
        ax, ay = self.arms
        return np.array([(c - 1) * ax - s * ay + q[0], s * ax + (c - 1) * ay + q[1]])

    def rotated_arms(self, theta: float) -> np.ndarray:
        """(2, n) current arms R(theta) (X_a - Xc), m."""
        c, s = math.cos(theta), math.sin(theta)
        ax, ay = self.arms
        return np.array([c * ax - s * ay, s * ax + c * ay])

    def generalised_force(self, r: np.ndarray, theta: float) -> np.ndarray:
        """(3,) force (N, N) and moment about the current centroid (N m) of the nodal forces
        ``r`` (full DOF vector) on the face."""
        rx, ry = r[self.dofs[0]], r[self.dofs[1]]
        vx, vy = self.rotated_arms(theta)
        return np.array([rx.sum(), ry.sum(), float(np.sum(vx * ry - vy * rx))])


def face_kinematics(model, face: RigidFace) -> FaceKinematics:
    """Build the kinematics of ``face`` on ``model`` (2-D only)."""
    if model.dim != 2:
        raise ValueError(f"RigidFace({face.group!r}) needs a 2-D model; this one is {model.dim}-D "
                         "(3-D rigid faces are not implemented)")
    dofs = group_dofs(model, face.group)
    if face.group not in model.mesh.boundaries:
        raise ValueError(f"RigidFace({face.group!r}) needs a boundary group, not a subdomain")
    pair = np.array([dofs[0], dofs[1]])
    X = model.basis.doflocs[:, pair[0]]
    fb = skfem.FacetBasis(model.mesh.mesh, model.basis.elem, facets=model.mesh.facets(face.group),
                          intorder=2)
    length = float(np.sum(fb.dx))
    centroid = np.array([np.sum(np.asarray(fb.global_coordinates())[i] * fb.dx) for i in range(2)]) / length
    arms = X - centroid[:, None]
    ell = float(np.sqrt(np.mean(np.sum(arms ** 2, axis=0))))
    if not ell > 0:
        raise ValueError(f"RigidFace({face.group!r}) has a single node; it cannot rotate")
    return FaceKinematics(face, pair, arms, centroid, ell)


class ReducedSpace:
    """Unknowns z = (u at free DOFs, free face coordinates [c_x, c_y, ell * theta]) and the
    map u(z, load_factor). D, xD: constrained DOFs and their full-load values (m)."""

    def __init__(self, model, D: np.ndarray, xD: np.ndarray, faces):
        self.n_dofs = model.n_dofs
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
        self.free = [np.flatnonzero(~fk.face.prescribed()) for fk in self.faces]
        offsets = np.cumsum([len(self.I)] + [len(f) for f in self.free])
        self.slots = [np.arange(a - len(f), a) for a, f in zip(offsets[1:], self.free)]
        self.n = int(offsets[-1])

    def coordinates(self, z: np.ndarray, load_factor: float) -> list[np.ndarray]:
        """(c_x, c_y, theta) of each face (m, m, rad)."""
        qs = []
        for fk, free, slot in zip(self.faces, self.free, self.slots):
            q = load_factor * fk.face.values()
            q[free] = z[slot]
            q[2] = q[2] / fk.ell if 2 in free else q[2]
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
            vx, vy = fk.rotated_arms(q[2])
            columns = {0: (np.ones_like(vx), np.zeros_like(vx)), 1: (np.zeros_like(vx), np.ones_like(vx)),
                       2: (-vy / fk.ell, vx / fk.ell)}
            for k, col in zip(free, slot):
                for comp in range(2):
                    rows.append(fk.dofs[comp])
                    cols.append(np.full(fk.dofs.shape[1], col))
                    vals.append(columns[k][comp])
        return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                             shape=(self.n_dofs, self.n))

    def geometric_term(self, z, load_factor, r: np.ndarray) -> np.ndarray:
        """Diagonal (n,) of sum_a r_a . d2u_a/dz2: nonzero at free rotations only (N/m)."""
        h = np.zeros(self.n)
        for fk, q, free, slot in zip(self.faces, self.coordinates(z, load_factor), self.free, self.slots):
            if 2 in free:
                vx, vy = fk.rotated_arms(q[2])
                h[slot[list(free).index(2)]] = -np.sum(r[fk.dofs[0]] * vx + r[fk.dofs[1]] * vy) / fk.ell ** 2
        return h

    def applied(self, load_factor: float) -> np.ndarray:
        """Generalised loads on the free face coordinates (N), scaled by the load factor."""
        g = np.zeros(self.n)
        for fk, free, slot in zip(self.faces, self.free, self.slots):
            loads = fk.face.loads() / np.array([1.0, 1.0, fk.ell])
            g[slot] = load_factor * loads[free]
        return g

    def held_mode_rows(self, model) -> np.ndarray:
        """Rows of the rigid-body modes that the constraints hold: modes at D and the
        prescribed face coordinates they would move, (n_rows, 3)."""
        points = model.basis.doflocs
        modes = rigid_body_modes(points)  # (3, n_dofs, 2): per DOF location
        comp = np.empty(self.n_dofs, dtype=int)
        for i, idx in enumerate(model.basis.split_indices()):
            comp[idx] = i
        rows = [modes[:, self.D, comp[self.D]].T]
        centre = points.mean(axis=1)
        for fk in self.faces:
            d = fk.centroid - centre
            # translation modes move c by (1, 0), (0, 1); the rotation mode moves c by
            # (-d_y, d_x) and theta by 1 (scaled by ell to match a length)
            q_of_mode = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [-d[1], d[0], fk.ell]]).T
            rows.append(q_of_mode[fk.face.prescribed()])
        return np.vstack(rows)
