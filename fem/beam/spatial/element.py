"""The spatial beam element in its local frame: linear stiffness and consistent mass.

Local DOFs per node (u, v, w, r_x, r_y, r_z) along the element's axes (x along it). Axial
bar (EA), Saint-Venant torsion (GJ) and two bending planes: x-y (v, r_z; Iz, shear area
Ay) and x-z (w, r_y; Iy, Az, with r_y = -dw/dx). Each bending plane is the planar element's
(fem/beam/element.py): the stiffness the inverse of the exact flexibility (exact in statics
for tapered sections too), the mass from the interdependent-interpolation shape functions
(Friedman & Kosmatka 1993), exact for a prismatic Timoshenko beam; no shear area:
Euler-Bernoulli. The consistent mass holds translational (rho A), rotary (rho Iy, rho Iz)
and torsional (rho Ip, Ip = Iy + Iz) inertia. Sections may be
rectangles tapered along local y (model.Section.rect), as the planar model's.
"""
import numpy as np

from ..element import WXI, XI, bending_shape_functions, bending_stiffness

XY = [1, 5, 7, 11]   # (v1, rz1, v2, rz2)
XZ = [2, 4, 8, 10]   # (w1, ry1, w2, ry2)
XZ_SIGN = np.array([1.0, -1.0, 1.0, -1.0])  # r_y = -dw/dx
AXIAL, TORSION = [0, 6], [3, 9]
BASIC = [6, 3, 4, 5, 9, 10, 11]  # (u2, r1, r2): natural deformations about the chord


def _bending(E, I, G, As, I_mid, rho, A, A_mid, L, factors=(1.0, 1.0)):
    """(n_e, 4, 4) stiffness and mass of one bending plane (planar DOF order v, theta); I,
    A (n_e, k) at the Gauss points; phi from the mid-length I_mid and the shear area As (of
    the mid-length section A_mid, following A along a tapered element, as the planar
    model's kappa A); ``factors`` (bending, shear) multiply E I and G As in the stiffness."""
    fb, fs = (np.broadcast_to(np.asarray(f, dtype=float), L.shape) for f in factors)
    As = fs * As  # the planar model's shear factor, in the mass's shape functions too
    phi = np.where(np.isfinite(As), 12.0 * E * I_mid / (G * As * L**2), 0.0)
    Nw, _, Np, _ = bending_shape_functions(XI, L, phi)
    wdx = WXI[None, :] * L[:, None]
    K = bending_stiffness(fb[:, None] * E * I, (G * As / A_mid)[:, None] * A,
                          L)  # As inf: no shear
    M = (np.einsum("eg,egi,egj->eij", rho * A * wdx, Nw, Nw)
         + np.einsum("eg,egi,egj->eij", rho * I * wdx, Np, Np))
    return K, M


def put_block(target, idx, block, sign=None):
    if sign is not None:
        block = block * sign[None, :, None] * sign[None, None, :]
    target[:, np.array(idx)[:, None], np.array(idx)[None, :]] += block


def local_matrices(model):
    """(K, M): (n_e, 12, 12) linear stiffness (N/m, N, N m) and consistent mass (kg,
    kg m, kg m^2) of every element in its local frame, integrated by 6-point Gauss
    quadrature along it (exact for the planar model's tapers in bending; the axial and
    torsional stiffnesses E / mean(1 / A), G / mean(1 / J))."""
    s, mid, L = model.section_at(XI), model.section_at([0.5]), model.lengths
    shear = model.section_table()
    mat = model.material
    E, rho = mat.E, mat.density_or_nan
    G = E / (2.0 * (1.0 + mat.nu))
    n = model.n_elements
    K, M = np.zeros((n, 12, 12)), np.zeros((n, 12, 12))
    bar = np.array([[1.0, -1.0], [-1.0, 1.0]])
    Nu = np.stack([1.0 - XI, XI], axis=-1)
    wdx = WXI[None, :] * L[:, None]
    factors = shear["factors"]
    put_block(K, AXIAL, (E * factors[:, 2] / ((WXI / s["A"]).sum(axis=1) * L))[:, None, None] * bar)
    put_block(M, AXIAL, np.einsum("eg,gi,gj->eij", rho * s["A"] * wdx, Nu, Nu))
    put_block(K, TORSION, (G / ((WXI / s["J"]).sum(axis=1) * L))[:, None, None] * bar)
    put_block(M, TORSION, np.einsum("eg,gi,gj->eij", rho * s["Ip"] * wdx, Nu, Nu))
    A_mid = mid["A"][:, 0]
    Kz, Mz = _bending(E, s["Iz"], G, shear["Ay"], mid["Iz"][:, 0], rho, s["A"], A_mid, L,
                      (factors[:, 0], factors[:, 1]))
    put_block(K, XY, Kz)
    put_block(M, XY, Mz)
    Ky, My = _bending(E, s["Iy"], G, shear["Az"], mid["Iy"][:, 0], rho, s["A"], A_mid, L,
                      (factors[:, 3], 1.0))
    put_block(K, XZ, Ky, XZ_SIGN)
    put_block(M, XZ, My, XZ_SIGN)
    return K, M * shear["mass_factor"][:, None, None]


def basic_stiffness(model) -> np.ndarray:
    """(n_e, 7, 7) stiffness of the natural deformations (extension, rotation vectors of
    the two ends relative to the co-rotated frame): the local stiffness with node 1 and
    the lateral translations of node 2 held."""
    K, _ = local_matrices(model)
    idx = np.array(BASIC)
    return K[:, idx[:, None], idx[None, :]]


def to_global(frames) -> np.ndarray:
    """(n_e, 12, 12) block-diagonal E with global = E @ local (frames: (n_e, 3, 3))."""
    Eb = np.zeros((len(frames), 12, 12))
    for k in range(4):
        Eb[:, 3 * k:3 * k + 3, 3 * k:3 * k + 3] = frames
    return Eb
