"""Stress tensors at arbitrary points and as nodal fields, for linear and nonlinear results.

    result.stress_at([(0.0, 0.005)])        # (1, 2, 2) Cauchy stress (Pa) in its element
    result.nodal_stress                     # (n_vertices, 2, 2), L2-projected (Pa)
    s = nonlinear_stress(large)             # {'second_piola_kirchhoff': ..., 'cauchy': ...}
    nonlinear_stress_at(large, points)      # the same at reference points

Points are located in their containing element (a KD-tree of element centroids, then the
inverse element map: exact for simplices, Newton for quadrilaterals and hexahedra) and the
element's own polynomial field is differentiated there: no smoothing.
"""
import numpy as np
import skfem
from skfem.helpers import eye, trace

from .hyperelastic import cauchy_stress, deformation, green_lagrange, svk_stress
from .model import PlaneStrain, linear_stress
from .projection import nodal_average

# a point counts as inside an element when its reference coordinates lie within the
# reference element up to this margin (reference units: 1e-9 of the element's size)
INSIDE_TOL = 1e-9
_CANDIDATES = 12  # nearest element centroids tried before searching every element


def _is_simplex(mesh) -> bool:
    return isinstance(mesh, (skfem.MeshTri, skfem.MeshTet))


def _reference_coordinates(mesh, mapping, x: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """(dim, n_cells) reference coordinates of the point ``x`` ((dim,), m) in each cell; for
    multilinear maps by unclipped Newton iterations (skfem's invF clips to the element)."""
    xs = np.broadcast_to(x[:, None, None], (len(x), len(cells), 1)).copy()
    if _is_simplex(mesh):
        return mapping.invF(xs, tind=cells)[:, :, 0]
    X = np.full(xs.shape, 0.5)
    for _ in range(30):
        dX = np.einsum("ijkl,jkl->ikl", mapping.invDF(X, tind=cells), xs - mapping.F(X, tind=cells))
        X = X + np.nan_to_num(dX)
        if np.max(np.abs(dX)) < 1e-13:
            break
    return X[:, :, 0]


def _inside_margin(mesh, X: np.ndarray) -> np.ndarray:
    """Smallest distance (reference units) of reference points ``X`` (dim, n) inside the
    reference element; negative outside."""
    if _is_simplex(mesh):
        return np.minimum(X.min(axis=0), 1.0 - X.sum(axis=0))
    return np.minimum(X.min(axis=0), (1.0 - X).min(axis=0))


def locate(mesh: skfem.Mesh, points) -> tuple[np.ndarray, np.ndarray]:
    """(cells (n,), reference coordinates (dim, n)) of ``points`` ((n, dim), m). A point in no
    element raises ValueError naming it."""
    dim = mesh.dim()
    pts = np.atleast_2d(np.asarray(points, dtype=float))
    if pts.ndim != 2 or pts.shape[1] != dim or not np.all(np.isfinite(pts)):
        raise ValueError(f"points = {np.asarray(points).tolist()} must be finite (n, {dim}) "
                         f"coordinates (m) of a {dim}-D mesh")
    mapping = mesh.mapping()
    centroids = mesh.p[:, mesh.t].mean(axis=1).T
    from scipy.spatial import cKDTree  # here: scipy.spatial costs every process ~7 MiB
    tree = cKDTree(centroids)
    k = min(_CANDIDATES, mesh.t.shape[1])
    cells = np.empty(len(pts), dtype=np.int64)
    X = np.empty((dim, len(pts)))
    lo, hi = mesh.p[:, mesh.t].min(axis=1), mesh.p[:, mesh.t].max(axis=1)  # (dim, n_el)
    for i, x in enumerate(pts):
        candidates = np.atleast_1d(tree.query(x, k)[1])
        Xc = _reference_coordinates(mesh, mapping, x, candidates)
        margin = _inside_margin(mesh, Xc)
        if margin.max() < -INSIDE_TOL:
            span = hi - lo
            near = np.all((lo - 1e-9 * span <= x[:, None]) & (x[:, None] <= hi + 1e-9 * span), axis=0)
            candidates = np.flatnonzero(near)
            if len(candidates) == 0:
                margin = np.array([-np.inf])
            else:
                Xc = _reference_coordinates(mesh, mapping, x, candidates)
                margin = _inside_margin(mesh, Xc)
        best = int(np.argmax(margin))
        if not margin[best] >= -INSIDE_TOL:
            gap = np.sqrt(np.min(np.sum((mesh.p - x[:, None]) ** 2, axis=0)))
            raise ValueError(f"points[{i}] = {x.tolist()} m lies in no element of the mesh "
                             f"(nearest vertex {gap:.3g} m away; the body spans "
                             f"{mesh.p.min(axis=1).tolist()} to {mesh.p.max(axis=1).tolist()} m)")
        cells[i], X[:, i] = candidates[best], Xc[:, best]
    return cells, X


def gradient_at(basis: skfem.CellBasis, u: np.ndarray, cells: np.ndarray,
                X: np.ndarray) -> np.ndarray:
    """(dim, dim, n, 1) gradient of the vector field ``u`` (DOF vector) at reference points
    ``X`` ((dim, n)) of ``cells``; component [i, j] = d u_i / d x_j."""
    mapping = basis.mapping
    Xe = X[:, :, None]
    grad = 0.0
    for k in range(basis.Nbfun):
        phi = basis.elem.gbasis(mapping, Xe, k, tind=cells)[0]
        grad = grad + u[basis.element_dofs[k, cells]][None, None, :, None] * phi.grad
    return grad


def stress_at(result, points, full: bool = False) -> np.ndarray:
    """Cauchy stress (Pa) of a StaticResult at ``points`` ((n, dim), m) in their containing
    elements: (n, dim, dim), or (n, 3, 3) with ``full`` (2-D: the out-of-plane sigma_zz)."""
    model = result.model
    cells, X = locate(model.mesh.mesh, points)
    sig = linear_stress(model, gradient_at(model.basis, result.u, cells, X))[:, :, :, 0]
    sig = np.moveaxis(sig, 2, 0)
    return sig if full else sig[:, :model.dim, :model.dim]


def _nonlinear_tensors(model, F: np.ndarray) -> dict:
    """{'second_piola_kirchhoff', 'cauchy'}: (3, 3, ...) stresses (Pa) of the deformation
    gradient ``F`` (St. Venant-Kirchhoff; 2-D as nonlinear.final_stress)."""

    lam, mu = model.lame
    E = green_lagrange(F)
    S = svk_stress(E, lam, mu)
    sig = cauchy_stress(F, S)
    if model.dim == 3:
        return {"second_piola_kirchhoff": S, "cauchy": sig}
    out = {}
    J = np.linalg.det(np.moveaxis(F, (0, 1), (-2, -1)))
    for name, value, scale in (("second_piola_kirchhoff", S, 1.0), ("cauchy", sig, 1.0 / J)):
        full = np.zeros((3, 3) + value.shape[2:])
        full[:2, :2] = value
        if isinstance(model.formulation, PlaneStrain):
            full[2, 2] = lam * trace(E) * scale
        out[name] = full
    return out


def nonlinear_stress_at(result, points, step: int = -1, full: bool = False) -> dict:
    """{'second_piola_kirchhoff', 'cauchy'}: (n, dim, dim) stresses (Pa) of a NonlinearResult
    at ``step``, at ``points`` ((n, dim), m) given in the reference (undeformed) configuration;
    (n, 3, 3) with ``full``."""
    model = result.model
    cells, X = locate(model.mesh.mesh, points)
    gu = gradient_at(model.basis, result.u[step], cells, X)
    F = gu + eye(np.ones_like(gu[0, 0]), model.dim)
    d = 3 if full else model.dim
    return {name: np.moveaxis(value[:, :, :, 0], 2, 0)[:, :d, :d]
            for name, value in _nonlinear_tensors(model, F).items()}


def nonlinear_stress(result, step: int = -1, full: bool = False) -> dict:
    """{'second_piola_kirchhoff', 'cauchy'}: (n_vertices, dim, dim) nodal stresses (Pa) of a
    NonlinearResult at ``step``, L2-projected from the quadrature points onto continuous linear
    fields on the reference mesh; (n_vertices, 3, 3) with ``full``."""

    model = result.model
    F = deformation(model.basis, result.u[step])
    d = 3 if full else model.dim
    return {name: np.moveaxis(nodal_average(model, value), 2, 0)[:, :d, :d]
            for name, value in _nonlinear_tensors(model, F).items()}
