"""A finite-element model: mesh + material + formulation + element order, and its matrices.

The stiffness and mass matrices are assembled on first use and kept on the model (an
explicit, named cache: ``model.stiffness``, ``model.mass``), so a static and a modal solve of
the same model share them.
"""
from dataclasses import dataclass
from functools import cached_property
import math
import numbers

import numpy as np
import skfem
from skfem.helpers import ddot, dot, sym_grad, trace, eye

from flexfem.fem.materials import Material
from flexfem.fem.mesh import FEMesh


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
        """Global stiffness matrix K (N/m), CSR."""
        lam, mu = self.lame
        t = self.thickness

        @skfem.BilinearForm
        def form(u, v, w):
            eps_u, eps_v = sym_grad(u), sym_grad(v)
            return t * (2.0 * mu * ddot(eps_u, eps_v) + lam * trace(eps_u) * trace(eps_v))

        return form.assemble(self.stiffness_basis).tocsr()

    @cached_property
    def mass(self):
        """Consistent mass matrix M (kg), CSR."""
        rho_t = self.material.rho * self.thickness

        @skfem.BilinearForm
        def form(u, v, w):
            return rho_t * dot(u, v)

        return form.assemble(self.basis).tocsr()

    def stress(self, u: np.ndarray, basis=None):
        """Cauchy stress (Pa) at the quadrature points of ``basis`` (default: the model's),
        as a (3, 3, n_elements, n_points) array (plane stress: zz = 0; plane strain:
        zz = lambda (xx + yy))."""
        basis = basis or self.basis
        lam, mu = self.lame
        eps = sym_grad(basis.interpolate(u))
        sig = 2.0 * mu * eps + lam * trace(eps) * eye(np.ones_like(eps[0, 0]), eps.shape[0])
        if self.dim == 3:
            return sig
        full = np.zeros((3, 3) + sig.shape[2:])
        full[:2, :2] = sig
        if isinstance(self.formulation, PlaneStrain):
            full[2, 2] = lam * trace(eps)
        return full


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
