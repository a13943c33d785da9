"""The spatial beam model's part of the linear (eigenvalue) buckling of
:func:`flexfem.fem.beam.buckling.solve_buckling`: its geometric stiffness and prebuckling
system.

About the linear static state, (K + lambda K_g) phi = 0 with each element's consistent
geometric stiffness of its axial force N: N int (v'^2 + w'^2 + u'^2) dx in both bending
planes (each plane's own interpolation, as the planar element's) and Wagner's torsion term
N (I_p / A) int theta_x'^2 dx (the shear centre at the centroid: a doubly symmetric
section), plus the rigid links' second-order term of the prebuckling forces. Torsion and
bending-moment terms are left out: Euler (flexural) and torsional buckling of compressed
members, in and out of the plane, are modelled; lateral-torsional buckling under bending
is not.
"""
import numpy as np

from ..element import WXI, XI, gram, bending_shape_functions
from .assembly import scatter
from .element import AXIAL, TORSION, XY, XZ, XZ_SIGN, put_block, to_global
from .model import Beam3DModel
from .static import linear_solution


def _plane(E, G, I_mid, As, L) -> np.ndarray:
    """(n_e, 4, 4) int N_w'^T N_w' dx of one bending plane (v, theta order); the shear
    parameter from the mid-length I and the shear area As (inf: Euler-Bernoulli)."""
    phi = np.where(np.isfinite(As), 12.0 * E * I_mid / (G * As * L**2), 0.0)
    _, dNw, _, _ = bending_shape_functions(XI, L, phi)
    return gram(WXI[None, :] * L[:, None], dNw, dNw)


def geometric_stiffness(model: Beam3DModel, axial_force) -> np.ndarray:
    """(n_e, 12, 12) element geometric stiffness (N/m, N, N m) in global DOF order for the
    axial forces ``axial_force`` (n_e,) N (tension > 0)."""
    L, mid, table = model.lengths, model.section_at([0.5]), model.section_table()
    E = model.material.E
    G = E / (2.0 * (1.0 + model.material.nu))
    local = np.zeros((model.n_elements, 12, 12))
    put_block(local, XY, _plane(E, G, mid["Iz"][:, 0], table["factors"][:, 1] * table["Ay"], L))
    put_block(local, XZ, _plane(E, G, mid["Iy"][:, 0], table["Az"], L), XZ_SIGN)
    bar = np.array([[1.0, -1.0], [-1.0, 1.0]]) / L[:, None, None]
    put_block(local, AXIAL, bar)
    put_block(local, TORSION, bar * (mid["Ip"][:, 0] / mid["A"][:, 0])[:, None, None])
    local *= np.asarray(axial_force, dtype=float)[:, None, None]
    Eg = to_global(model.frames)
    return np.einsum("eij,ejk,elk->eil", Eg, local, Eg)


def prebuckling(model: Beam3DModel, held, nodal) -> tuple:
    """(linear state, reduced K, reduced K_g, T = dq/dz) of a spatial model under node
    supports ``held`` and loads ``nodal``: K_g the elements' geometric stiffness of the
    state's axial forces plus the rigid links' (symmetrised) second-order term of its forces
    about the reference configuration."""
    state, _, r, K, T, asm = linear_solution(model, held, nodal)
    links = asm.space.constraint_tangent(asm.space.reference()[1], r)
    G_full = scatter(model, geometric_stiffness(model, state.axial_force)) \
        + 0.5 * (links + links.T)
    return state, K, (T.T @ G_full @ T).tocsc(), T
