"""The bilinear plane-stress quadrilateral (Q4) of a structured grid."""
import numpy as np

# node order: bottom-left, bottom-right, top-right, top-left; DOFs (x, y) per node
CORNERS = np.array([(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)])
GAUSS = np.array([-1.0, 1.0]) / np.sqrt(3.0)


def plane_stress_matrix(E: float, nu: float) -> np.ndarray:
    """The 3x3 plane-stress elasticity matrix (Pa), Voigt order xx, yy, xy (engineering)."""
    return E / (1.0 - nu**2) * np.array([[1.0, nu, 0.0], [nu, 1.0, 0.0],
                                         [0.0, 0.0, (1.0 - nu) / 2.0]])


def strain_displacement(dx: float, dy: float, xi: float, eta: float) -> np.ndarray:
    """B (3x8, 1/m) of a dx x dy (m) rectangle at the natural point (xi, eta)."""
    dN_dxi = CORNERS[:, 0] * (1.0 + CORNERS[:, 1] * eta) / 4.0
    dN_deta = CORNERS[:, 1] * (1.0 + CORNERS[:, 0] * xi) / 4.0
    dN_dx, dN_dy = dN_dxi * 2.0 / dx, dN_deta * 2.0 / dy
    B = np.zeros((3, 8))
    B[0, 0::2] = dN_dx
    B[1, 1::2] = dN_dy
    B[2, 0::2] = dN_dy
    B[2, 1::2] = dN_dx
    return B


def element_stiffness(dx: float = 1.0, dy: float = 1.0, E: float = 1.0, nu: float = 0.3,
                      thickness: float = 1.0) -> np.ndarray:
    """KE (8x8, N/m) of a dx x dy (m) rectangle, 2x2 Gauss (exact for Q4). For a unit square
    with E = 1 it is top88's ``lk()``."""
    D = plane_stress_matrix(E, nu)
    KE = np.zeros((8, 8))
    for xi in GAUSS:
        for eta in GAUSS:
            B = strain_displacement(dx, dy, xi, eta)
            KE += B.T @ D @ B * (dx * dy / 4.0)
    return KE * thickness


def element_mass(dx: float = 1.0, dy: float = 1.0, thickness: float = 1.0) -> np.ndarray:
    """The consistent mass matrix (8x8, kg per kg/m^3) of a dx x dy (m) rectangle of unit
    mass density: rho t dx dy / 36 [4 2 1 2; 2 4 2 1; 1 2 4 2; 2 1 2 4] for x and y each."""
    m4 = np.array([[4.0, 2.0, 1.0, 2.0], [2.0, 4.0, 2.0, 1.0], [1.0, 2.0, 4.0, 2.0],
                   [2.0, 1.0, 2.0, 4.0]]) * (dx * dy * thickness / 36.0)
    return np.kron(m4, np.eye(2))


def von_mises_matrix(dx: float, dy: float, E: float, nu: float) -> np.ndarray:
    """S (8x8, Pa^2 per m^2) with u_e^T S u_e = the von Mises stress squared at the centre of
    a dx x dy (m) rectangle of modulus E (Pa) in plane stress."""
    DB = plane_stress_matrix(E, nu) @ strain_displacement(dx, dy, 0.0, 0.0)
    V = np.array([[1.0, -0.5, 0.0], [-0.5, 1.0, 0.0], [0.0, 0.0, 3.0]])
    return DB.T @ V @ DB
