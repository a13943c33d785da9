"""Plane-stress patches condensed onto beam nodes: a part too deep for a beam (a member as
deep as it is long, borne by a pad on part of one face) as a 2-D continuum, reduced to the
DOFs (x, y, theta) of the beam nodes it joins (:class:`flexfem.fem.beam.Superelement`).

    patch = TensorPatch(xs, ys, nu, keep=lambda x, y: ...)  # Q2 cells on a tensor grid
    K, M = patch.condensed([section((x0, y1), (x1, y1)),    # joint 0: a beam goes on there
                            held_face((x0, y0), (x0, y2))])  # joint 1: a rigid end cap
    # K, M (3 x 3 joints): per unit Young's modulus, out-of-plane width and density

Elements: 9-node Lagrange quadrilaterals (Q2, 3 x 3 Gauss points) on axis-aligned
rectangles, whose matrices are three reference matrices scaled by each cell's aspect ratio, so
a patch of a few hundred cells assembles in about a millisecond.

Joints (the beam nodes, each at the middle of its segment of the patch's boundary):

- :func:`section`: where the part goes on as a beam. The beam's section forces act on the
  cut as the tractions of beam theory: N uniform, M linear, V parabolic (Timoshenko's
  kappa = 5/6). The node's motion is their work-conjugate: its axial motion and rotation the
  mean and the first moment of the normal displacement over the section, its transverse motion
  the mean of the tangential displacement weighted by the parabolic shear. A prismatic strip
  condenses to the Timoshenko beam (the plane-stress solution with those tractions is the
  beam's: tests/fem/test_patch2d.py), and the cut adds no stiffness of its own, so
  where it is placed beyond the part's deep region does not matter.
- :func:`held_face`: a face held by a rigid body along its normal (an actuator's end cap): each
  point's normal motion follows the node rigidly; the tangential motion is free, and its mean
  is the node's.

Condensation: the static mode of each joint DOF (the others held, Lagrange multipliers) gives
the stiffness as the multipliers' work; the mass is Guyan's, the patch's consistent mass on
the static modes (exact for the rigid motions, good far below the patch's own modes). The
multipliers come from the patch's flexibility, held statically determinate: its K is then
positive definite with a narrow band (nodes row by row), which LAPACK's banded Cholesky
factors (the DBMA's member patch: ~1.5 ms, about half the cost of a sparse LU of its saddle
system). The band is narrow where the patch is short along x (the DBMA's members: 17 nodes a
row); the patch must be one connected piece.
"""
import functools

import numpy as np
import scipy.sparse as sp
from scipy.linalg import block_diag, lapack

_GAUSS = (np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)]), np.array([5.0, 8.0, 5.0]) / 9.0)


def _shape(t):
    """1-D quadratic Lagrange functions at t in [-1, 1] (nodes -1, 0, 1), (3, ...)."""
    return np.array([t * (t - 1) / 2, 1 - t * t, t * (t + 1) / 2])


def _shape_dt(t):
    return np.array([t - 0.5, -2 * t, t + 0.5])


@functools.lru_cache(maxsize=8)
def _reference(nu: float) -> tuple:
    """(A, B, C, M) 18 x 18 (DOFs (u, v) node by node, nodes row by row along x): a cell of
    width hx and height hy has stiffness (hy / hx) A + (hx / hy) B + C (plane stress, E = 1,
    unit width) and mass hx hy / 4 M (unit density)."""
    D = np.array([[1, nu, 0], [nu, 1, 0], [0, 0, (1 - nu) / 2]]) / (1 - nu ** 2)
    A, B, C, M = (np.zeros((18, 18)) for _ in range(4))
    t, w = _GAUSS
    for xi, wx in zip(t, w):
        for eta, wy in zip(t, w):
            N = np.outer(_shape(eta), _shape(xi)).ravel()
            Nx = np.outer(_shape(eta), _shape_dt(xi)).ravel()
            Ny = np.outer(_shape_dt(eta), _shape(xi)).ravel()
            Bx, By, Nu = np.zeros((3, 18)), np.zeros((3, 18)), np.zeros((2, 18))
            Bx[0, 0::2] = Bx[2, 1::2] = Nx
            By[1, 1::2] = By[2, 0::2] = Ny
            Nu[0, 0::2] = Nu[1, 1::2] = N
            A += wx * wy * Bx.T @ D @ Bx
            B += wx * wy * By.T @ D @ By
            C += wx * wy * (Bx.T @ D @ By + By.T @ D @ Bx)
            M += wx * wy * Nu.T @ Nu
    return A, B, C, M


def cell_edges(breaks, size: float, refine_at=(), levels: int = 0) -> np.ndarray:
    """Cell edges (m) splitting each interval of the sorted ``breaks`` into cells of at most
    ``size``, graded towards the points ``refine_at`` (re-entrant corners, where the stress
    is singular): cells of size / 2^levels next to them, doubling outwards."""
    breaks = np.asarray(breaks, dtype=float)
    out = [breaks[:1]]
    for a, b in zip(breaks[:-1], breaks[1:]):
        points = {a, b}
        for c in refine_at:
            if a <= c <= b:
                points |= {q for k in range(1, levels + 1)
                           for q in (c - size / 2 ** k, c + size / 2 ** k) if a < q < b}
        points = sorted(points)
        for p, q in zip(points[:-1], points[1:]):
            n = max(1, int(np.ceil((q - p) / size - 1e-9)))
            out.append(np.linspace(p, q, n + 1)[1:])
    return np.concatenate(out)


class TensorPatch:
    """Q2 cells on the tensor grid of cell edges ``xs``, ``ys`` (m), those whose centres
    ``keep(x, y)`` accepts (arrays in, a boolean array out; default all); Poisson's ratio
    ``nu``. ``K``: the patch's stiffness per unit E and width; ``xy`` the nodes (m)."""

    def __init__(self, xs, ys, nu: float, keep=None):
        xs, ys = np.asarray(xs, float), np.asarray(ys, float)
        cx, cy = np.meshgrid(np.arange(len(xs) - 1), np.arange(len(ys) - 1))
        cx, cy = cx.ravel(), cy.ravel()
        if keep is not None:
            inside = np.asarray(keep((xs[cx] + xs[cx + 1]) / 2, (ys[cy] + ys[cy + 1]) / 2))
            cx, cy = cx[inside], cy[inside]
        X = np.sort(np.concatenate([xs, (xs[:-1] + xs[1:]) / 2]))
        Y = np.sort(np.concatenate([ys, (ys[:-1] + ys[1:]) / 2]))
        a, b = np.meshgrid(np.arange(3), np.arange(3))
        grid = (2 * cy[:, None] + b.ravel()) * len(X) + 2 * cx[:, None] + a.ravel()
        used, cells = np.unique(grid, return_inverse=True)
        self.xy = np.column_stack([X[used % len(X)], Y[used // len(X)]])
        self.n = 2 * len(self.xy)
        self.dofs = (2 * cells.reshape(grid.shape)[:, :, None] + np.arange(2)).reshape(-1, 18)
        self.hx, self.hy = xs[cx + 1] - xs[cx], ys[cy + 1] - ys[cy]
        A, B, C, self._mass = _reference(float(nu))
        Ke = (self.hy / self.hx)[:, None, None] * A + (self.hx / self.hy)[:, None, None] * B + C
        rows = np.broadcast_to(self.dofs[:, :, None], Ke.shape).ravel()
        cols = np.broadcast_to(self.dofs[:, None, :], Ke.shape).ravel()
        self._entries = (rows, cols, Ke.ravel())

    @property
    def K(self) -> sp.csc_matrix:
        """The stiffness per unit E and width (CSC, DOFs (u, v) node by node)."""
        rows, cols, values = self._entries
        return sp.csc_matrix((values, (rows, cols)), shape=(self.n, self.n))

    def mass_of(self, U) -> np.ndarray:
        """U^T M U (k, k) for displacement fields U (n, k): the consistent mass per unit
        width and density, cell by cell."""
        Ue = U[self.dofs]  # (cells, 18, k)
        MU = (self.hx * self.hy / 4)[:, None, None] * (self._mass @ Ue)
        return Ue.reshape(-1, U.shape[1]).T @ MU.reshape(-1, U.shape[1])

    def boundary(self, p0, p1) -> tuple:
        """(nodes, s) on the straight segment p0 -> p1 (an axis-aligned cell boundary), in
        order, s their distance from its middle (m)."""
        length, t, n, middle = _frame(p0, p1)
        r = self.xy - middle
        s, off = r @ t, r @ n
        tol = 1e-9 * length
        on = np.flatnonzero((np.abs(off) < tol) & (np.abs(s) <= length / 2 + tol))
        on = on[np.argsort(s[on])]
        if len(on) < 3 or len(on) % 2 == 0:
            raise ValueError(f"patch: the segment {list(p0)} -> {list(p1)} is not a boundary "
                             "of whole cells")
        return on, s[on]

    def condensed(self, joints) -> tuple:
        """(K, M) on the joints' DOFs (3 a joint, (x, y, theta), in order), per unit E, width
        and density: the static modes of each joint DOF, the others held (constraint rows
        Cu u + Cg g = 0, Lagrange multipliers lam: K = Cg^T lam).

        The multipliers come from the patch's flexibility: held statically determinate, the
        patch's K is positive definite and a narrow band (nodes row by row), K = U^T U with
        U its banded Cholesky factor. The joints' tractions are self-equilibrated, so
        u = -K^-1 Cu^T lam + R alpha with R the rigid motions: with W = U^-T Cu^T,
        [[-W^T W, Cu R], [(Cu R)^T, 0]] [lam; alpha] = [-Cg; 0] is a small dense system
        (joint rows + 3), and u = R alpha - U^-1 W lam."""
        rows = [joint(self) for joint in joints]
        Cu = np.vstack([C for C, _ in rows])
        Cg = block_diag(*[G for _, G in rows])
        factor, held = self._held_factor()
        Ct = np.array(Cu.T, order="F")
        Ct[held] = 0.0  # the holds carry no load: self-equilibrated forces have no reactions
        W = lapack.dtbtrs(factor, Ct, trans="T", overwrite_b=True)[0]
        R = self.rigid_motions()
        CR = Cu @ R
        small = np.block([[-W.T @ W, CR], [CR.T, np.zeros((3, 3))]])
        rhs = np.vstack([-Cg, np.zeros((3, Cg.shape[1]))])
        solution = np.linalg.solve(small, rhs)
        lam, alpha = solution[:len(Cu)], solution[len(Cu):]
        U = R @ alpha - lapack.dtbtrs(factor, np.asfortranarray(W @ lam), overwrite_b=True)[0]
        K, M = Cg.T @ lam, self.mass_of(U)
        return (K + K.T) / 2, (M + M.T) / 2

    def rigid_motions(self) -> np.ndarray:
        """(n, 3): the patch moved along x, along y, and turned about the origin (per rad)."""
        R = np.zeros((self.n, 3))
        R[0::2, 0] = R[1::2, 1] = 1.0
        R[0::2, 2], R[1::2, 2] = -self.xy[:, 1], self.xy[:, 0]
        return R

    def _held_factor(self) -> tuple:
        """(U, held): the upper banded Cholesky factor (LAPACK's band storage) of K with the
        patch held statically determinate at the DOFs ``held`` (its first node, and the
        farthest node across the line to it), their rows and columns the identity's."""
        d = self.xy - self.xy[0]
        far = int(np.argmax(np.hypot(*d.T)))
        held = [0, 1, 2 * far + int(abs(d[far, 0]) > abs(d[far, 1]))]
        rows, cols, values = self._entries
        upper = rows <= cols
        rows, cols = rows[upper], cols[upper]
        bw = int((cols - rows).max())
        # LAPACK's upper band storage, (bw + 1, n) in Fortran order: K_rc at [bw + r - c, c]
        band = np.bincount(cols * (bw + 1) + bw + rows - cols, values[upper],
                           (bw + 1) * self.n).reshape(self.n, bw + 1).T
        for j in held:  # their rows and columns: the identity's
            i = np.arange(1, min(bw, self.n - 1 - j) + 1)
            band[:, j] = 0.0  # column j above the diagonal
            band[bw - i, j + i] = 0.0  # row j right of it
            band[bw, j] = 1.0
        diagonal = band[bw].copy()
        factor, info = lapack.dpbtrf(band, lower=0, overwrite_ab=True)
        if info != 0 or np.min(factor[bw] ** 2 / diagonal) < 1e-10:
            raise ValueError("patch: its cells are not all connected (it must be one piece; "
                             "a part of it would move freely)")
        return factor, held


def _weights(s, f) -> np.ndarray:
    """W_i = int f(s) N_i(s) ds over the quadratic edges through the points s (sorted, an
    odd count: each edge's ends and middle)."""
    t, w = _GAUSS
    a, b = s[:-2:2, None], s[2::2, None]
    x = (a + b) / 2 + t * (b - a) / 2  # (edges, 3 Gauss points)
    local = (w * (b - a) / 2 * f(x)) @ _shape(t).T  # (edges, 3 nodes)
    W = np.zeros(len(s))
    np.add.at(W, 2 * np.arange(len(local))[:, None] + np.arange(3), local)
    return W


def _frame(p0, p1) -> tuple:
    """(length, tangent t, its normal n = z x t, middle) of the segment p0 -> p1."""
    p0, p1 = np.asarray(p0, float), np.asarray(p1, float)
    length = float(np.linalg.norm(p1 - p0))
    t = (p1 - p0) / length
    return length, t, np.array([-t[1], t[0]]), (p0 + p1) / 2


def _rows(patch, nodes, weights, directions) -> np.ndarray:
    """Constraint rows (m, patch DOFs): row r is sum_i weights[r, i] u_i . directions[r]."""
    C = np.zeros((len(weights), patch.n))
    C[:, 2 * nodes] = weights * directions[:, :1]
    C[:, 2 * nodes + 1] = weights * directions[:, 1:]
    return C


def section(p0, p1):
    """A joint: the beam section across the segment p0 -> p1 (m), its node at the middle
    and its axis along the segment's normal n = z x t (the module's text). A rigid rotation
    theta moves the point s t by theta s n."""
    def rows(patch):
        a, t, n, _ = _frame(p0, p1)
        nodes, s = patch.boundary(p0, p1)
        W = np.array([_weights(s, lambda x: 1.5 / a * (1 - 4 * x ** 2 / a ** 2)),
                      _weights(s, lambda x: np.full_like(x, 1.0 / a)),
                      _weights(s, lambda x: 12.0 * x / a ** 3)])
        G = -np.array([[t[0], t[1], 0.0], [n[0], n[1], 0.0], [0.0, 0.0, 1.0]])
        return _rows(patch, nodes, W, np.array([t, n, n])), G
    return rows


def held_face(p0, p1):
    """A joint: the face p0 -> p1 (m) held along its normal n = z x t by a rigid body, its
    node at the middle (the module's text)."""
    def rows(patch):
        a, t, n, _ = _frame(p0, p1)
        nodes, s = patch.boundary(p0, p1)
        # each point's normal motion is the body's there: u . n = u_node . n + theta s
        normal = np.tile(n, (len(nodes), 1))
        W = np.vstack([np.eye(len(nodes)), _weights(s, lambda x: np.full_like(x, 1.0 / a))])
        G = -np.vstack([np.column_stack([normal, s]), [t[0], t[1], 0.0]])
        return _rows(patch, nodes, W, np.vstack([normal, t])), G
    return rows
