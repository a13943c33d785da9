"""A finite-element model: mesh + material + formulation + element order, and its matrices.

The stiffness and mass matrices are assembled on first use and kept on the model as their
upper triangles (an explicit, named cache: ``model.stiffness_upper``, ``model.mass_upper``),
which is what the static and modal solves read, so that they share them; the full matrices
``model.stiffness`` and ``model.mass`` are built from these on first use and kept too.
"""
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np
import scipy.sparse as sp
import skfem
from skfem.helpers import eye, grad, trace

from . import assembly, checks, memory, symmetric
from .materials import Material
from .mesh import FEMesh


@dataclass(frozen=True)
class PlaneStress:
    """2-D plane stress: thin plate of ``thickness`` (m) loaded in its plane."""

    thickness: float

    def __post_init__(self):
        checks.positive("thickness", self.thickness, owner="PlaneStress", unit="m")


@dataclass(frozen=True)
class PlaneStrain:
    """2-D plane strain: a slice of ``thickness`` (m, default 1) of a long prismatic body."""

    thickness: float = 1.0

    def __post_init__(self):
        checks.positive("thickness", self.thickness, owner="PlaneStrain", unit="m")


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


class LazyCellBasis(skfem.CellBasis):
    """skfem's CellBasis, with the shape functions at the quadrature points (``basis``, ``dx``)
    evaluated on first use instead of on construction: a 3-D P2 vector basis holds ~26 kB of
    them per element (530 MiB and 1.1 s at 20 580 tetrahedra), which the assembly, the static
    and the modal solves do not read (they need its DOFs and rule only)."""

    def __init__(self, mesh, elem, mapping=None, intorder=None, elements=None,
                 quadrature=None, dofs=None, disable_doflocs=False):
        # CellBasis.__init__ less its two eager lines (skfem >= 10)
        skfem.assembly.basis.AbstractBasis.__init__(self, mesh, elem, mapping, intorder,
                                                    quadrature, mesh.refdom, dofs,
                                                    disable_doflocs)
        self.tind = None if elements is None else mesh.normalize_elements(elements)
        self.nelems = mesh.nelements if elements is None else len(self.tind)

    @cached_property
    def basis(self):
        return [self.elem.gbasis(self.mapping, self.X, j, tind=self.tind)
                for j in range(self.Nbfun)]

    @cached_property
    def dx(self):
        return (np.abs(self.mapping.detDF(self.X, tind=self.tind))
                * np.broadcast_to(self.W, (self.nelems, self.W.shape[-1])))


@dataclass(frozen=True, eq=False)
class Model:
    """The continuum finite-element model: a mesh, its material and formulation.

    Parameters
    ----------
    mesh : FEMesh
        The mesh with its named groups (coordinates in m).
    material : Material
        The isotropic linear-elastic material (Pa, kg/m^3).
    formulation : PlaneStress, PlaneStrain or Solid3D
        A 2-D mesh's plane stress (with its out-of-plane thickness, m) or plane strain; a 3-D
        mesh's Solid3D.
    order : int
        1 (linear) or 2 (quadratic, the default) Lagrange elements.

    Raises
    ------
    ValueError
        A formulation that does not match the mesh's dimension, an order that is not 1 or 2.
    """

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

    @cached_property
    def cell_mesh(self) -> skfem.Mesh:
        """The mesh the cells are mapped on: ``mesh.mesh``, or its quadratic (curved) copy
        where the mesh has curved edges and the order is 2 (:meth:`.FEMesh.cell_mesh`)."""
        return self.mesh.cell_mesh(self.order)

    @property
    def is_affine(self) -> bool:
        """Straight-sided triangles or tetrahedra: a constant Jacobian in each cell."""
        return bool(getattr(self.cell_mesh, "affine", False))

    @cached_property
    def basis(self) -> skfem.CellBasis:
        """Vector basis; quadrature exact for the mass matrix (degree 2 * order)."""
        element = skfem.ElementVector(scalar_element(self.cell_mesh, self.order))
        intorder = 2 * self.order if self.is_affine else 2 * self.order + 1
        return LazyCellBasis(self.cell_mesh, element, intorder=intorder)

    @cached_property
    def stiffness_basis(self) -> skfem.CellBasis:
        """Basis with the lowest quadrature exact for the stiffness: degree 2 (order - 1) on
        straight-sided simplices; the mass-matrix rule elsewhere."""
        if not self.is_affine:
            return self.basis
        return LazyCellBasis(self.cell_mesh, self.basis.elem, intorder=max(2 * (self.order - 1), 1))

    @property
    def n_dofs(self) -> int:
        return self.basis.N

    @cached_property
    def node_pattern(self) -> assembly.NodePattern:
        """Node-to-node sparsity pattern of the mesh, shared by the stiffness and the mass."""
        dofs = assembly.node_dofs(self.basis.element_dofs, self.dim)
        return assembly.node_pattern(dofs, self.n_dofs // self.dim)

    @cached_property
    def stiffness_upper(self):
        """Upper triangle (diagonal included) of the global stiffness matrix K (N/m), CSR:
        :func:`.assembly.elasticity_stiffness_upper`, the matrix of skfem's BilinearForm
        t (2 mu eps(u):eps(v) + lam tr eps(u) tr eps(v)) on ``stiffness_basis``."""
        return self.assemble_stiffness_upper()

    def assemble_stiffness_upper(self):
        """``stiffness_upper`` assembled anew and not kept on the model."""
        lam, mu = self.lame
        K = assembly.elasticity_stiffness_upper(
            self.cell_mesh, scalar_element(self.cell_mesh, self.order), self.stiffness_quadrature,
            self.node_pattern, self.dim, lam, mu, self.thickness)
        memory.release_freed()  # the element blocks' temporaries
        return K

    @cached_property
    def mass_upper(self):
        """Upper triangle (diagonal included) of the consistent mass matrix M (kg), CSR:
        :func:`.assembly.consistent_mass` on the quadrature of ``basis`` (the matrix of
        skfem's BilinearForm rho t u.v)."""
        M = symmetric.upper(assembly.consistent_mass(
            self.cell_mesh, scalar_element(self.cell_mesh, self.order), self.quadrature,
            self.node_pattern, self.dim, self.material.density * self.thickness))
        memory.release_freed()
        return M

    @cached_property
    def stiffness(self):
        """Global stiffness matrix K (N/m), full CSR, built from ``stiffness_upper`` on first
        use (the static and modal solves read the upper triangle only)."""
        return symmetric.symmetric_from_upper(self.stiffness_upper)

    @cached_property
    def mass(self):
        """Consistent mass matrix M (kg), full CSR, built from ``mass_upper`` on first use."""
        return symmetric.symmetric_from_upper(self.mass_upper)

    def with_stiffness(self, extra) -> "Model":
        """A copy of this model whose stiffness is K + ``extra`` (N/m; a symmetric sparse
        n_dofs x n_dofs matrix, e.g. :func:`~flexfem.fem.springs.group_spring`), for the linear
        analyses (static, modal, harmonic, compliance, buckling) and, as a linear term
        ``extra @ u`` in the residual and its tangent, the nonlinear solver (a spring that
        stays along its axis: small spring rotations)."""
        if getattr(extra, "shape", None) != (self.n_dofs, self.n_dofs):
            raise ValueError(f"extra stiffness of shape {getattr(extra, 'shape', None)} must be "
                             f"({self.n_dofs}, {self.n_dofs})")
        extra = sp.csr_matrix(extra, dtype=float)
        scale = abs(extra).max() if extra.nnz else 0.0
        if extra.nnz and abs(extra - extra.T).max() > 1e-12 * scale:
            raise ValueError("extra stiffness must be symmetric (it is added to K, which the "
                             "solvers keep as its upper triangle)")
        copy = replace(self)
        # the named cache: the upper triangle of K + extra
        copy.__dict__["stiffness_upper"] = symmetric.upper(self.stiffness_upper + extra)
        copy.__dict__["extra_stiffness"] = extra + self.extra_stiffness
        return copy

    @cached_property
    def extra_stiffness(self) -> sp.csr_matrix:
        """The stiffness added by :meth:`with_stiffness` (N/m; zero for a plain model)."""
        return sp.csr_matrix((self.n_dofs, self.n_dofs))

    @property
    def stiffness_quadrature(self):
        """(points, weights) of the stiffness rule on the reference element."""
        if not self.is_affine:
            return self.basis.X, self.basis.W
        return skfem.quadrature.get_quadrature(self.basis.elem.refdom, max(2 * (self.order - 1), 1))

    @property
    def quadrature(self):
        """(points, weights) of ``basis``'s rule on the reference element."""
        return self.basis.X, self.basis.W

    def stress(self, u: np.ndarray, basis=None):
        """Cauchy stress (Pa) at the quadrature points of ``basis`` (default: the model's),
        as a (3, 3, n_elements, n_points) array (plane stress: zz = 0; plane strain:
        zz = lambda (xx + yy))."""
        if basis is None:  # from the scalar shape functions: the vector basis is not built
            gu = assembly.displacement_gradient(
                self.cell_mesh, scalar_element(self.cell_mesh, self.order), self.quadrature,
                self.basis.element_dofs, self.dim, u)
        else:
            gu = grad(basis.interpolate(u))
        return linear_stress(self, gu)


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
