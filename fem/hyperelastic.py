"""Total-Lagrangian kinematics and St. Venant-Kirchhoff material: deformation gradient,
Green-Lagrange strain, stresses, the consistent tangent and its assembly, and the geometric
(initial-stress) stiffness used by buckling and prestressed modal analyses.

St. Venant-Kirchhoff (S = lambda tr(E) I + 2 mu E) is Hooke's law written in the Green-Lagrange
strain: exact for large rotations with small strains. Its stress departs from a linear law by a
relative ~1.5 e at a uniaxial strain e (nominal stress E (e + 1.5 e^2 + e^3 / 2)), and in
compression it softens and loses stability at a stretch of 1/sqrt(3) (e = -42 %), so beyond a
few per cent of strain its response is no material's: :data:`STRAIN_LIMIT` (5 %, 7.5 %
departure) is the validity limit flagged by the nonlinear solver.
"""
import numpy as np
import scipy.sparse as sp
import skfem
from skfem.helpers import ddot, eye, grad, mul, transpose, trace

from . import assembly
from .model import Model, PlaneStrain, scalar_element, von_mises
from .projection import nodal_average
from .symmetric import symmetric_from_upper
from .stepping import StepFailed  # raised here, caught by the step driver

STRAIN_LIMIT = 0.05


def green_lagrange(F: np.ndarray) -> np.ndarray:
    """E = (F^T F - I) / 2 of a (dim, dim, ...) deformation gradient."""
    return 0.5 * (mul(transpose(F), F) - eye(np.ones_like(F[0, 0]), F.shape[0]))


def green_lagrange_of_gradient(H: np.ndarray) -> np.ndarray:
    """E = (H + H^T + H^T H) / 2 of a (dim, dim, ...) displacement gradient H = grad u: the
    Green-Lagrange strain without forming F^T F - I, whose cancellation leaves an absolute
    error of ~1e-16 in every strain. That floor (a residual of ~2 mu 1e-16 Pa times each
    element's area) does not shrink with the load, so at a small load step Newton's relative
    residual would stall above its tolerance; computed from H the error stays relative to the
    strain itself."""
    return 0.5 * (H + transpose(H) + mul(transpose(H), H))


def svk_stress(E: np.ndarray, lam: float, mu: float) -> np.ndarray:
    """Second Piola-Kirchhoff stress (Pa) S = lam tr(E) I + 2 mu E."""
    return lam * trace(E) * eye(np.ones_like(E[0, 0]), E.shape[0]) + 2.0 * mu * E


def cauchy_stress(F: np.ndarray, S: np.ndarray) -> np.ndarray:
    """sigma = F S F^T / det F (Pa)."""
    return mul(mul(F, S), transpose(F)) / np.linalg.det(np.moveaxis(F, (0, 1), (-2, -1)))


def deformation(basis, u: np.ndarray):
    """F = I + grad u at the quadrature points of ``basis``, (dim, dim, n_elements, n_points)."""
    gu = basis.interpolate(u).grad
    return gu + eye(np.ones_like(gu[0, 0]), gu.shape[0])


@skfem.LinearForm
def _internal_force(v, w):
    return w.t * ddot(mul(w.F, w.S), grad(v))


def tangent_modulus(F: np.ndarray, S: np.ndarray, lam: float, mu: float) -> np.ndarray:
    """A_iJkL = delta_ik S_JL + F_iM C_MJNL F_kN (Pa), (dim,) * 4 + (n_elements, n_points):
    dP = A : grad du, the consistent tangent of P = F S for St. Venant-Kirchhoff."""
    d = F.shape[0]
    I = np.eye(d)
    A = np.einsum("ik,jl...->ijkl...", I, S)
    A += lam * np.einsum("ij...,kl...->ijkl...", F, F)
    A += mu * (np.einsum("il...,kj...->ijkl...", F, F) + np.einsum("ik...,jl...->ijkl...",
                                                                    np.einsum("im...,km...->ik...", F, F),
                                                                    I[..., None, None] + 0 * S))
    return A


class Assembler:
    """Internal force (N) and tangent (N/m) of a model, on the model's stiffness quadrature
    (exact for the linear part, so the tangent at u = 0 is ``model.stiffness``); the tangent
    batched on the model's node pattern (:func:`.assembly.tangent_stiffness_upper`)."""

    def __init__(self, model: Model):
        self.model = model
        self.basis = model.stiffness_basis
        self.lam, self.mu = model.lame
        self.t = model.thickness

    def state(self, u: np.ndarray):
        """(F, S) at the quadrature points; raises StepFailed where det F <= 0."""
        H = self.basis.interpolate(u).grad
        F = H + eye(np.ones_like(H[0, 0]), H.shape[0])
        J = np.linalg.det(np.moveaxis(F, (0, 1), (-2, -1)))
        if not np.all(np.isfinite(J)) or J.min() <= 0:
            raise StepFailed(f"an element turned inside out (min det F = {J.min():.2g})", [])
        return F, svk_stress(green_lagrange_of_gradient(H), self.lam, self.mu)

    def internal_force(self, F, S) -> np.ndarray:
        return _internal_force.assemble(self.basis, F=F, S=S, t=self.t)

    def tangent(self, F, S) -> sp.csr_matrix:
        m = self.model
        upper = assembly.tangent_stiffness_upper(
            m.cell_mesh, scalar_element(m.cell_mesh, m.order), m.stiffness_quadrature,
            m.node_pattern, m.dim, self.t * tangent_modulus(F, S, self.lam, self.mu))
        return symmetric_from_upper(upper)


def final_stress(model: Model, u: np.ndarray):
    """(nodal von Mises (n_vertices,), element max (n_elements,)) of the Cauchy stress (Pa).
    2-D: sigma_zz = 0 in plane stress, S_zz / det F in plane strain; the thickness change
    is neglected in det F (strains small beside rotations)."""
    basis = model.basis
    lam, mu = model.lame
    F = deformation(basis, u)
    E = green_lagrange(F)
    sig = cauchy_stress(F, svk_stress(E, lam, mu))
    if model.dim == 2:
        full = np.zeros((3, 3) + sig.shape[2:])
        full[:2, :2] = sig
        if isinstance(model.formulation, PlaneStrain):
            full[2, 2] = lam * trace(E) / np.linalg.det(np.moveaxis(F, (0, 1), (-2, -1)))
        sig = full
    return von_mises(nodal_average(model, sig)), von_mises(sig).max(axis=1)


def geometric_stiffness(model: Model, u: np.ndarray) -> sp.csr_matrix:
    """Initial-stress (geometric) stiffness K_sigma (N/m) of the linear stress of ``u``:
    K_sigma(du, v) = t int grad v . sigma . grad du^T dX, on the mass-matrix quadrature
    (exact for sigma of degree order - 1), on the model's node pattern
    (:func:`.assembly.geometric_stiffness`). (K + K_sigma) is the tangent about a prestressed
    reference configuration."""
    mesh = model.cell_mesh
    stress = model.stress(u)[:model.dim, :model.dim]  # (dim, dim, e, q) on model.quadrature
    return assembly.geometric_stiffness(mesh, scalar_element(mesh, model.order), model.quadrature,
                                        model.node_pattern, model.dim, stress, model.thickness)


def max_strain(model: Model, u: np.ndarray) -> float:
    """Largest absolute principal Green-Lagrange strain (-) of state ``u`` over the stiffness
    quadrature points."""
    E = green_lagrange(deformation(model.stiffness_basis, u))
    eig = np.linalg.eigvalsh(np.moveaxis(E, (0, 1), (-2, -1)))
    return float(np.abs(eig).max())
