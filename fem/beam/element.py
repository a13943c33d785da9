"""The planar beam element: local stiffness and mass, and Crisfield's co-rotational kinematics.

Local element: axial bar + bending. The bending stiffness is the inverse of the element's
exact flexibility (:func:`bending_stiffness`: with no load along it the moment is linear and
the shear constant, whatever the section does), so a tapered element, with or without
Timoshenko shear, is exact in statics up to the quadrature of 1 / EI and 1 / kappa G A; for
a prismatic one it is the classical element. The consistent mass (translational + rotary
inertia) uses the interdependent-interpolation (IIE) shape functions of Friedman & Kosmatka
(1993), exact for a prismatic Timoshenko beam (phi = 12 E I / (kappa G A L^2) from the
mid-length section; phi = 0: the cubic Hermite functions). Integrals along an element use
6-point Gauss quadrature.
The co-rotational element (Crisfield, Non-linear Finite Element Analysis of Solids and
Structures, vol. 1, sec. 7.3) carries the basic forces (N, M1, M2) of the local element's
natural deformations (extension, end rotations relative to the chord).
"""
from functools import lru_cache

import numpy as np

from .section import AXIAL_FACTOR, BENDING_FACTOR, MASS_FACTOR

GAUSS_X, GAUSS_W = np.polynomial.legendre.leggauss(6)
XI = 0.5 * (GAUSS_X + 1.0)
WXI = 0.5 * GAUSS_W
_MOMENT_SHAPES = np.stack([XI - 1.0, XI], axis=-1)  # (6, 2) M / (M1, M2) at the Gauss points
_AXIAL_SHAPES = np.stack([1.0 - XI, XI], axis=-1)  # (6, 2) the bar's linear shape functions
STRESS_POINTS = np.linspace(0.0, 1.0, 5)  # where along an element bending_stress looks
# every fraction along an element where the functions here read its section: the Gauss
# points and the stress points (the ends, the middle among them), one section_at for all;
# the columns of each set read (a slice of them: no copy)
_POINTS = np.concatenate([XI, STRESS_POINTS])
_COLUMNS = {tuple(XI.tolist()): slice(0, 6), tuple(STRESS_POINTS.tolist()): slice(6, 11),
            (0.0, 1.0): slice(6, 11, 4), (0.5,): slice(8, 9)}


def bending_shape_functions(xi, L, phi):
    """IIE shape functions at xi (k,) for (n_e,) elements: N_w, dN_w/dx, N_psi, dN_psi/dx,
    each (n_e, k, 4) for DOFs (v1, theta1, v2, theta2)."""
    Nw, Np = shape_values(xi, L, phi)
    dNw, dNp = _shape_slopes(xi, L, phi)
    return Nw, dNw, Np, dNp


# the IIE shape functions' polynomials in x = xi: f (C0 + phi C1) [1, x, x^2, x^3], each row
# scaled by (f, f L, f, f L, 6 f / L, f, 6 f / L, f), f = 1 / (1 + phi): N_w's four, N_psi's
_SHAPE_C0 = np.array([[1, 0, -3, 2], [0, 1, -2, 1], [0, 0, 3, -2], [0, 0, -1, 1],
                      [0, -1, 1, 0], [1, -4, 3, 0], [0, 1, -1, 0], [0, -2, 3, 0]], float)
_SHAPE_C1 = np.array([[1, -1, 0, 0], [0, 0.5, -0.5, 0], [0, 1, 0, 0], [0, -0.5, 0.5, 0],
                      [0, 0, 0, 0], [1, -1, 0, 0], [0, 0, 0, 0], [0, 1, 0, 0]], float)


def shape_values(xi, L, phi):
    """(N_w, N_psi) of :func:`bending_shape_functions`, each (n_e, k, 4), as polynomials
    (one product for all eight: the mass needs no slopes)."""
    f = 1.0 / (1.0 + phi)
    scale = np.stack([f, f * L, f, f * L, 6.0 * f / L, f, 6.0 * f / L, f], axis=1)
    powers = np.asarray(xi, dtype=float)[None, :] ** np.arange(4)[:, None]  # (4, k)
    N = ((_SHAPE_C0 + phi[:, None, None] * _SHAPE_C1) @ powers) * scale[:, :, None]
    N = N.transpose(0, 2, 1)  # (n_e, k, 8)
    return N[:, :, :4], N[:, :, 4:]


def _shape_slopes(xi, L, phi):
    """(dN_w/dx, dN_psi/dx) of :func:`bending_shape_functions`."""
    x = xi[None, :]
    L_, p = L[:, None], phi[:, None]
    f = 1.0 / (1.0 + p)
    dNw = np.stack([f * (6 * x**2 - 6 * x - p) / L_,
                    f * (3 * x**2 - (4 + p) * x + 1 + p / 2),
                    -f * (6 * x**2 - 6 * x - p) / L_,
                    f * (3 * x**2 - (2 - p) * x - p / 2)], axis=-1)
    dNp = np.stack([6 * f * (2 * x - 1) / L_**2,
                    f * (6 * x - 4 - p) / L_,
                    -6 * f * (2 * x - 1) / L_**2,
                    f * (6 * x - 2 + p) / L_], axis=-1)
    return dNw, dNp


def gram(weight, A, B) -> np.ndarray:
    """sum_g weight[e, g] A[e, g, i] B[e, g, j]: (n_e, i, j) (einsum's, by matmul)."""
    return np.matmul((A * weight[:, :, None]).transpose(0, 2, 1), B)


def sections(model, xi):
    """model.section_at(xi) at the fixed point sets used here (Gauss points, ends, middle,
    stress points), cached: columns of one section_at at all of them (_POINTS) on the
    distinct elements (the same numbers: a section's are computed point by point)."""
    key = tuple(np.asarray(xi, dtype=float).tolist())
    return model.cached(("section_at", key), lambda: _sections(model, key))


def _sections(model, xi: tuple):
    if xi not in _COLUMNS:
        return model.section_at(np.array(xi))
    if not isinstance(model, _Distinct):
        distinct = _distinct(model)
        return tuple(a[distinct.inverse] for a in sections(distinct, xi))
    table = model.cached("section_at_points", lambda: model.section_at(_POINTS))
    return tuple(a[:, _COLUMNS[xi]] for a in table)


BEND = [1, 2, 4, 5]  # local DOFs (v1, theta1, v2, theta2) in (u1, v1, theta1, u2, v2, theta2)
AXIAL = [0, 3]


def shear_parameter(model) -> np.ndarray:
    """phi = 12 E I / (kappa G A L^2) per element, from the mid-length section (0 without
    shear)."""
    if not model.shear:
        return np.zeros(model.n_elements)
    mat = model.material
    G = mat.E / (2.0 * (1.0 + mat.nu))
    A, I, _ = sections(model, [0.5])
    kappa = model.section_table[:, 7]
    return 12.0 * mat.E * I[:, 0] / (kappa * G * A[:, 0] * model.lengths**2)


def axial_stiffness(model) -> np.ndarray:
    """EA / L per element as E / int_0^L ds / A(s): exact (logarithmic mean) for a linear
    taper, 6-point Gauss quadrature of 1 / A for a quadratic one."""
    A, _, _ = sections(model, [0.0, 1.0])
    a0, a1 = A[:, 0], A[:, 1]
    ratio = a1 / a0
    close = np.abs(ratio - 1.0) < 1e-6
    mean = np.where(close, 0.5 * (a0 + a1), (a1 - a0) / np.log(np.where(close, 2.0, ratio)))
    quadratic = np.isfinite(model.section_table[:, 8])
    if quadratic.any():
        A_g, _, _ = sections(model, XI)
        mean = np.where(quadratic, 1.0 / (WXI / A_g).sum(axis=1), mean)
    return model.material.E * model.section_table[:, AXIAL_FACTOR] * mean / model.lengths


class _Distinct:
    """The distinct elements of a model (the same section row and length, bit for bit), which
    the local matrices are computed for once each (the DBMA's 16 hinges share one profile):
    the model's fields the local matrices read, for those elements; ``inverse`` maps every
    element to its representative."""

    def __init__(self, model):
        key = np.column_stack([model.section_table, model.lengths])
        key[np.isnan(key)] = -1.0  # one NaN (no field is -1)
        key = key.view(np.int64)  # the numbers' bits: equal rows, equal bits
        # rows grouped by a hash (np.unique by rows sorts ~10x slower), checked exactly
        with np.errstate(over="ignore"):
            h = key @ _mix(key.shape[1])  # wraps around as the products' sum would
        _, first, inverse = np.unique(h, return_index=True, return_inverse=True)
        if not np.array_equal(key[first][inverse.ravel()], key):  # a collision: no grouping
            first, inverse = np.arange(len(key)), np.arange(len(key))
        self.inverse = inverse.ravel()
        self.lengths, self.section_table = model.lengths[first], model.section_table[first]
        self.material, self.shear, self.n_elements = model.material, model.shear, len(first)
        self._model_type = type(model)

    def cached(self, key, compute):
        return self._model_type.cached(self, key, compute)

    def section_at(self, xi):
        return self._model_type.section_at(self, xi)


@lru_cache(maxsize=4)
def _mix(width: int) -> np.ndarray:
    """The hash's fixed odd multipliers, one per key column (read-only)."""
    mix = np.random.default_rng(0).integers(1, 2**62, width) | 1
    mix.setflags(write=False)
    return mix


def _distinct(model) -> _Distinct:
    return model.cached("distinct_elements", lambda: _Distinct(model))


def local_stiffness(model) -> np.ndarray:
    """(n_e, 6, 6) linear stiffness in each element's local frame (N/m, N, N m)."""
    distinct = _distinct(model)
    return _local_stiffness(distinct)[distinct.inverse]


def bending_stiffness(EI, kGA, L) -> np.ndarray:
    """(n_e, 4, 4) bending stiffness (N/m, N, N m) for the DOFs (v1, theta1, v2, theta2) of
    elements of length L (n_e,) m whose EI (N m^2) and kappa G A (N) (n_e, 6) at the Gauss
    points XI may vary along them (kGA None: no shear deformation). With no load along an
    element its moment is linear, M = (xi - 1) M1 + xi M2, and its shear (M1 + M2) / L
    constant, so the flexibility of the end moments is exact (up to the quadrature):
    f = int b b^T / EI dx + int dx / (kappa G A L^2) [1 1; 1 1], b = (xi - 1, xi). Its
    inverse acts on the end rotations relative to the chord, theta_i - (v2 - v1) / L."""
    n = len(L)
    wdx = WXI[None, :] * L[:, None]
    b = np.broadcast_to(_MOMENT_SHAPES, (n, len(XI), 2))
    f = gram(wdx / EI, b, b)
    if kGA is not None:
        f = f + ((wdx / kGA).sum(axis=1) / L**2)[:, None, None]
    chord = np.zeros((n, 2, 4))  # basic deformations from the DOFs
    chord[:, :, 0], chord[:, :, 2] = (1.0 / L)[:, None], (-1.0 / L)[:, None]
    chord[:, 0, 1] = chord[:, 1, 3] = 1.0
    return np.matmul(chord.transpose(0, 2, 1), np.linalg.inv(f) @ chord)


def _local_stiffness(model) -> np.ndarray:
    mat = model.material
    A, I, _ = sections(model, XI)
    kGA = None
    if model.shear:
        G = mat.E / (2.0 * (1.0 + mat.nu))
        kGA = model.section_table[:, 7][:, None] * G * A
    EI = mat.E * model.section_table[:, BENDING_FACTOR, None] * I
    Kb = bending_stiffness(EI, kGA, model.lengths)
    K = np.zeros((model.n_elements, 6, 6))
    K[:, np.array(BEND)[:, None], np.array(BEND)[None, :]] = Kb
    ea = axial_stiffness(model)
    K[:, 0, 0] = K[:, 3, 3] = ea
    K[:, 0, 3] = K[:, 3, 0] = -ea
    return K


def basic_stiffness(model) -> np.ndarray:
    """(n_e, 3, 3) stiffness of the natural deformations (extension, theta1, theta2) about
    the chord: the local stiffness with node 1 and v2 held."""
    K = local_stiffness(model)
    idx = np.array([3, 2, 5])
    return K[:, idx[:, None], idx[None, :]]


def local_mass(model) -> np.ndarray:
    """(n_e, 6, 6) consistent mass in the local frame (kg, kg m, kg m^2): translational
    rho A and rotary inertia rho I, with the same shape functions as the stiffness."""
    distinct = _distinct(model)
    return _local_mass(distinct)[distinct.inverse]


def _local_mass(model) -> np.ndarray:
    L, rho = model.lengths, model.material.density
    phi = shear_parameter(model)
    A, I, _ = sections(model, XI)
    Nw, Np = shape_values(XI, L, phi)
    wdx = WXI[None, :] * L[:, None]
    Mb = gram(rho * A * wdx, Nw, Nw) + gram(rho * I * wdx, Np, Np)
    Ma = np.einsum("eg,gi,gj->eij", rho * A * wdx, _AXIAL_SHAPES, _AXIAL_SHAPES)
    M = np.zeros((model.n_elements, 6, 6))
    M[:, np.array(BEND)[:, None], np.array(BEND)[None, :]] = Mb
    M[:, np.array(AXIAL)[:, None], np.array(AXIAL)[None, :]] = Ma
    return M * model.section_table[:, MASS_FACTOR, None, None]


def rotation_to_global(angles) -> np.ndarray:
    """(n_e, 6, 6) T with local = T @ global for element chord angles (rad)."""
    c, s = np.cos(angles), np.sin(angles)
    T = np.zeros((len(angles), 6, 6))
    for k in (0, 3):
        T[:, k, k] = T[:, k + 1, k + 1] = c
        T[:, k, k + 1] = s
        T[:, k + 1, k] = -s
        T[:, k + 2, k + 2] = 1.0
    return T


def wrap(angle):
    """Angle wrapped to (-pi, pi]."""
    return np.arctan2(np.sin(angle), np.cos(angle))


def corotational(model, Kb, q, tangent=True):
    """Internal forces and tangents of all elements at nodal DOFs ``q`` (n_nodes, 3).

    Returns f (n_e, 6) global element forces, K (n_e, 6, 6) tangent stiffness (None if not
    ``tangent``) and the basic forces (n_e, 3): N (N, tension > 0), M1, M2 (N m, end
    moments acting on the element, counter-clockwise)."""
    e = model.elements
    D = model.nodes[e[:, 1]] - model.nodes[e[:, 0]]
    du = q[e[:, 1], :2] - q[e[:, 0], :2]
    d = D + du  # chord; Ln^2 - L0^2 from the differences, accurate for small strains
    Ln = np.hypot(d[:, 0], d[:, 1])
    L0 = model.lengths
    stretch = (2.0 * np.einsum("ei,ei->e", D, du) + np.einsum("ei,ei->e", du, du)) / (Ln + L0)
    c, s = d[:, 0] / Ln, d[:, 1] / Ln
    beta = np.arctan2(d[:, 1], d[:, 0])
    rigid = wrap(beta - model.angles)
    strain = np.stack([stretch,
                       wrap(q[e[:, 0], 2] - rigid), wrap(q[e[:, 1], 2] - rigid)], axis=1)
    fb = np.einsum("eij,ej->ei", Kb, strain)
    z0 = np.zeros_like(c)
    r = np.stack([-c, -s, z0, c, s, z0], axis=1)
    zv = np.stack([s, -c, z0, -s, c, z0], axis=1)
    B = np.empty((len(c), 3, 6))
    B[:, 0] = r
    B[:, 1] = -zv / Ln[:, None]
    B[:, 2] = -zv / Ln[:, None]
    B[:, 1, 2] += 1.0
    B[:, 2, 5] += 1.0
    f = np.einsum("eij,ei->ej", B, fb)
    if not tangent:
        return f, None, fb
    K = np.matmul(B.transpose(0, 2, 1), Kb @ B)
    K += (fb[:, 0] / Ln)[:, None, None] * np.einsum("ei,ej->eij", zv, zv)
    rz = np.einsum("ei,ej->eij", r, zv)
    K += ((fb[:, 1] + fb[:, 2]) / Ln**2)[:, None, None] * (rz + rz.transpose(0, 2, 1))
    return f, K, fb


def undeformed(model, Kb):
    """:func:`corotational` at q = 0, its (f, K, fb), with less work: no forces, and the
    tangent's terms in the forces vanish (K = B^T Kb B)."""
    e = model.elements
    D = model.nodes[e[:, 1]] - model.nodes[e[:, 0]]
    L = np.hypot(D[:, 0], D[:, 1])
    c, s = D[:, 0] / L, D[:, 1] / L
    z0 = np.zeros_like(c)
    zv = np.stack([s, -c, z0, -s, c, z0], axis=1)
    B = np.empty((len(c), 3, 6))
    B[:, 0] = np.stack([-c, -s, z0, c, s, z0], axis=1)
    B[:, 1] = B[:, 2] = -zv / L[:, None]
    B[:, 1, 2] += 1.0
    B[:, 2, 5] += 1.0
    K = np.matmul(B.transpose(0, 2, 1), Kb @ B)
    return np.zeros((len(c), 6)), K, np.zeros((len(c), 3))


def bending_stress(model, fb, n_points: int = 5):
    """Largest |N/A| + |M| c / I (Pa) per element over ``n_points`` along it (the moment
    is linear between the ends: M(0) = -M1, M(L) = M2). Returns (sigma (n_e,), xi (n_e,))."""
    xi = STRESS_POINTS if n_points == len(STRESS_POINTS) else np.linspace(0.0, 1.0, n_points)
    A, I, c = sections(model, xi)
    M = -fb[:, 1:2] * (1.0 - xi) + fb[:, 2:3] * xi
    sigma = np.abs(fb[:, 0:1]) / A + np.abs(M) * c / I
    k = np.argmax(np.where(np.isnan(sigma), -1.0, sigma), axis=1)  # NaN: no stress (c None)
    rows = np.arange(len(k))
    return sigma[rows, k], xi[k]
