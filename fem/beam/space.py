"""The reduced space of unknowns: supports and rigid links eliminated.

Rigid links are exact rigid-body constraints (master-slave elimination), not stiff beams: a
stiff beam 10^4-10^6 times stiffer than the flexures would raise the condition number of K
by as much and spoil the Newton convergence test of the flexible part, while elimination
keeps the system as well conditioned as the flexures alone and is exact at large rotations:
x_s = x_m + R(theta_m) (X_s - X_m), theta_s = theta_m.

The link Jacobian dq/d(z, p) is stored per DOF rather than as a sparse matrix: every DOF is
a combination of at most two independent DOFs (its own; or its master's translation and
rotation), ``col`` (n_dofs, 2) their indices (free unknowns z first, then the held values p;
-1: none) and ``weights(q)`` (n_dofs, 2) the coefficients at a state.
"""
import numpy as np
import scipy.sparse as sp

from .model import BeamModel
from .supports import NodeFixed, NodePrescribed, dof_index
from .pattern import Condensed, block_dofs, global_matrix, shared


def held_values(model, supports, kinds=(NodeFixed, NodePrescribed)) -> np.ndarray:
    """(n_dofs,) prescribed value of each held DOF (m, rad), NaN where free, of a planar or a
    spatial beam model; ``kinds``: the support classes of that model."""
    values = np.full(model.n_dofs, np.nan)
    per_node = model.n_dofs // model.n_nodes
    for sup in supports:
        if not isinstance(sup, kinds):
            raise ValueError(f"supports: {sup!r} is not a NodeFixed or NodePrescribed")
        for node, dof, value in sup.prescribed(per_node):
            if not 0 <= node < model.n_nodes:
                raise ValueError(f"supports: node {node} outside 0..{model.n_nodes - 1}")
            if model.master_of[node] >= 0:
                raise ValueError(f"supports: node {node} is a rigid-link slave; "
                                 f"support its master {model.master_of[node]}")
            values[per_node * node + dof] = value
    return values


def independent_dofs(model, supports) -> tuple:
    """(slave nodes, their masters, the arms X_s - X_m (m), the held DOFs, their values (m,
    rad), the free DOFs) of a planar or spatial ``model`` under ``supports``: the unknowns
    are the DOFs of independent (non-slave) nodes that are not held. ValueError if none."""
    per_node = model.n_dofs // model.n_nodes
    values = held_values(model, supports)
    slaves = np.flatnonzero(model.master_of >= 0)
    masters = model.master_of[slaves]
    held = np.flatnonzero(~np.isnan(values))
    dependent = np.zeros(model.n_dofs, dtype=bool)
    dependent[(per_node * slaves[:, None] + np.arange(per_node)).ravel()] = True
    dependent[held] = True
    free = np.flatnonzero(~dependent)
    if len(free) == 0:
        raise ValueError("supports: every DOF is held; nothing to solve")
    return slaves, masters, model.nodes[slaves] - model.nodes[masters], held, values[held], free


class Space:
    """Unknowns z: the DOFs of independent (non-slave) nodes that are not prescribed.

    q(z, lam): full (n_nodes, 3) DOFs; prescribed DOFs = lam * value; slave nodes follow
    their master rigidly. weights(q): the link Jacobian's coefficients at q; reduce(v, w) =
    (T^T v, T_p^T v) and expand(z, p, w) = T z + T_p p with T = dq/dz, T_p = dq/dp."""

    FLOOR = (1e-12, 1e-6)  # the stepper's round-off: correction / |z|, residual / reference

    def __init__(self, model: BeamModel, supports):
        self.model = model
        n = model.n_dofs
        (self.slaves, self.masters, self.arm, self.held, self.p_hat,
         self.free) = independent_dofs(model, supports)
        slave_dofs = (3 * self.slaves[:, None] + np.arange(3)).ravel()
        self.n = len(self.free)
        index = -np.ones(n, dtype=np.int64)
        index[self.free] = np.arange(self.n)
        index[self.held] = self.n + np.arange(len(self.held))
        self.col = np.full((n, 2), -1, dtype=np.int64)
        self.col[:, 0] = index
        sd, md = 3 * self.slaves, 3 * self.masters
        self.col[slave_dofs, 0] = index[(md[:, None] + np.arange(3)).ravel()]
        self.col[sd, 1] = self.col[sd + 1, 1] = index[md + 2]
        self._base = (self.col >= 0).astype(float)
        self._base[:, 1] = 0.0
        self._stiffness, self._tangents = None, 0

    def control_index(self, control) -> int:
        """The free unknown of ``control`` = (node, dof, value); ValueError if held."""
        node, dof, _ = control
        where = np.flatnonzero(self.free == 3 * int(node) + dof_index(dof))
        if not len(where):
            raise ValueError(f"control = {control!r}: the DOF is held or on a rigid-link "
                             "slave; control a free DOF")
        return int(where[0])

    def start(self) -> np.ndarray:
        """The undeformed unknowns z = 0, where a solve starts."""
        return np.zeros(self.n)

    @staticmethod
    def advance(z, dz, dlam):
        """The unknowns after the correction dz (the load factor's dlam moves q, not z)."""
        return z + dz

    @staticmethod
    def size(z) -> float:
        return np.linalg.norm(z)

    @staticmethod
    def value(z, k: int) -> float:
        return z[k]

    def weights(self, q) -> np.ndarray:
        """(n_dofs, 2) coefficients of the DOFs in their unknowns at state q (n_nodes, 3)."""
        w = self._base.copy()
        if len(self.slaves):
            th = q[self.masters, 2]
            c, s = np.cos(th), np.sin(th)
            ax, ay = self.arm[:, 0], self.arm[:, 1]
            w[3 * self.slaves, 1] = -s * ax - c * ay
            w[3 * self.slaves + 1, 1] = c * ax - s * ay
        return w

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

    def reduce(self, v, w) -> tuple:
        """(T^T v (n,), T_p^T v (n_held,)) of a full vector v (n_dofs,) at weights w."""
        ok = self.col >= 0
        g = np.bincount(self.col[ok], weights=(w * np.asarray(v)[:, None])[ok],
                        minlength=self.n + len(self.held))
        return g[:self.n], g[self.n:]

    def expand(self, z, p, w) -> np.ndarray:
        """T z + T_p p (n_dofs,) or (n_dofs, k) for z (n,) or (n, k) and held values p."""
        held = np.broadcast_to(p.reshape(-1, *([1] * (z.ndim - 1))), (len(p),) + z.shape[1:])
        x = np.concatenate([z, held, np.zeros((1,) + z.shape[1:])])  # col -1: the zero row
        shape = (-1,) + (1,) * (z.ndim - 1)
        # the two terms added as a sum over them would (that sum is ~4x slower)
        return (w[:, 0].reshape(shape) * x[self.col[:, 0]]
                + w[:, 1].reshape(shape) * x[self.col[:, 1]])

    def rows(self, node: int, w) -> np.ndarray:
        """(3, n) dense rows of T for ``node``'s DOFs (d(node DOFs)/dz)."""
        out = np.zeros((3, self.n))
        for r in range(3):
            for k in range(2):
                c = self.col[3 * node + r, k]
                if 0 <= c < self.n:
                    out[r, c] += w[3 * node + r, k]
        return out

    def constraint_diagonal(self, q, r_full) -> np.ndarray:
        """Second-order term sum_s r_s . d^2 x_s / d theta_m^2 on the masters' theta DOFs
        (the diagonal of the links' contribution to the tangent, full (n_dofs,): nonzero on
        free DOFs only, a held one has no row in the reduced tangent)."""
        diag = np.zeros(self.model.n_dofs)
        if len(self.slaves):
            th = q[self.masters, 2]
            c, s = np.cos(th), np.sin(th)
            ax, ay = self.arm[:, 0], self.arm[:, 1]
            rs = r_full.reshape(-1, 3)[self.slaves]
            term = rs[:, 0] * (-c * ax + s * ay) + rs[:, 1] * (-s * ax - c * ay)
            np.add.at(diag, 3 * self.masters + 2, term)
            diag[self.held] = 0.0
        return diag

    def jacobian(self, w) -> sp.csr_matrix:
        """T = dq/dz (n_dofs, n) at link weights w."""
        ok = (self.col >= 0) & (self.col < self.n)
        indptr = np.concatenate([[0], np.cumsum(ok.sum(axis=1))])
        return sp.csr_matrix((w[ok], self.col[ok], indptr), shape=(self.model.n_dofs, self.n))

    def condense_global(self, K_full, w) -> sp.csc_matrix:
        """T^T K T (CSC) of a global matrix (n_dofs, n_dofs) at link weights w."""
        T = self.jacobian(w)
        return (T.T @ K_full @ T).tocsc()

    def condense(self, ke, w, diagonal=None) -> sp.csc_matrix:
        """T^T K T (CSC) of the element matrices ``ke`` (n_e, 6, 6) plus the full diagonal
        ``diagonal`` (n_dofs,) at link weights w: by sparse products the first time (a
        linear solve), by the elements' fixed pattern (Condensed) from the second on
        (Newton iterations, where its one-off setup, ~2x the products', pays)."""
        self._tangents += 1
        if self._tangents == 1:
            return self.condense_global(global_matrix(self.model, ke, diagonal), w)
        d = np.zeros(self.n) if diagonal is None else diagonal[self.free]
        return self.condensed().matrix(ke, w, d)

    def condensed(self, blocks=None) -> Condensed:
        """The reduced matrix's fixed pattern (Condensed) of this Space's elements (or of
        ``blocks``, (m, 2) node pairs), shared between the models of one topology and held
        DOFs (a sweep's designs)."""
        if blocks is None:
            if self._stiffness is None:
                self._stiffness = self.condensed(self.model.connectivity)
            return self._stiffness
        key = ("condensed", self.n, self.col.tobytes(), blocks.tobytes())
        return shared(key, lambda: Condensed(self.col, self.n, block_dofs(blocks)))
