"""Assembly and the reduced space of unknowns: supports and rigid links eliminated.

A configuration is (u, R): nodal displacements u (n, 3) m and rotation matrices R (n, 3, 3).
Increments are (du, dw) per node, dw a spatial spin (rad): R <- exp(dw) R. Rigid links are
exact rigid-body constraints (master-slave elimination, as in the planar model):
x_s = x_m + R_m (X_s - X_m), R_s = R_m.
"""
from typing import NamedTuple

import numpy as np
import scipy.sparse as sp

from ..space import independent_dofs
from .corotational import internal_forces, local_deformations
from .element import basic_stiffness, local_matrices, to_global
from ..supports import dof_index, load_vector
from .model import Beam3DModel
from .rotations import expm, logm, skew


def scatter(model: Beam3DModel, ke: np.ndarray) -> sp.csr_matrix:
    """Global sparse matrix from element matrices (n_e, 12, 12) in global DOF order."""
    dofs = (6 * model.elements[:, :, None] + np.arange(6)).reshape(-1, 12)
    rows = np.broadcast_to(dofs[:, :, None], ke.shape).ravel()
    cols = np.broadcast_to(dofs[:, None, :], ke.shape).ravel()
    n = model.n_dofs
    return sp.csr_matrix((ke.ravel(), (rows, cols)), shape=(n, n))


def gather(model: Beam3DModel, fe: np.ndarray) -> np.ndarray:
    """Global vector from element vectors (n_e, 12)."""
    dofs = (6 * model.elements[:, :, None] + np.arange(6)).reshape(-1)
    return np.bincount(dofs, weights=fe.ravel(), minlength=model.n_dofs)


def mass_matrix(model: Beam3DModel, u=None, R=None) -> sp.csr_matrix:
    """Consistent global mass matrix (kg, kg m, kg m^2), point masses included; at a
    configuration (u, R) the element masses turn with their co-rotated frames and the point
    masses' inertia with their nodes (default: undeformed)."""
    _ = model.material.density  # its clear error where the material has none
    frames = model.frames
    if R is not None:
        frames = local_deformations(model, model.nodes + u, R)[1][2]
    E = to_global(frames)
    _, M = local_matrices(model)
    Mg = scatter(model, np.einsum("eij,ejk,elk->eil", E, M, E))
    rows, cols, vals = [], [], []
    for node, (m, jx, jy, jz) in model.point_masses.items():
        k = 6 * int(node)
        J = np.diag([jx, jy, jz]) if R is None else R[node] @ np.diag([jx, jy, jz]) @ R[node].T
        block = np.zeros((6, 6))
        block[:3, :3], block[3:, 3:] = m * np.eye(3), J
        r, c = np.meshgrid(np.arange(k, k + 6), np.arange(k, k + 6), indexing="ij")
        rows.append(r.ravel()), cols.append(c.ravel()), vals.append(block.ravel())
    n = model.n_dofs
    if rows:
        Mg = Mg + sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows),
                                                       np.concatenate(cols))), shape=(n, n))
    return Mg.tocsr()


class SpatialSpace:
    """Unknowns: the DOF increments of independent (non-slave) nodes that are not held.
    Held DOFs move by the load factor's increment times their value (a prescribed
    rotation: a spin about that global axis); slave nodes follow their master rigidly."""

    FLOOR = (1e-10, np.inf)  # the stepper's round-off: a correction of 1e-10 of the
    # configuration (a load-free rigid motion has no force scale to compare with)

    def __init__(self, model: Beam3DModel, supports):
        self.model = model
        n = model.n_dofs
        (self.slaves, self.masters, self.arm, self.held, self.p_hat,
         self.free) = independent_dofs(model, supports)
        self.n = len(self.free)
        self.independent = np.concatenate([self.free, self.held])
        self._col_free = -np.ones(n, dtype=int)
        self._col_free[self.free] = np.arange(self.n)
        self._col_held = -np.ones(n, dtype=int)
        self._col_held[self.held] = np.arange(len(self.held))

    def start(self) -> tuple:
        """The undeformed configuration (u, R), where a solve starts."""
        return self.reference()

    def reference(self):
        """The undeformed configuration (u, R)."""
        n = self.model.n_nodes
        return np.zeros((n, 3)), np.tile(np.eye(3), (n, 1, 1))

    def control_index(self, control) -> int:
        """The free unknown of ``control`` = (node, translation dof, value)."""
        node, dof, _ = control
        k = dof_index(dof, 6)
        where = np.flatnonzero(self.free == 6 * int(node) + k)
        if k > 2 or not len(where):
            raise ValueError(f"control = {control!r}: control a free translation DOF (not "
                             "held, not on a rigid-link slave, not a rotation)")
        return int(where[0])

    def advance(self, config, dz, dlam) -> tuple:
        """update() of a configuration (u, R)."""
        return self.update(*config, dz, dlam)

    def size(self, config) -> float:
        """|(u, log R)| over the free unknowns (m, rad)."""
        u, R = config
        return np.linalg.norm(np.hstack([u, logm(R)]).ravel()[self.free])

    def value(self, config, k: int) -> float:
        """Free translation unknown k's displacement (m)."""
        full = self.free[k]
        return config[0][full // 6, full % 6]

    def update(self, u, R, dz, dlam):
        """New (u, R) after free increments dz and a load-factor increment dlam."""
        inc = np.zeros(self.model.n_dofs)
        inc[self.free] = dz
        inc[self.held] = dlam * self.p_hat
        inc = inc.reshape(-1, 6)
        u = u + inc[:, :3]
        R = np.einsum("nij,njk->nik", expm(inc[:, 3:]), R)
        if len(self.slaves):
            Rm = R[self.masters]
            u[self.slaves] = u[self.masters] + np.einsum("sij,sj->si", Rm, self.arm) - self.arm
            R[self.slaves] = Rm
        return u, R

    def jacobian(self, R):
        """Sparse d(full increments)/dz (T) and d/dp (T_p, the held DOFs) at rotations R."""
        rows, cols = [self.independent], [self.independent]
        vals = [np.ones(len(self.independent))]
        if len(self.slaves):
            b = np.einsum("sij,sj->si", R[self.masters], self.arm)
            Sb = -skew(b)  # du_s = du_m + dw_m x b = du_m - S(b) dw_m
            sd, md = 6 * self.slaves, 6 * self.masters
            for k in range(6):
                rows.append(sd + k)
                cols.append(md + k)
                vals.append(np.ones(len(sd)))
            for i in range(3):
                for j in range(3):
                    rows.append(sd + i)
                    cols.append(md + 3 + j)
                    vals.append(Sb[:, i, j])
        rows, cols, vals = np.concatenate(rows), np.concatenate(cols), np.concatenate(vals)
        n = self.model.n_dofs
        out = []
        for column, width in ((self._col_free, self.n), (self._col_held, len(self.held))):
            k = column[cols]
            keep = k >= 0
            out.append(sp.csr_matrix((vals[keep], (rows[keep], k[keep])), shape=(n, width)))
        return out[0], out[1]

    def constraint_tangent(self, R, r_full) -> sp.csr_matrix:
        """Full (n_dofs, n_dofs) second-order term of the links: the slave force r_s turns
        with the arm b = R_m (X_s - X_m), K = S(r_s) S(b) on the master's spins."""
        n = self.model.n_dofs
        if not len(self.slaves):
            return sp.csr_matrix((n, n))
        b = np.einsum("sij,sj->si", R[self.masters], self.arm)
        rs = r_full.reshape(-1, 6)[self.slaves, :3]
        blocks = skew(rs) @ skew(b)
        md = 6 * self.masters + 3
        rows = np.broadcast_to(md[:, None, None] + np.arange(3)[None, :, None], blocks.shape)
        cols = np.broadcast_to(md[:, None, None] + np.arange(3)[None, None, :], blocks.shape)
        return sp.csr_matrix((blocks.ravel(), (rows.ravel(), cols.ravel())), shape=(n, n))


class Evaluation3D(NamedTuple):
    """A state: r (n_dofs,) = f_int - lam f_ext (N, N m), rz = T^T r, K the reduced
    tangent (None without), T and Tp the link Jacobians, Kf the full tangent, fl the
    elements' local forces."""

    r: np.ndarray
    rz: np.ndarray
    K: object
    T: object
    Tp: object
    Kf: object
    fl: object


class SpatialAssembler:
    """Internal force, residual and reduced tangent of a model at a configuration."""

    def __init__(self, model: Beam3DModel, supports, loads):
        self.model = model
        self.space = SpatialSpace(model, supports)
        self.f_ext = load_vector(model, loads)
        self.Kb = basic_stiffness(model)

    def evaluate(self, u, R, lam, tangent=True):
        """(r_full, rz, Kz, T, T_p, K_full, f_l) with r = f_int - lam f_ext (N, N m)."""
        x = self.model.nodes + u
        fe, ke, fl = internal_forces(self.model, self.Kb, x, R, tangent)
        r = gather(self.model, fe) - lam * self.f_ext
        T, Tp = self.space.jacobian(R)
        rz = T.T @ r
        if not tangent:
            return Evaluation3D(r, rz, None, T, Tp, None, fl)
        K = scatter(self.model, ke) + self.space.constraint_tangent(R, r)
        Kz = (T.T @ K @ T).tocsc()
        return Evaluation3D(r, rz, Kz, T, Tp, K, fl)

    def at(self, config, lam, tangent=True) -> Evaluation3D:
        """evaluate() of a configuration (u, R): the stepper's state."""
        return self.evaluate(*config, lam, tangent)

    def load_rate(self, ev: Evaluation3D) -> np.ndarray:
        """d(rz)/d(lam) = T^T (K T_p p - f_ext)."""
        p = self.space.p_hat
        g = -(ev.T.T @ self.f_ext)
        if len(p):
            g = g + ev.T.T @ (ev.Kf @ (ev.Tp @ p))
        return g


def symmetric_tangent(asm: SpatialAssembler, about=None):
    """(K_z, T, u, R): the reduced tangent about a converged state ``about`` (a Beam3DState
    of the same model, supports and loads; default undeformed), symmetric. ValueError if
    it is not symmetric (to 1e-6, Jacobi-scaled): at equilibrium it is only under
    dead forces; dead moments about fixed axes are not conservative for finite rotations,
    and then modes and compliance about the state are not defined by a symmetric K."""
    if about is None:
        (u, R), lam = asm.space.reference(), 0.0
    else:
        if getattr(about, "model", None) is not asm.model:
            raise ValueError("about: a Beam3DState of this model is needed")
        u, R, lam = about.u, about.R, about.load_factor
    _, _, K, T, _, _, _ = asm.evaluate(u, R, lam)
    d = sp.diags(1.0 / np.sqrt(np.abs(K.diagonal())))
    skew_part = abs(d @ (K - K.T) @ d).max()  # Jacobi-scaled: DOFs of any stiffness compare
    if skew_part > 1e-6:
        raise ValueError(f"about: the tangent is not symmetric ({skew_part:.1e}, Jacobi-"
                         "scaled): applied moments at a rotated state, or a state that is "
                         "not converged for these supports and loads")
    return (0.5 * (K + K.T)).tocsc(), T, u, R
