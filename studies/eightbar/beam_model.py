"""The eight-bar suspension's reduced beam model as a builder for its analyses
(:mod:`.analysis`), and the spatial beam model's modes.

    out = analyze_eightbar(model="beam")        # the continuum's analyses, in milliseconds

The beam model (:func:`flexfem.reduced.eightbar.eightbar_beam_model`) carries the
mesh's groups "fixed" and "end_effector" (a node on the face's centroid, with the face's
extent), so the continuum's loadings apply as they are (:mod:`flexfem.fem.beam.face`): k_x
with the end-effector's x prescribed (y and rotation free: the face is horizontal), k_y with
x held and y prescribed (which holds the face's rotation, as the continuum's every face node
is), the modes with the anchors clamped, the large-deflection path with the face a RigidFace
whose x is prescribed. The flexures' beam stress is |N|/A + |M|c/I (the continuum's von Mises
peak includes the fillet's stress concentration, which beam theory has not). SI units.
"""
import numpy as np

from ...reduced.layout import ROOT_EXTENSION
from ...reduced.eightbar import eightbar_beam_model
from ...geometry.eightbar.flexure import EightBarFlexureParams
from .places import Places

# elements per flexure of the nonlinear stroke's model: its outputs agree with 24 to ~3e-5
# (force, stress) and it solves ~3x faster; the linear and modal solves keep 24 (above 800
# unknowns the modes use the sparse shift-invert solver, well conditioned here)
STROKE_ELEMENTS = 12


def beam_model(params: EightBarFlexureParams, n_per_flexure: int = 24,
               root_extension: float | None = None, stroke: bool = False) -> tuple:
    """(BeamModel with the mesh's groups, Places, facts {"root_extension"}); ``stroke``: at
    most STROKE_ELEMENTS elements a flexure (the large-deflection path's model)."""
    extension = ROOT_EXTENSION if root_extension is None else float(root_extension)
    n = min(n_per_flexure, STROKE_ELEMENTS) if stroke else n_per_flexure
    model, info = eightbar_beam_model(params, n, extension)

    def peak(result):
        e, _, where = result.state.max_stress_location
        return {"x": float(where[0]), "y": float(where[1]), "flexure": _flexure_of(info, e)}

    return model, Places(peak, lambda result, e: _flexure_of(info, e)), {
        "root_extension": extension}


def _flexure_of(info, element: int) -> str:
    for joint, (a, b) in info["flexures"].items():
        if a <= element < b:
            return f"flexure_{joint}"
    return "unknown"


def spatial_beam_modes(params: EightBarFlexureParams, n: int = 4,
                       root_extension: float = ROOT_EXTENSION) -> list:
    """modal_analysis' rows from the spatial beam model (flexible links, the flexures'
    torsion with Vlasov's warping restraint; docs/beam.md), with "m_eff_z_kg", as the 3-D
    FEM's."""
    from .eightbar_modes3d import beam_modes as spatial

    out = spatial(params, n, warping=True, root_extension=root_extension)
    mass = np.array(out["mass_fraction"]) * out["total_mass_kg"]
    return [{"f_hz": float(f), "m_eff_x_kg": float(m[0]), "m_eff_y_kg": float(m[1]),
             "m_eff_z_kg": float(m[2])} for f, m in zip(out["f_hz"], mass)]
