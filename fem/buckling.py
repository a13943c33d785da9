"""Linear (eigenvalue) buckling: ``solve_buckling(model, supports, loads, n) -> Buckling``,
and the incremental buckling about a converged state, ``solve_incremental_buckling(model,
state, supports, loads, n) -> StateBuckling`` (see that function).

About the linear static state u0 of the loads (and prescribed displacements), the critical
load factors lambda and shapes phi solve (K + lambda K_sigma(u0)) phi = 0, K_sigma the
geometric stiffness of u0's stress (:func:`.hyperelastic.geometric_stiffness`). It is solved
as -K_sigma phi = mu K phi, mu = 1 / lambda, for the largest mu by Lanczos with one
Cholesky factorization of K (the buckling loads are the extreme eigenvalues of K^-1 K_sigma,
well separated, so few iterations). Only positive factors are returned: a load pattern that
only stretches the body has none.
"""
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import scipy.sparse.linalg as spla

from . import assembly
from .factor import factor
from .boundary import constrained_dofs, load_vector
from .hyperelastic import geometric_stiffness
from .model import Model, scalar_element
from .stability import count_negative_eigenvalues, state_displacement, tangent_stiffness
from .state_buckling import StateBuckling
from .static import StaticResult, solve_static, vertex_displacement


@dataclass(frozen=True, eq=False)
class Buckling:
    """Linear buckling of a model (:func:`flexfem.fem.solve_buckling`).

    Attributes
    ----------
    model : Model
        The model solved.
    load_factors : ndarray
        (k,) critical multipliers (-) of the applied loads and prescribed displacements,
        ascending.
    shapes : ndarray
        (k, n_dofs) buckling shapes scaled to a largest displacement component of 1 (m per m,
        arbitrary sign).
    prebuckling : StaticResult
        The linear static state that was scaled.
    """

    model: Model
    load_factors: np.ndarray
    shapes: np.ndarray
    prebuckling: StaticResult

    def vertex_shape(self, k: int) -> np.ndarray:
        """(n_vertices, dim) buckling shape k at the mesh vertices."""
        return vertex_displacement(self.model, self.shapes[k])

    def critical_reaction(self, group: str, k: int = 0) -> np.ndarray:
        """Reaction (N) of supported ``group`` at the k-th critical load: the prebuckling
        reaction times the load factor (the critical load of a displacement-driven test)."""
        return self.load_factors[k] * self.prebuckling.reactions[group]

    def write(self, path) -> Path:
        """Write every shape as a vertex field 'buckling_k (factor)' to ``.vtu``."""
        import meshio

        from .export import cell_types, pad3, oriented_corners

        femesh = self.model.mesh
        (linear, _), _ = cell_types(femesh.mesh)
        point = {f"buckling_{k + 1} ({f:.6g})": pad3(self.vertex_shape(k))
                 for k, f in enumerate(self.load_factors)}
        path = Path(path)
        if path.suffix != ".vtu":
            raise ValueError(f"path = {str(path)!r}: buckling shapes are written as .vtu")
        meshio.write(path, meshio.Mesh(pad3(femesh.mesh.p.T),
                                       [(linear, oriented_corners(femesh.mesh))],
                                       point_data=point), file_format="vtu")
        return path


def solve_buckling(model: Model, supports, loads, n: int = 3) -> Buckling:
    """The ``n`` lowest positive critical load factors and shapes of ``loads`` (Force,
    Traction, ...; N) and the prescribed displacements of ``supports`` (Fixed, Prescribed;
    held at zero in the buckling shapes). Raises ValueError if the loads compress nothing."""
    if not (isinstance(n, (int, np.integer)) and n >= 1):
        raise ValueError(f"number of buckling modes n = {n!r} must be a positive integer")
    state = solve_static(model, supports, loads)
    D, _, _ = constrained_dofs(model, supports)
    I = np.setdiff1d(np.arange(model.n_dofs), D)
    if n >= len(I):
        raise ValueError(f"n = {n} buckling modes asked for but only {len(I)} free DOFs exist")
    K = model.stiffness[I][:, I].tocsr()
    G = geometric_stiffness(model, state.u)[I][:, I].tocsr()
    if not np.any(G.data):
        raise ValueError("the loads leave the body unstressed: no buckling")
    factors, vectors = lowest_factors(K, G, n)
    shapes = np.zeros((len(factors), model.n_dofs))
    shapes[:, I] = vectors.T
    shapes /= np.abs(shapes).max(axis=1, keepdims=True)
    return Buckling(model, factors, shapes, state)


def lowest_factors(K, G, n: int) -> tuple:
    """(lambda (k,) ascending, vectors (N, k)): the k <= n lowest positive lambda of
    (K + lambda G) phi = 0 (K symmetric positive definite, N/m), solved as -G phi = mu K phi
    for the largest mu = 1 / lambda by Lanczos on one Cholesky factor of K. ValueError
    where none is positive (G compresses nothing)."""
    with factor(K, "spd") as F:
        return factored_lowest(F, K, G, n)


def factored_lowest(F, K, G, n: int, spare: int = 4, tol: float = 1e-10) -> tuple:
    """:func:`lowest_factors` on ``F``, a factor of K already made; Lanczos for n + ``spare``
    values to the relative accuracy ``tol`` (2 and 1e-8: ~4x fewer iterations, the lowest
    factor of the eight-bar unchanged to 1e-7)."""
    k = min(K.shape[0] - 1, n + spare)  # a few more than asked: tension modes may take slots
    op = spla.LinearOperator(K.shape, matvec=F.solve, matmat=F.solve, dtype=float)
    try:
        mu, vectors = spla.eigsh(-G, k=k, M=K, Minv=op, which="LA", tol=tol,
                                 maxiter=100 * k)
    except spla.ArpackNoConvergence as partial:
        # a pure-tension pattern has no isolated positive mu: take what converged
        mu, vectors = partial.eigenvalues, partial.eigenvectors
    keep = np.flatnonzero(mu > 1e-12 * np.abs(mu).max())
    if len(keep) == 0:
        raise ValueError("the loads put no part of the body in compression: no positive "
                         "buckling load factor")
    keep = keep[np.argsort(-mu[keep])][:n]
    return 1.0 / mu[keep], vectors[:, keep]


def incremental_stress(model: Model, u, du, linear: bool = False) -> np.ndarray:
    """(dim, dim, n_elements, n_points) the change dS (Pa) of the second Piola-Kirchhoff
    stress at the model's quadrature points when the state ``u`` (m) moves by ``du`` (m):
    C : sym(F^T grad du), F = I + grad u (St. Venant-Kirchhoff; plane stress's lambda*);
    ``linear``: F = I (the linear stress of du, the linearised prestress's increment)."""
    mesh = model.mesh.mesh
    element = scalar_element(mesh, model.order)

    def gradient(v):
        return assembly.displacement_gradient(mesh, element, model.quadrature,
                                              model.basis.element_dofs, model.dim, v)

    dH = gradient(du)
    F = dH * 0.0 if linear else gradient(u)
    F += np.eye(model.dim)[:, :, None, None]
    FtdH = np.einsum("kieq,kjeq->ijeq", F, dH)
    dE = 0.5 * (FtdH + FtdH.transpose(1, 0, 2, 3))
    lam, mu = model.lame
    trace = np.einsum("iieq->eq", dE)
    return lam * trace * np.eye(model.dim)[:, :, None, None] + 2.0 * mu * dE


def _state_step(state):
    """The step index a state names (None: a DOF vector or a linear state)."""
    if isinstance(state, tuple):
        return int(state[1]) % len(state[0].u)
    return len(state.u) - 1 if hasattr(state, "load_factors") else None


def solve_incremental_buckling(model: Model, state, supports, loads,
                               n: int = 3) -> StateBuckling:
    """Incremental linearised buckling about a converged ``state``: the ``n`` lowest
    positive lambda at which K_T(state) + lambda K_G(state, P) is singular (the buckling
    load of the loads P added to the state, as Abaqus' *BUCKLE after a nonlinear step).

    K_T is the tangent about the state (:func:`.stability.tangent_stiffness`: a
    NonlinearResult's step, ``(result, step)``, a DOF vector, or a StaticResult's linearised
    prestress K + K_sigma); du = K_T^-1 P the state's linear response to P (``loads``, N; dead
    loads) with ``supports`` held at zero (their values ignored: the state already holds
    them); K_G the initial-stress stiffness of the stress increment of du
    (:func:`incremental_stress`, in the state's configuration). Not the limit point of the
    path itself (the path's own loads are not scaled; the change of the material tangent
    with du is left out): a first-order estimate that is exact for a linear column, where
    it gives P_cr - P_pre, and close to the path's own critical point where the state is
    near it. ValueError if the tangent is not positive definite (the state is not stable
    under these supports) or P compresses nothing."""
    if not (isinstance(n, (int, np.integer)) and n >= 1):
        raise ValueError(f"number of buckling modes n = {n!r} must be a positive integer")
    u, kind = state_displacement(model, state)
    K_T = tangent_stiffness(model, state)
    if kind == "nonlinear":
        K_T = K_T + model.extra_stiffness
    D, _, _ = constrained_dofs(model, supports)
    I = np.setdiff1d(np.arange(model.n_dofs), D)
    if n >= len(I):
        raise ValueError(f"n = {n} buckling modes asked for but only {len(I)} free DOFs exist")
    K = K_T[I][:, I]
    K = (0.5 * (K + K.T)).tocsr()
    f = load_vector(model, loads)[I]
    if not np.any(f):
        raise ValueError("loads: the added loads are zero on the free DOFs: nothing to buckle")
    negative = count_negative_eigenvalues(K)
    if negative:
        raise ValueError(f"state: the tangent has {negative} negative eigenvalue(s) under "
                         "these supports: the state is not stable, no buckling about it")
    du = np.zeros(model.n_dofs)
    with factor(K, "spd") as F:
        du[I] = F.solve(f)
        dS = incremental_stress(model, u, du, linear=kind == "linear")
        mesh = model.mesh.mesh
        G = assembly.geometric_stiffness(mesh, scalar_element(mesh, model.order),
                                         model.quadrature, model.node_pattern, model.dim, dS,
                                         model.thickness)[I][:, I].tocsr()
        factors, vectors = factored_lowest(F, K, G, n, spare=2, tol=1e-8)
    shapes = np.zeros((len(factors), model.n_dofs))
    shapes[:, I] = vectors.T
    shapes /= np.abs(shapes).max(axis=1, keepdims=True)
    return StateBuckling(model, factors, shapes, du, _state_step(state))
