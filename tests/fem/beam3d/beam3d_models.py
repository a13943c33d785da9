"""Spatial beam models the beam3d tests share."""
import numpy as np

from flexfem.fem.beam.spatial import Beam3DModel


def straight(material, section, length=0.1, n=20, direction=(1.0, 0.0, 0.0),
             orientation=None, **options):
    """Straight beam of ``n`` elements from the origin along ``direction``: (model, tip)."""
    d = np.asarray(direction, dtype=float)
    nodes = np.linspace(0.0, length, n + 1)[:, None] * (d / np.linalg.norm(d))
    elements = np.column_stack([np.arange(n), np.arange(1, n + 1)])
    return Beam3DModel(nodes, elements, section, material, orientation=orientation,
                       **options), n


def closed_form_tip_compliance(material, section, length, shear=False) -> np.ndarray:
    """6x6 tip compliance of a cantilever along local x in its local axes: axial L/EA,
    bending L^3/3EI (+ L/(G A_s)), rotation L/EI, couplings +L^2/2EIz (v, r_z) and
    -L^2/2EIy (w, r_y), torsion L/GJ."""
    E, L = material.E, length
    G = E / (2.0 * (1.0 + material.nu))
    C = np.zeros((6, 6))
    C[0, 0] = L / (E * section.A)
    C[1, 1] = L**3 / (3 * E * section.Iz) + (L / (G * section.Ay) if shear else 0.0)
    C[2, 2] = L**3 / (3 * E * section.Iy) + (L / (G * section.Az) if shear else 0.0)
    C[3, 3] = L / (G * section.J)
    C[4, 4] = L / (E * section.Iy)
    C[5, 5] = L / (E * section.Iz)
    C[1, 5] = C[5, 1] = L**2 / (2 * E * section.Iz)
    C[2, 4] = C[4, 2] = -L**2 / (2 * E * section.Iy)
    return C
