"""Stresses of the spatial beam model from its element forces: the largest normal stress of
each rectangular section (axial force and both bending moments, at a corner) and its largest
Saint-Venant torsion shear stress (middle of the long sides), along each element.

The moments vary linearly along an element (no distributed load): M(0) = -M1, M(L) = M2 for
the end moments M1, M2 acting on it (the planar model's convention, fem/beam/element.py).
"""
import numpy as np

from ..section import rect_torsion_shear


def section_stresses(model, local_forces: np.ndarray, n_points: int = 5) -> dict:
    """Stresses (Pa) at ``n_points`` fractions ``xi`` along every element, each (n_e, k):
    'normal' |N| / A + |M_y| d_z / (2 I_y) + |M_z| d_y / (2 I_z), the largest normal stress of
    the rectangle (at a corner); 'torsion' the largest Saint-Venant shear stress |T| tau_1
    (:func:`..section.rect_torsion_shear`); 'von_mises' sqrt(normal^2 + 3 torsion^2), an upper
    bound of the section's largest von Mises stress (the two peaks lie at different points;
    the shear of the transverse forces is left out, as in the planar model). NaN for general
    sections (no depths). local_forces: (n_e, 7) as Beam3DState.local_forces."""
    xi = np.linspace(0.0, 1.0, n_points)
    s = model.section_at(xi)
    dy, dz = s["depth_y"], s["depth_z"]
    f = np.asarray(local_forces, dtype=float)
    T, My, Mz = (-f[:, k:k + 1] * (1.0 - xi) + f[:, k + 3:k + 4] * xi for k in (1, 2, 3))
    normal = (np.abs(f[:, 0:1]) / s["A"] + np.abs(My) * dz / (2.0 * s["Iy"])
              + np.abs(Mz) * dy / (2.0 * s["Iz"]))
    torsion = np.abs(T) * rect_torsion_shear(dy, dz)
    return {"xi": xi, "normal": normal, "torsion": torsion,
            "von_mises": np.sqrt(normal**2 + 3.0 * torsion**2)}


def peak_stress(model, local_forces: np.ndarray) -> tuple:
    """(largest von Mises bound (Pa), its element, its xi) of :func:`section_stresses`; NaN
    and -1 where no element has a rectangular section."""
    stresses = section_stresses(model, local_forces)
    vm = np.nan_to_num(stresses["von_mises"], nan=-1.0)
    e, k = np.unravel_index(int(np.argmax(vm)), vm.shape)
    if vm[e, k] < 0:
        return float("nan"), -1, float("nan")
    return float(vm[e, k]), int(e), float(stresses["xi"][k])
