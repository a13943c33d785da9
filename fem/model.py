"""A finite-element model: mesh + material + formulation + element order, and its matrices.

The stiffness and mass matrices are assembled on first use and kept on the model (an
explicit, named cache: ``model.stiffness``, ``model.mass``), so a static and a modal solve of
the same model share them.
"""
import math
import numbers
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np
import scipy.sparse as sp
import skfem
from skfem.helpers import eye, grad, trace

from .materials import Material
from .mesh import FEMesh


def _check_thickness(formulation: str, thickness) -> None:
    ok = isinstance(thickness, numbers.Real) and not isinstance(thickness, bool)
    if not (ok and math.isfinite(thickness) and thickness > 0):
        raise ValueError(f"{formulation} thickness = {thickness!r} must be a finite number > 0 (m)")


@dataclass(frozen=True)
class PlaneStress:
    """2-D plane stress: thin plate of ``thickness`` (m) loaded in its plane."""

    thickness: float

    def __post_init__(self):
        _check_thickness("PlaneStress", self.thickness)


@dataclass(frozen=True)
class PlaneStrain:
    """2-D plane strain: a slice of ``thickness`` (m, default 1) of a long prismatic body."""

    thickness: float = 1.0

    def __post_init__(self):
        _check_thickness("PlaneStrain", self.thickness)


@dataclass(frozen=True)
class Solid3D:
    """3-D solid."""

    thickness: float = 1.0  # integrals are not scaled in 3-D


_ELEMENTS = {
    (skfem.MeshTri, 1): skfem.ElementTriP1, (skfem.MeshTri, 2): skfem.ElementTriP2,
    (skfem.MeshQuad, 1): skfem.ElementQuad1, (skfem.MeshQuad, 2): skfem.ElementQuad2,
    (skfem.MeshTet, 1): skfem.ElementTetP1, (skfem.MeshTet, 2): skfem.ElementTetP2,
    (skfem.MeshHex, 1): skfem.ElementHex1, (skfem.MeshHex, 2): skfem.ElementHex2,
}


def scalar_element(mesh: skfem.Mesh, order: int) -> skfem.Element:
    """The Lagrange element of ``order`` (1 or 2) for the mesh's cell type."""
    for (mesh_type, o), element in _ELEMENTS.items():
        if isinstance(mesh, mesh_type) and o == order:
            return element()
    raise ValueError(f"order = {order} must be 1 or 2 for a {type(mesh).__name__}")


@dataclass(frozen=True, eq=False)
class Model:
    """mesh : FEMesh (m); material : Material; formulation : PlaneStress, PlaneStrain or
    Solid3D; order : 1 (linear) or 2 (quadratic) elements."""

    mesh: FEMesh
    material: Material
    formulation: object
    order: int = 2

    def __post_init__(self):
        dim = self.mesh.dim
        if dim == 3 and not isinstance(self.formulation, Solid3D):
            raise ValueError("a 3-D mesh needs formulation=Solid3D()")
        if dim == 2 and not isinstance(self.formulation, (PlaneStress, PlaneStrain)):
            raise ValueError("a 2-D mesh needs formulation=PlaneStress(thickness) or PlaneStrain()")
        scalar_element(self.mesh.mesh, self.order)  # validates the order

    @property
    def dim(self) -> int:
        return self.mesh.dim

    @property
    def thickness(self) -> float:
        """Out-of-plane thickness (m) multiplying 2-D integrals; 1 in 3-D."""
        return 1.0 if self.dim == 3 else self.formulation.thickness

    @property
    def lame(self) -> tuple[float, float]:
        """(lambda, mu) in Pa; plane stress uses lambda* = 2 lambda mu / (lambda + 2 mu)."""
        lam, mu = self.material.lame
        if isinstance(self.formulation, PlaneStress):
            lam = 2 * lam * mu / (lam + 2 * mu)
        return lam, mu

    @property
    def is_affine(self) -> bool:
        return isinstance(self.mesh.mesh, (skfem.MeshTri, skfem.MeshTet))

    @cached_property
    def basis(self) -> skfem.CellBasis:
        """Vector basis; quadrature exact for the mass matrix (degree 2 * order)."""
        element = skfem.ElementVector(scalar_element(self.mesh.mesh, self.order))
        intorder = 2 * self.order if self.is_affine else 2 * self.order + 1
        return skfem.Basis(self.mesh.mesh, element, intorder=intorder)

    @cached_property
    def stiffness_basis(self) -> skfem.CellBasis:
        """Basis with the lowest quadrature exact for the stiffness: degree 2 (order - 1) on
        straight-sided simplices; the mass-matrix rule elsewhere."""
        if not self.is_affine:
            return self.basis
        return skfem.Basis(self.mesh.mesh, self.basis.elem, intorder=max(2 * (self.order - 1), 1))

    @property
    def n_dofs(self) -> int:
        return self.basis.N

    @cached_property
    def stiffness(self):
        """Global stiffness matrix K (N/m), CSR: :func:`elasticity_stiffness`, the matrix of
        skfem's BilinearForm t (2 mu eps(u):eps(v) + lam tr eps(u) tr eps(v)) on
        ``stiffness_basis``, assembled ~3x faster."""
        lam, mu = self.lame
        scalar = self._scalar_basis(self.stiffness_quadrature)
        return elasticity_stiffness(scalar, self.basis.element_dofs, self.dim, lam, mu,
                                    self.thickness, self.n_dofs)

    @cached_property
    def mass(self):
        """Consistent mass matrix M (kg), CSR: :func:`consistent_mass` on the quadrature of
        ``basis`` (the matrix of skfem's BilinearForm rho t u.v)."""
        scalar = self._scalar_basis((self.basis.X, self.basis.W))
        return consistent_mass(scalar, self.basis.element_dofs, self.dim,
                               self.material.rho * self.thickness, self.n_dofs)

    def with_stiffness(self, extra) -> "Model":
        """A copy of this model whose stiffness is K + ``extra`` (N/m; a symmetric sparse
        n_dofs x n_dofs matrix, e.g. :func:`~flexfem.fem.springs.group_spring`), for the linear
        analyses (static, modal, harmonic, compliance, buckling); the nonlinear solver
        assembles its own tangent and does not see it."""
        if getattr(extra, "shape", None) != (self.n_dofs, self.n_dofs):
            raise ValueError(f"extra stiffness of shape {getattr(extra, 'shape', None)} must be "
                             f"({self.n_dofs}, {self.n_dofs})")
        copy = replace(self)
        copy.__dict__["stiffness"] = (self.stiffness + extra).tocsr()  # the named cache
        return copy

    @property
    def stiffness_quadrature(self):
        """(points, weights) of the stiffness rule on the reference element."""
        if not self.is_affine:
            return self.basis.X, self.basis.W
        return skfem.quadrature.get_quadrature(self.basis.elem.refdom, max(2 * (self.order - 1), 1))

    def _scalar_basis(self, quadrature) -> skfem.CellBasis:
        return skfem.CellBasis(self.mesh.mesh, scalar_element(self.mesh.mesh, self.order),
                               quadrature=quadrature)

    def stress(self, u: np.ndarray, basis=None):
        """Cauchy stress (Pa) at the quadrature points of ``basis`` (default: the model's),
        as a (3, 3, n_elements, n_points) array (plane stress: zz = 0; plane strain:
        zz = lambda (xx + yy))."""
        basis = basis or self.basis
        return linear_stress(self, grad(basis.interpolate(u)))


# elements per block of the vectorised assembly: bounds its temporaries to ~0.1 GB in 3-D P2
_BLOCK = 20_000


def _scalar_gradients(scalar: skfem.CellBasis, elements: slice) -> np.ndarray:
    """(n_elements, n_local, dim, n_points) gradients (1/m) of the scalar shape functions."""
    return np.stack([phi[0].grad[:, elements] for phi in scalar.basis]).transpose(2, 0, 1, 3)


def elasticity_stiffness(scalar: skfem.CellBasis, element_dofs: np.ndarray, dim: int,
                         lam: float, mu: float, thickness: float, n_dofs: int):
    """Isotropic linear-elastic stiffness (N/m), CSR, from the scalar shape-function gradients
    of ``scalar`` (its quadrature sets the rule) and the vector element DOFs ``element_dofs``
    ((n_local dim, n_elements), skfem's ElementVector order: local DOF a dim + i is
    component i of scalar function a).

    K_e[a i, b j] = t sum_q w_q (lam d_i phi_a d_j phi_b + mu d_j phi_a d_i phi_b
    + mu delta_ij grad phi_a . grad phi_b), i.e. t (2 mu eps(u):eps(v) + lam div u div v).
    """
    n_local = len(scalar.basis)
    n_el = element_dofs.shape[1]
    data = np.empty((n_el, n_local, dim, n_local, dim))
    eye = np.eye(dim)
    for start in range(0, n_el, _BLOCK):
        block = slice(start, min(start + _BLOCK, n_el))
        G = _scalar_gradients(scalar, block).reshape(-1, n_local * dim, scalar.dx.shape[1])
        C = np.matmul(G * (thickness * scalar.dx[block])[:, None, :], G.transpose(0, 2, 1))
        C = C.reshape(-1, n_local, dim, n_local, dim)  # t sum_q w d_i phi_a d_j phi_b
        laplace = np.einsum("eakbk->eab", C)
        out = data[block]
        np.multiply(lam, C, out=out)
        out += mu * C.transpose(0, 1, 4, 3, 2)
        out += mu * laplace[:, :, None, :, None] * eye[None, None, :, None, :]
    return _to_csr(data.reshape(n_el, n_local * dim, n_local * dim), element_dofs, n_dofs)


def consistent_mass(scalar: skfem.CellBasis, element_dofs: np.ndarray, dim: int,
                    density: float, n_dofs: int):
    """Consistent mass matrix (kg), CSR: M_e[a i, b j] = delta_ij sum_q w_q rho t phi_a phi_b,
    ``density`` = rho t (kg/m^3 in 3-D, kg/m^2 in 2-D); arguments as
    :func:`elasticity_stiffness`. Only the delta_ij blocks are assembled."""
    n_local = len(scalar.basis)
    # a DiscreteField is the array of values in skfem >= 11, a named tuple before
    phi = np.stack([np.asarray(f[0]) if isinstance(f[0], np.ndarray) else f[0].value
                    for f in scalar.basis]).transpose(1, 0, 2)  # (e, a, q)
    m = np.matmul(phi * (density * scalar.dx)[:, None, :], phi.transpose(0, 2, 1))  # (e, a, b)
    dofs = element_dofs.reshape(n_local, dim, -1).transpose(2, 1, 0)  # (e, i, a)
    rows = np.broadcast_to(dofs[:, :, :, None], dofs.shape + (n_local,))
    cols = np.broadcast_to(dofs[:, :, None, :], dofs.shape + (n_local,))
    data = np.broadcast_to(m[:, None], rows.shape)
    return sp.coo_matrix((data.ravel(), (rows.ravel(), cols.ravel())),
                         shape=(n_dofs, n_dofs)).tocsr()


def _to_csr(local: np.ndarray, element_dofs: np.ndarray, n_dofs: int):
    """Sum element matrices (n_elements, n, n) into a global CSR matrix (duplicates added,
    exact zeros dropped as skfem does)."""
    dofs = element_dofs.T.astype(np.int64 if n_dofs > 2**31 - 1 else np.int32)  # (e, n)
    n = dofs.shape[1]
    rows = np.repeat(dofs, n, axis=1).ravel()
    cols = np.tile(dofs, (1, n)).ravel()
    K = sp.coo_matrix((local.ravel(), (rows, cols)), shape=(n_dofs, n_dofs)).tocsr()
    K.eliminate_zeros()
    return K


def von_mises(sig: np.ndarray) -> np.ndarray:
    """Von Mises equivalent stress (Pa) of a (3, 3, ...) stress array."""
    s = sig - np.einsum("ii...->...", sig) / 3.0 * np.eye(3).reshape((3, 3) + (1,) * (sig.ndim - 2))
    return np.sqrt(1.5 * np.einsum("ij...,ij...->...", s, s))


def rigid_body_modes(points: np.ndarray) -> np.ndarray:
    """Rigid-body displacement fields at ``points`` ((dim, n), m): (n, dim) per mode,
    stacked as (n_modes, n, dim): 3 modes in 2-D, 6 in 3-D."""
    dim, n = points.shape
    x = points - points.mean(axis=1, keepdims=True)
    modes = []
    for i in range(dim):
        m = np.zeros((n, dim))
        m[:, i] = 1.0
        modes.append(m)
    pairs = [(0, 1)] if dim == 2 else [(0, 1), (1, 2), (2, 0)]
    for i, j in pairs:
        m = np.zeros((n, dim))
        m[:, i], m[:, j] = -x[j], x[i]
        modes.append(m)
    return np.array(modes)


def linear_stress(model, gu: np.ndarray) -> np.ndarray:
    """(3, 3, ...) Cauchy stress (Pa) of the displacement gradient ``gu`` ((dim, dim, ...));
    plane stress: zz = 0, plane strain: zz = lambda (xx + yy)."""
    lam, mu = model.lame
    eps = 0.5 * (gu + np.swapaxes(gu, 0, 1))
    sig = 2.0 * mu * eps + lam * trace(eps) * eye(np.ones_like(eps[0, 0]), eps.shape[0])
    if model.dim == 3:
        return sig
    full = np.zeros((3, 3) + sig.shape[2:])
    full[:2, :2] = sig
    if isinstance(model.formulation, PlaneStrain):
        full[2, 2] = lam * trace(eps)
    return full
