"""Reduced beam model of the eight-bar flexure suspension, generated from its parameters.

    model, info = eightbar_beam_model(EightBarFlexureParams())
    info["end_effector"]        # master node on the "end_effector" face's centroid

Built from the same planar layout as the 2-D continuum model
(:func:`flexfem.geometry.eightbar.flexure.eightbar_layout`): each of the ten flexures is a
beam of its length, in-plane width and root fillets (a tapered section through the fillets),
out-of-plane width ``thickness``; the links (cranks, rockers, couplers, end-effector) are
rigid bodies with their masses; flexures O, C are clamped at their anchors. Root extension:
see :mod:`flexfem.geometry.beam_layout` (0.38 x root thickness per root by default).
"""
from ...fem.materials import material as material_named
from ..beam_layout import ROOT_EXTENSION, layout_beam_model
from .flexure import EightBarFlexureParams, eightbar_layout, end_effector_point

EE_LINK = "end_effector"


def eightbar_beam_model(params: EightBarFlexureParams, n_per_flexure: int = 24,
                        root_extension: float = ROOT_EXTENSION, shear: bool = True) -> tuple:
    """(BeamModel, info) of the suspension in its drawn pose. info: "end_effector" (master
    node of the end-effector link, on its bottom face's centroid), "ground" (clamped nodes),
    "masters" {link: node}, "flexures" {joint: (first, last element)}."""
    layout = eightbar_layout(params)
    model, info = layout_beam_model(
        layout, material_named(params.material), params.thickness,
        fillet_radius=params.root_fillet_radius, n_per_flexure=n_per_flexure,
        root_extension=root_extension, anchors={EE_LINK: end_effector_point(params)},
        shear=shear)
    info["end_effector"] = info["masters"][EE_LINK]
    return model, info
