"""Assembly and the reduced space of unknowns: supports and rigid links eliminated.

Rigid links are exact rigid-body constraints (master-slave elimination), not stiff beams: a
stiff beam 10^4-10^6 times stiffer than the flexures would raise the condition number of K
by as much and spoil the Newton convergence test of the flexible part, while elimination
keeps the system as well conditioned as the flexures alone and is exact at large rotations:
x_s = x_m + R(theta_m) (X_s - X_m), theta_s = theta_m.
"""
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .element import basic_stiffness, corotational, local_mass, rotation_to_global
from .model import BeamModel, Fixed, NodalLoad, Prescribed

DENSE_EIGEN_LIMIT = 800  # unknowns up to which modal analysis uses a dense eigensolver


class SingularBeamError(ValueError):
    """The reduced stiffness is singular: a mechanism (supports leave a motion free)."""


def scatter(model: BeamModel, ke: np.ndarray) -> sp.csr_matrix:
    """Global sparse matrix from element matrices (n_e, 6, 6) in global DOF order."""
    dofs = (3 * model.elements[:, :, None] + np.arange(3)).reshape(-1, 6)
    rows = np.broadcast_to(dofs[:, :, None], ke.shape).ravel()
    cols = np.broadcast_to(dofs[:, None, :], ke.shape).ravel()
    n = model.n_dofs
    return sp.csr_matrix((ke.ravel(), (rows, cols)), shape=(n, n))


def gather(model: BeamModel, fe: np.ndarray) -> np.ndarray:
    """Global vector from element vectors (n_e, 6)."""
    dofs = (3 * model.elements[:, :, None] + np.arange(3)).reshape(-1)
    return np.bincount(dofs, weights=fe.ravel(), minlength=model.n_dofs)


def mass_matrix(model: BeamModel) -> sp.csr_matrix:
    """Consistent global mass matrix (kg, kg m, kg m^2), point masses included."""
    T = rotation_to_global(model.angles)
    M = scatter(model, np.einsum("eki,ekl,elj->eij", T, local_mass(model), T))
    diag = np.zeros(model.n_dofs)
    for node, (m, J) in model.point_masses.items():
        diag[3 * int(node):3 * int(node) + 2] += m
        diag[3 * int(node) + 2] += J
    return (M + sp.diags(diag)).tocsr()


def load_vector(model: BeamModel, loads) -> np.ndarray:
    """Full-load vector (N, N m) from NodalLoad objects."""
    f = np.zeros(model.n_dofs)
    for load in loads:
        if not isinstance(load, NodalLoad):
            raise ValueError(f"loads: {load!r} is not a NodalLoad")
        if not 0 <= int(load.node) < model.n_nodes:
            raise ValueError(f"loads: node {load.node} outside 0..{model.n_nodes - 1}")
        f[3 * int(load.node):3 * int(load.node) + 3] += (load.fx, load.fy, load.m)
    return f


class Space:
    """Unknowns z: the DOFs of independent (non-slave) nodes that are not prescribed.

    q(z, lam): full (n_nodes, 3) DOFs; prescribed DOFs = lam * value; slave nodes follow
    their master rigidly. jacobian(q) -> sparse T = dq/dz (and T_p = dq/dp for the
    prescribed values p)."""

    def __init__(self, model: BeamModel, supports):
        self.model = model
        n = model.n_dofs
        values = np.full(n, np.nan)
        for sup in supports:
            if not isinstance(sup, (Fixed, Prescribed)):
                raise ValueError(f"supports: {sup!r} is not a Fixed or Prescribed")
            for node, dof, value in sup.prescribed():
                if not 0 <= node < model.n_nodes:
                    raise ValueError(f"supports: node {node} outside 0..{model.n_nodes - 1}")
                if model.master_of[node] >= 0:
                    raise ValueError(f"supports: node {node} is a rigid-link slave; "
                                     f"support its master {model.master_of[node]}")
                values[3 * node + dof] = value
        slave_dofs = (3 * np.flatnonzero(model.master_of >= 0)[:, None] + np.arange(3)).ravel()
        self.held = np.flatnonzero(~np.isnan(values))
        self.p_hat = values[self.held]
        dependent = np.zeros(n, dtype=bool)
        dependent[slave_dofs] = True
        dependent[self.held] = True
        self.free = np.flatnonzero(~dependent)
        self.slaves = np.flatnonzero(model.master_of >= 0)
        self.masters = model.master_of[self.slaves]
        self.arm = model.nodes[self.slaves] - model.nodes[self.masters]
        self.n = len(self.free)
        self.independent = np.concatenate([self.free, self.held])
        self._col_free = -np.ones(n, dtype=int)
        self._col_free[self.free] = np.arange(len(self.free))
        self._col_held = -np.ones(n, dtype=int)
        self._col_held[self.held] = np.arange(len(self.held))
        if self.n == 0:
            raise ValueError("supports: every DOF is held; nothing to solve")

    def q(self, z, lam) -> np.ndarray:
        """(n_nodes, 3) DOFs for unknowns z and load factor lam."""
        flat = np.zeros(self.model.n_dofs)
        flat[self.free] = z
        flat[self.held] = lam * self.p_hat
        q = flat.reshape(-1, 3)
        if len(self.slaves):
            qm = q[self.masters]
            c, s = np.cos(qm[:, 2]), np.sin(qm[:, 2])
            ax, ay = self.arm[:, 0], self.arm[:, 1]
            q[self.slaves, 0] = qm[:, 0] + c * ax - s * ay - ax
            q[self.slaves, 1] = qm[:, 1] + s * ax + c * ay - ay
            q[self.slaves, 2] = qm[:, 2]
        return q

    def jacobian(self, q):
        """Sparse dq/dz (T, for the free DOFs) and dq/dp (T_p, for the held ones)."""
        rows, cols = [self.independent], [self.independent]
        vals = [np.ones(len(self.independent))]
        if len(self.slaves):
            th = q[self.masters, 2]
            c, s = np.cos(th), np.sin(th)
            ax, ay = self.arm[:, 0], self.arm[:, 1]
            sd, md = 3 * self.slaves, 3 * self.masters
            for r, col, v in [(0, 0, 1.0), (1, 1, 1.0), (2, 2, 1.0),
                              (0, 2, -s * ax - c * ay), (1, 2, c * ax - s * ay)]:
                rows.append(sd + r)
                cols.append(md + col)
                vals.append(np.broadcast_to(v, sd.shape))
        rows, cols, vals = np.concatenate(rows), np.concatenate(cols), np.concatenate(vals)
        n = self.model.n_dofs
        out = []
        for column, width in ((self._col_free, self.n), (self._col_held, len(self.held))):
            k = column[cols]
            keep = k >= 0
            out.append(sp.csr_matrix((vals[keep], (rows[keep], k[keep])), shape=(n, width)))
        return out[0], out[1]

    def constraint_tangent(self, q, r_full) -> np.ndarray:
        """Second-order term sum_s r_s . d^2 x_s / d theta_m^2 on the free theta_m DOFs
        (dense diagonal contribution, (n, n) as a sparse diagonal)."""
        diag = np.zeros(self.model.n_dofs)
        if len(self.slaves):
            th = q[self.masters, 2]
            c, s = np.cos(th), np.sin(th)
            ax, ay = self.arm[:, 0], self.arm[:, 1]
            rs = r_full.reshape(-1, 3)[self.slaves]
            term = rs[:, 0] * (-c * ax + s * ay) + rs[:, 1] * (-s * ax - c * ay)
            np.add.at(diag, 3 * self.masters + 2, term)
        return sp.diags(diag[self.free])


class Assembler:
    """Internal force, residual and reduced tangent of a model at a state."""

    def __init__(self, model: BeamModel, supports, loads):
        self.model = model
        self.space = Space(model, supports)
        self.f_ext = load_vector(model, loads)
        self.Kb = basic_stiffness(model)

    def evaluate(self, z, lam, tangent=True):
        """(q, r_full, rz, Kz, T, T_p, K_full) with r = f_int - lam f_ext (N, N m)."""
        q = self.space.q(z, lam)
        fe, ke, _ = corotational(self.model, self.Kb, q, tangent)
        r = gather(self.model, fe) - lam * self.f_ext
        T, Tp = self.space.jacobian(q)
        rz = T.T @ r
        if not tangent:
            return q, r, rz, None, T, Tp, None
        K = scatter(self.model, ke)
        Kz = (T.T @ K @ T + self.space.constraint_tangent(q, r)).tocsc()
        return q, r, rz, Kz, T, Tp, K


class Factor:
    """Sparse LU (SuperLU: single-threaded, fast for the banded systems of beam models) of
    the Jacobi-scaled K (unit diagonal, so that pivots compare across DOFs of any
    stiffness). Raises SingularBeamError if K is (numerically) singular. ``sign``: the sign
    of det K (it flips where the tangent loses definiteness: a limit or bifurcation point)."""

    def __init__(self, K):
        K = sp.csc_matrix(K)
        diag = np.abs(K.diagonal())
        if not np.all(np.isfinite(diag)) or np.any(diag == 0):
            raise SingularBeamError("singular stiffness: a DOF has no stiffness at all (a "
                                    "node without elements, or a mechanism)")
        self.scale = 1.0 / np.sqrt(diag)
        S = sp.diags(self.scale)
        try:
            self.lu = spla.splu((S @ K @ S).tocsc())
        except RuntimeError as exc:
            raise SingularBeamError(f"singular stiffness: {exc}") from None
        d = self.lu.U.diagonal()
        if not np.isfinite(d).all() or np.abs(d).min() <= 1e-13:
            raise SingularBeamError(f"singular stiffness (scaled pivot {np.abs(d).min():.1e}): "
                                    "a mechanism; the supports or links leave a motion free")
        self.d = d

    @property
    def sign(self) -> int:
        parity = _parity(self.lu.perm_r) ^ _parity(self.lu.perm_c)
        return int(np.prod(np.sign(self.d))) * (-1 if parity else 1)

    def solve(self, b):
        b = np.asarray(b, dtype=float)
        scale = self.scale if b.ndim == 1 else self.scale[:, None]
        return scale * self.lu.solve(scale * b)


def _parity(perm) -> int:
    """0 for an even permutation, 1 for an odd one."""
    seen = np.zeros(len(perm), dtype=bool)
    cycles = 0
    for start in range(len(perm)):
        if not seen[start]:
            cycles += 1
            j = start
            while not seen[j]:
                seen[j] = True
                j = perm[j]
    return (len(perm) - cycles) % 2


def solve(K, b):
    """Solve K x = b (see Factor)."""
    return Factor(K).solve(b)
