"""Linear (eigenvalue) buckling: ``solve_buckling(model, supports, loads, n) -> Buckling``.

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

from .factor import factor
from .boundary import constrained_dofs
from .hyperelastic import geometric_stiffness
from .model import Model
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
    k = min(len(I) - 1, n + 4)  # a few more than asked: tension modes may take some slots
    with factor(K, "spd") as F:
        op = spla.LinearOperator(K.shape, matvec=F.solve, matmat=F.solve, dtype=float)
        try:
            mu, vectors = spla.eigsh(-G, k=k, M=K, Minv=op, which="LA", tol=1e-10,
                                     maxiter=100 * k)
        except spla.ArpackNoConvergence as partial:
            # a pure-tension pattern has no isolated positive mu: take what converged
            mu, vectors = partial.eigenvalues, partial.eigenvectors
    keep = np.flatnonzero(mu > 1e-12 * np.abs(mu).max())
    if len(keep) == 0:
        raise ValueError("the loads put no part of the body in compression: no positive "
                         "buckling load factor")
    keep = keep[np.argsort(-mu[keep])][:n]
    shapes = np.zeros((len(keep), model.n_dofs))
    shapes[:, I] = vectors[:, keep].T
    shapes /= np.abs(shapes).max(axis=1, keepdims=True)
    return Buckling(model, 1.0 / mu[keep], shapes, state)
