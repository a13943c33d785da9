"""p-multigrid preconditioned CG for elasticity on quadratic elements, the iterative path.

Smoothed-aggregation AMG applied to the P2 matrix itself diverges on slender 3-D parts; the
field's answer is a two-level p-multigrid (P2 -> P1 on the same mesh) whose P1 level is solved
by smoothed-aggregation AMG with the rigid-body modes as near null space:

- prolongation: the P1 space's interpolation into P2 (vertex DOFs injected, edge-midpoint DOFs
  the mean of their two vertices; in general the P1 shape functions at the P2 nodes), per
  displacement component, columns of held vertex DOFs dropped;
- P2 level: Chebyshev smoothing of degree ``degree`` on the Jacobi-scaled operator (a fixed
  polynomial, so the preconditioner stays symmetric and CG valid), before and after;
- P1 level: one V-cycle of pyamg's smoothed aggregation on the Galerkin operator P^T K P (the
  P1 stiffness where the quadrature is exact), rigid-body modes of the vertices as near null
  space.

Linear elements have no P2 level: the preconditioner is the AMG V-cycle on K itself.
The stiffness is read as its upper triangle (``Model.stiffness_upper``) and never copied whole.
"""
from dataclasses import dataclass, field

import numpy as np
import pyamg
import scipy.sparse as sp
import scipy.sparse.linalg as spla
import skfem

from .factor_protocol import LinearFactor, checked_rhs
from .linsolve import Restriction, SingularSystemError
from .model import rigid_body_modes, scalar_element

# Chebyshev smoothing of D^-1 K on [LAMBDA_FRACTION lambda_max, lambda_max]: the upper part
# of the spectrum that the P1 level cannot represent (pyamg's default fraction for its
# Chebyshev smoother is 1/30)
LAMBDA_FRACTION = 1.0 / 30.0
# the power iteration's estimate of lambda_max (a lower bound) raised by this factor
LAMBDA_SAFETY = 1.1


def lagrange_interpolation(mesh: skfem.Mesh, fine: skfem.Element,
                           coarse: skfem.Element) -> sp.csr_matrix:
    """(n_fine, n_coarse) interpolation of the scalar ``coarse`` Lagrange space into the
    ``fine`` one on the same mesh: entry (i, j) is coarse shape function j at fine node i
    (dimensionless; P1 -> P2: 1 at a vertex, 1/2 at an edge's midpoint)."""
    fine_dofs = skfem.assembly.Dofs(mesh, fine).element_dofs      # (n_local_fine, n_el)
    coarse_dofs = skfem.assembly.Dofs(mesh, coarse).element_dofs  # (n_local_coarse, n_el)
    X = np.asarray(fine.doflocs, dtype=float).T                   # reference nodes (dim, n)
    weights = np.array([coarse.lbasis(X, j)[0] for j in range(coarse_dofs.shape[0])]).T
    a, b = np.nonzero(np.abs(weights) > 1e-12)
    rows = fine_dofs[a].ravel()
    cols = coarse_dofs[b].ravel()
    values = np.repeat(weights[a, b], fine_dofs.shape[1])
    n_fine, n_coarse = int(fine_dofs.max()) + 1, int(coarse_dofs.max()) + 1
    keys, first = np.unique(rows.astype(np.int64) * n_coarse + cols, return_index=True)
    return sp.csr_matrix((values[first], (keys // n_coarse, keys % n_coarse)),
                         shape=(n_fine, n_coarse))


def vector_prolongation(model) -> tuple[sp.csr_matrix, np.ndarray]:
    """(P, points): the model's P1 vector space interpolated into its own (n_dofs x
    dim n_vertices; DOFs interleaved by node as skfem numbers them) and the P1 nodes'
    coordinates (dim, n_vertices) (m). For a linear model P is the identity."""
    mesh = model.mesh.mesh
    fine = scalar_element(mesh, model.order)
    coarse = scalar_element(mesh, 1)
    scalar = lagrange_interpolation(mesh, fine, coarse)
    P = sp.kron(scalar, sp.identity(model.dim), format="csr")
    if P.shape[0] != model.n_dofs:
        raise ValueError(f"the prolongation has {P.shape[0]} rows, the model {model.n_dofs} DOFs")
    return P, mesh.p


def _chebyshev(apply_A, inverse_diagonal, r, x, lam_min, lam_max, degree):
    """``degree`` Chebyshev steps for A x = r preconditioned by D^-1 from ``x`` (Saad,
    Iterative Methods, 2nd ed., Algorithm 12.1); x updated and returned."""
    theta, delta = 0.5 * (lam_max + lam_min), 0.5 * (lam_max - lam_min)
    sigma = theta / delta
    rho = 1.0 / sigma
    residual = r - apply_A(x) if x is not None else r.copy()
    x = np.zeros_like(r) if x is None else x
    step = inverse_diagonal * residual / theta
    for k in range(degree):
        x += step
        if k == degree - 1:
            break
        residual -= apply_A(step)
        rho_next = 1.0 / (2.0 * sigma - rho)
        step = rho_next * rho * step + 2.0 * rho_next / delta * (inverse_diagonal * residual)
        rho = rho_next
    return x


def largest_eigenvalue(apply_A, inverse_diagonal, n, steps=20, seed=0) -> float:
    """An estimate of the largest eigenvalue of D^-1 A (power iteration, ``steps``; a lower
    bound, which :data:`LAMBDA_SAFETY` raises)."""
    v = np.random.default_rng(seed).standard_normal(n)
    lam = 0.0
    for _ in range(steps):
        w = inverse_diagonal * apply_A(v)
        lam = float(np.linalg.norm(w) / np.linalg.norm(v))
        v = w / np.linalg.norm(w)
    return lam


class UpperRestriction(Restriction):
    """K[I][:, I] of a symmetric K kept as its upper triangle, as an operator: the
    :class:`~flexfem.fem.restriction.Restriction` with K's diagonal read once, not at every
    product (a CG iteration makes several)."""

    def __init__(self, K, I: np.ndarray):
        super().__init__(K, I, upper=True)
        self.full_diagonal = K.diagonal()

    def _product(self, full):
        d = self.full_diagonal if full.ndim == 1 else self.full_diagonal[:, None]
        return self.A @ full + self.A.T @ full - d * full

    def diagonal(self) -> np.ndarray:
        return self.full_diagonal[self.I]


@dataclass
class PMultigrid:
    """The two-level preconditioner of the free-DOF stiffness K_II of ``model``: ``K`` the
    upper triangle (CSR, N/m) of the stiffness on all the model's DOFs or on the free DOFs
    ``I`` (sorted) alone; ``M(r)`` approximates K_II^-1 r. ``degree``: Chebyshev steps per
    smoothing on the P2 level."""

    model: object
    K: sp.csr_matrix
    I: np.ndarray
    degree: int = 2
    stats: dict = field(default_factory=dict)

    def __post_init__(self):
        n = self.model.n_dofs
        P, points = vector_prolongation(self.model)
        free = np.zeros(n, dtype=bool)
        free[self.I] = True
        # coarse DOFs whose own P2 node is held are dropped (a P1 vertex is a P2 node)
        keep = free[np.asarray(P.argmax(axis=0)).ravel()]
        P = P[:, np.flatnonzero(keep)]
        if self.K.shape[0] == n:  # K on all DOFs: held rows of P zeroed
            P_K, local = (sp.diags(free.astype(float)) @ P).tocsr(), self.I
        elif self.K.shape[0] == len(self.I):  # K on the free DOFs already
            P_K, local = P[self.I].tocsr(), np.arange(len(self.I))
        else:
            raise ValueError(f"K of shape {self.K.shape} is neither on the model's {n} DOFs "
                             f"nor on the {len(self.I)} free ones")
        P_K.eliminate_zeros()
        self.operator = UpperRestriction(self.K, local)
        self.P = P_K[local].tocsr()
        self.PT = self.P.T.tocsr()
        # Galerkin coarse operator P^T (U + U^T - D) P from the upper triangle U
        B = (P_K.T @ (self.K @ P_K)).tocsr()
        coarse = (B + B.T - P_K.T @ sp.diags(self.K.diagonal()) @ P_K).tocsr()
        coarse.eliminate_zeros()
        dim = self.model.dim
        modes = rigid_body_modes(points)  # (n_modes, n_vertices, dim)
        near_null = modes.reshape(len(modes), -1).T[np.flatnonzero(keep)]
        self.amg = pyamg.smoothed_aggregation_solver(
            coarse, B=near_null, symmetry="symmetric", max_coarse=1000, coarse_solver="splu",
            strength=("symmetric", {"theta": 0.0}), smooth=("jacobi", {"omega": 4.0 / 3.0}))
        self.coarse_cycle = self.amg.aspreconditioner(cycle="V")
        self.two_level = self.model.order > 1
        if self.two_level:
            self.inverse_diagonal = 1.0 / self.operator.diagonal()
            lam = LAMBDA_SAFETY * largest_eigenvalue(self.operator.matvec,
                                                     self.inverse_diagonal, len(self.I))
            self.lam_max, self.lam_min = lam, LAMBDA_FRACTION * lam
        self.stats.update(fine_unknowns=len(self.I), coarse_unknowns=coarse.shape[0],
                          amg_levels=len(self.amg.levels), dim=dim)

    def __call__(self, r: np.ndarray) -> np.ndarray:
        r = np.ravel(r)
        if not self.two_level:
            return self.coarse_cycle @ r
        A = self.operator.matvec
        x = _chebyshev(A, self.inverse_diagonal, r, None, self.lam_min, self.lam_max,
                       self.degree)
        x += self.P @ (self.coarse_cycle @ (self.PT @ (r - A(x))))
        return _chebyshev(A, self.inverse_diagonal, r, x, self.lam_min, self.lam_max,
                          self.degree)

    def as_operator(self) -> spla.LinearOperator:
        n = len(self.I)
        return spla.LinearOperator((n, n), matvec=self, dtype=float)


def preconditioned_cg(preconditioner: PMultigrid, b: np.ndarray, rtol: float = 1e-9,
                      maxiter: int = 1000) -> tuple[np.ndarray, dict]:
    """CG on ``preconditioner``'s K_II with it as the preconditioner, to the relative
    residual ``rtol``: (x, info: iterations, relative residual, levels). Raises
    :class:`SingularSystemError` where it does not converge in ``maxiter``."""
    iterations = [0]

    def count(_):
        iterations[0] += 1

    x, status = spla.cg(preconditioner.operator, b, rtol=rtol, atol=0.0, maxiter=maxiter,
                        M=preconditioner.as_operator(), callback=count)
    relative = float(np.linalg.norm(b - preconditioner.operator @ x)
                     / max(np.linalg.norm(b), 1e-300))
    info = dict(preconditioner.stats, iterations=iterations[0], relative_residual=relative)
    if status != 0 or not np.all(np.isfinite(x)):
        raise SingularSystemError(
            f"p-multigrid CG did not converge (relative residual {relative:.1e} after "
            f"{iterations[0]} iterations); try solver='direct'")
    return x, info


def solve_pmg(model, K, I: np.ndarray, b: np.ndarray, rtol: float = 1e-9,
              maxiter: int = 1000) -> tuple[np.ndarray, dict]:
    """Solve K_II x = b (``K`` as :class:`PMultigrid` reads it; ``b`` in N) by CG
    preconditioned with :class:`PMultigrid` to the relative residual ``rtol``: (x (m), info)
    of :func:`preconditioned_cg`."""
    return preconditioned_cg(PMultigrid(model, K, I), b, rtol, maxiter)


class PMultigridFactor(LinearFactor):
    """p-multigrid CG as a factor of the protocol (fem/factor.py's backend 'pmg-cg'):
    ``A`` the SPD stiffness on the free DOFs ``free`` (sorted) of ``model`` (whole or its upper
    triangle), set up once, one CG solve per column to the relative residual ``tol``. It needs
    the model (the mesh carries the P1 level): ``needs_model``."""

    backend = "pmg-cg"
    needs_model = True

    def __init__(self, A, kind: str = "spd", model=None, free=None, tol: float = 1e-9,
                 maxiter: int = 1000):
        if kind != "spd":
            raise ValueError(f"p-multigrid CG solves SPD systems, not kind = {kind!r}")
        if model is None or free is None:
            raise ValueError("backend 'pmg-cg' needs model= (the Model) and free= (the DOFs "
                             "of A's unknowns, sorted)")
        self.n, self.tol, self.maxiter = A.shape[0], tol, maxiter
        self.preconditioner = PMultigrid(model, sp.triu(A, format="csr"), np.asarray(free))
        self.info = {}

    def solve(self, b) -> np.ndarray:
        b = checked_rhs(b, self.n)
        if b.ndim == 2:
            return np.column_stack([self.solve(c) for c in b.T]).reshape(b.shape)
        x, self.info = preconditioned_cg(self.preconditioner, b, self.tol, self.maxiter)
        return x

    def free(self) -> None:
        self.preconditioner = None
