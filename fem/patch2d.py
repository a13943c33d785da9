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
the static modes (exact for the rigid motions, good far below the patch's own modes).
"""
from dataclasses import dataclass
import functools

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

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


def cell_edges(breaks, size: float) -> np.ndarray:
    """Cell edges (m) splitting each interval of the sorted ``breaks`` into equal cells of
    at most ``size``."""
    breaks = np.asarray(breaks, dtype=float)
    out = [breaks[:1]]
    for a, b in zip(breaks[:-1], breaks[1:]):
        n = max(1, int(np.ceil((b - a) / size - 1e-9)))
        out.append(np.linspace(a, b, n + 1)[1:])
    return np.concatenate(out)


@dataclass(frozen=True)
class Joint:
    """A beam node's coupling to the patch: constraint rows on the patch's DOFs (dict
    DOF -> coefficient, one per row) and on the node's own (3,) DOFs (x, y, theta)."""

    rows: tuple
    node_rows: np.ndarray


class TensorPatch:
    """Q2 cells on the tensor grid of cell edges ``xs``, ``ys`` (m), those whose centres
    ``keep(x, y)`` accepts (arrays in, a boolean array out; default all); Poisson's ratio
    ``nu``. ``K``, ``M``: the patch's
    stiffness and mass per unit E, width and density (CSC, DOFs (u, v) node by node);
    ``xy`` the nodes (m)."""

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
        self.cells = cells.reshape(grid.shape)
        self.xy = np.column_stack([X[used % len(X)], Y[used // len(X)]])
        self.n = 2 * len(self.xy)
        hx, hy = (xs[cx + 1] - xs[cx])[:, None, None], (ys[cy + 1] - ys[cy])[:, None, None]
        A, B, C, M = _reference(float(nu))
        dofs = (2 * self.cells[:, :, None] + np.arange(2)).reshape(len(cx), 18)
        rows = np.broadcast_to(dofs[:, :, None], (len(cx), 18, 18)).ravel()
        cols = np.broadcast_to(dofs[:, None, :], (len(cx), 18, 18)).ravel()
        matrix = lambda e: sp.csc_matrix((e.ravel(), (rows, cols)), shape=(self.n, self.n))
        self.K = matrix(hy / hx * A + hx / hy * B + C)
        self.M = matrix(hx * hy / 4 * M)

    def boundary(self, p0, p1) -> tuple:
        """(nodes, s) on the straight segment p0 -> p1 (an axis-aligned cell boundary), in
        order, s their distance from its middle (m)."""
        p0, p1 = np.asarray(p0, float), np.asarray(p1, float)
        length = float(np.linalg.norm(p1 - p0))
        t = (p1 - p0) / length
        r = self.xy - (p0 + p1) / 2
        s, off = r @ t, r @ np.array([-t[1], t[0]])
        tol = 1e-9 * length
        on = np.flatnonzero((np.abs(off) < tol) & (np.abs(s) <= length / 2 + tol))
        on = on[np.argsort(s[on])]
        if len(on) < 3 or len(on) % 2 == 0:
            raise ValueError(f"patch: the segment {p0.tolist()} -> {p1.tolist()} is not a "
                             "boundary of whole cells")
        return on, s[on]

    def condensed(self, joints) -> tuple:
        """(K, M) on the joints' DOFs (3 a joint, (x, y, theta), in order), per unit E, width
        and density: the static modes of each joint DOF, the others held."""
        Cu, Cg = _constraints(self, joints)
        S = sp.bmat([[self.K, Cu.T], [Cu, None]], format="csc")
        rhs = np.vstack([np.zeros((self.n, Cg.shape[1])), -Cg])
        # the saddle matrix's pattern is symmetric: a symmetric ordering halves the fill
        solution = spla.splu(S, permc_spec="MMD_AT_PLUS_A").solve(rhs)
        U, lam = solution[:self.n], solution[self.n:]
        K, M = Cg.T @ lam, U.T @ (self.M @ U)
        return (K + K.T) / 2, (M + M.T) / 2


def _constraints(patch: TensorPatch, joints) -> tuple:
    """(Cu (m, n) sparse, Cg (m, 3 k)): the joints' rows Cu u + Cg g = 0."""
    data, rows, cols, G = [], [], [], []
    for j, joint in enumerate(joints):
        for coeffs, g in joint(patch):
            for dof, c in coeffs.items():
                rows.append(len(G))
                cols.append(dof)
                data.append(c)
            row = np.zeros(3 * len(joints))
            row[3 * j:3 * j + 3] = g
            G.append(row)
    Cu = sp.csc_matrix((data, (rows, cols)), shape=(len(G), patch.n))
    return Cu, np.array(G)


def _weights(s, f) -> np.ndarray:
    """W_i = int f(s) N_i(s) ds over the quadratic edges through the points s (sorted, an
    odd count: each edge's ends and middle)."""
    t, w = _GAUSS
    W = np.zeros(len(s))
    for k in range(0, len(s) - 2, 2):
        a, b = s[k], s[k + 2]
        x = (a + b) / 2 + t * (b - a) / 2
        W[k:k + 3] += _shape(t) @ (w * (b - a) / 2 * f(x))
    return W


def _frame(p0, p1) -> tuple:
    """(length, tangent t, its normal z x t, middle) of the segment p0 -> p1."""
    p0, p1 = np.asarray(p0, float), np.asarray(p1, float)
    length = float(np.linalg.norm(p1 - p0))
    t = (p1 - p0) / length
    return length, t, np.array([-t[1], t[0]]), (p0 + p1) / 2


def _mean(nodes, W, d) -> dict:
    """Row of sum_i W_i u_i . d (d a direction) on the patch's DOFs."""
    return {**{2 * int(i): w * d[0] for i, w in zip(nodes, W)},
            **{2 * int(i) + 1: w * d[1] for i, w in zip(nodes, W)}}


def section(p0, p1):
    """A joint: the beam section across the segment p0 -> p1 (m), its node at the middle
    and its axis along the segment's normal n = z x t (the module's text). A rigid rotation
    theta moves the point s t by theta s n."""
    def rows(patch):
        a, t, n, _ = _frame(p0, p1)
        nodes, s = patch.boundary(p0, p1)
        shear = _weights(s, lambda x: 1.5 / a * (1 - 4 * x ** 2 / a ** 2))
        mean = _weights(s, lambda x: np.full_like(x, 1.0 / a))
        moment = _weights(s, lambda x: 12.0 * x / a ** 3)
        return [(_mean(nodes, shear, t), -np.array([t[0], t[1], 0.0])),
                (_mean(nodes, mean, n), -np.array([n[0], n[1], 0.0])),
                (_mean(nodes, moment, n), -np.array([0.0, 0.0, 1.0]))]
    return rows


def held_face(p0, p1):
    """A joint: the face p0 -> p1 (m) held along its normal n = z x t by a rigid body, its
    node at the middle (the module's text)."""
    def rows(patch):
        a, t, n, _ = _frame(p0, p1)
        nodes, s = patch.boundary(p0, p1)
        # each point's normal motion is the body's there: u . n = u_node . n + theta s
        held = [({2 * int(i): n[0], 2 * int(i) + 1: n[1]}, -np.array([n[0], n[1], si]))
                for i, si in zip(nodes, s)]
        mean = _weights(s, lambda x: np.full_like(x, 1.0 / a))
        return held + [(_mean(nodes, mean, t), -np.array([t[0], t[1], 0.0]))]
    return rows
