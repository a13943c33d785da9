"""The total-Lagrangian bilinear quad of a structured grid, St. Venant-Kirchhoff, vectorised
over the elements: internal forces and consistent tangents for a modulus of 1 Pa, and the
energy interpolation that keeps near-void elements linear.

The material is flexfem's continuum one (fem/hyperelastic.py: S = lam tr(E) I + 2 mu E) with
the plane-stress Lame constants lam = E nu / (1 - nu^2), mu = E / (2 (1 + nu)), so that the
small-displacement limit is exactly the linear plane-stress element (element.py).
"""
import numpy as np

from .element import CORNERS, GAUSS

# the energy interpolation's switch: Wang, Lazarov, Sigmund & Jensen 2014 (Comput Methods Appl
# Mech Engrg 276:453-472, doi:10.1016/j.cma.2014.03.021), its Heaviside of the density
GAMMA_SHARPNESS = 500.0
GAMMA_THRESHOLD = 0.01


def shape_gradients(dx: float, dy: float) -> np.ndarray:
    """dN_a/dX_j (1/m) at the 2 x 2 Gauss points of a dx x dy (m) rectangle, (4, 4, 2):
    Gauss point, node (element.py's order), direction."""
    out = np.empty((4, 4, 2))
    for k, (xi, eta) in enumerate((x, e) for x in GAUSS for e in GAUSS):
        out[k, :, 0] = CORNERS[:, 0] * (1.0 + CORNERS[:, 1] * eta) / 4.0 * 2.0 / dx
        out[k, :, 1] = CORNERS[:, 1] * (1.0 + CORNERS[:, 0] * xi) / 4.0 * 2.0 / dy
    return out


class LargeStrainQ4:
    """Internal force and tangent of grid elements of unit modulus, thickness ``thickness``
    (m) and Poisson's ratio ``nu``: ``force_tangent(ue)`` with ue (n, 8) element DOFs (m)."""

    def __init__(self, dx: float, dy: float, nu: float, thickness: float):
        self.G = shape_gradients(dx, dy)
        self.G0 = CORNERS / 2.0 / np.array([dx, dy])     # dN_a/dX_j at the centre
        self.weight = dx * dy / 4.0 * thickness
        self.lam, self.mu = nu / (1.0 - nu**2), 1.0 / (2.0 * (1.0 + nu))

    def force_tangent(self, ue: np.ndarray):
        """(f (n, 8) N, K (n, 8, 8) N/m, each element's smallest det F (n,)) for modulus
        1 Pa."""
        U = ue.reshape(-1, 4, 2)
        f = np.zeros_like(U)
        K = np.zeros((U.shape[0], 4, 2, 4, 2))
        I = np.eye(2)
        det = np.full(U.shape[0], np.inf)
        for G in self.G:
            F = I + np.einsum("nai,aj->nij", U, G)
            det = np.minimum(det, F[:, 0, 0] * F[:, 1, 1] - F[:, 0, 1] * F[:, 1, 0])
            C = np.einsum("nki,nkj->nij", F, F)
            E = 0.5 * (C - I)
            S = self.lam * (E[:, 0, 0] + E[:, 1, 1])[:, None, None] * I + 2.0 * self.mu * E
            P = np.einsum("nij,njk->nik", F, S)
            f += self.weight * np.einsum("nij,aj->nai", P, G)
            FG = np.einsum("nij,bj->nbi", F, G)          # F_iJ dN_b/dX_J
            GSG = np.einsum("aj,njl,bl->nab", G, S, G)   # dN_a.S.dN_b
            GG = G @ G.T
            K += self.weight * (
                np.einsum("nab,ik->naibk", GSG, I)
                + self.lam * np.einsum("nai,nbk->naibk", FG, FG)
                + self.mu * np.einsum("nbi,nak->naibk", FG, FG)
                + self.mu * np.einsum("ab,nik->naibk", GG, np.einsum("nim,nkm->nik", F, F)))
        f = f.reshape(-1, 8)
        return f, K.reshape(-1, 8, 8), det


def centre_stress(element: LargeStrainQ4, E0: float, ue: np.ndarray):
    """(von Mises (n,) Pa, d von Mises / d ue (n, 8) Pa/m) of the second Piola-Kirchhoff
    stress S = E0 (lam tr(E) I + 2 mu E) at the element centres, E the Green-Lagrange
    strain: in the small-displacement limit the linear element's centre stress (element.py);
    the derivative is 0 where the stress is."""
    G, I = element.G0, np.eye(2)
    F = I + np.einsum("nai,aj->nij", ue.reshape(-1, 4, 2), G)
    E = 0.5 * (np.einsum("nki,nkj->nij", F, F) - I)
    S = E0 * (element.lam * (E[:, 0, 0] + E[:, 1, 1])[:, None, None] * I + 2 * element.mu * E)
    s11, s22, s12 = S[:, 0, 0], S[:, 1, 1], S[:, 0, 1]
    vm = np.sqrt(np.maximum(s11**2 - s11 * s22 + s22**2 + 3 * s12**2, 0.0))
    # d vm^2 / dS_ij (symmetric S, both off-diagonal entries) and dS/dE, dE/du
    dS = np.stack([2 * s11 - s22, 2 * s22 - s11, 3 * s12], axis=1)           # (n, 3)
    dE11 = np.einsum("nm,a->nam", F[:, :, 0], G[:, 0])                       # (n, 4, 2)
    dE22 = np.einsum("nm,a->nam", F[:, :, 1], G[:, 1])
    dE12 = 0.5 * (np.einsum("nm,a->nam", F[:, :, 0], G[:, 1])
                  + np.einsum("nm,a->nam", F[:, :, 1], G[:, 0]))
    lam, mu = E0 * element.lam, E0 * element.mu
    tr = dE11 + dE22
    d_vm2 = (dS[:, 0, None, None] * (lam * tr + 2 * mu * dE11)
             + dS[:, 1, None, None] * (lam * tr + 2 * mu * dE22)
             + dS[:, 2, None, None] * 2 * mu * dE12 * 2)
    d_vm = np.where(vm[:, None] > 0, d_vm2.reshape(-1, 8) / (2 * np.where(vm > 0, vm, 1.0))[:, None],
                    0.0)
    return vm, d_vm


def energy_gamma(rho: np.ndarray):
    """(gamma, d gamma / d rho): 0 for void, 1 for solid, the switch at GAMMA_THRESHOLD."""
    b, r0 = GAMMA_SHARPNESS, GAMMA_THRESHOLD
    den = np.tanh(b * r0) + np.tanh(b * (1.0 - r0))
    t = np.tanh(b * (rho - r0))
    return (np.tanh(b * r0) + t) / den, b * (1.0 - t**2) / den


def interpolated(element: LargeStrainQ4, KL: np.ndarray, ue: np.ndarray, gamma: np.ndarray):
    """The energy interpolation of Wang et al. (2014): an element's energy is
    psi_NL(gamma u) + psi_L(u) - psi_L(gamma u), nonlinear where gamma = 1 (solid), linear
    where gamma = 0 (void, whose distortion would otherwise stop Newton). Returns (g, Kt,
    dg/dgamma) for unit modulus: g = gamma f_NL(gamma u) + (1 - gamma^2) KL u and
    Kt = gamma^2 K_NL(gamma u) + (1 - gamma^2) KL."""
    gu = gamma[:, None] * ue
    fN, KN, _ = element.force_tangent(gu)
    fL = ue @ KL.T
    g2 = gamma**2
    g = gamma[:, None] * fN + (1.0 - g2)[:, None] * fL
    Kt = g2[:, None, None] * KN + (1.0 - g2)[:, None, None] * KL
    dg = fN + gamma[:, None] * np.einsum("nij,nj->ni", KN, ue) - 2.0 * gamma[:, None] * fL
    return g, Kt, dg
