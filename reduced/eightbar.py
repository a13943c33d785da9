"""Reduced beam model of the eight-bar flexure suspension, generated from its parameters.

    model, info = eightbar_beam_model(EightBarFlexureParams())
    info["end_effector"]        # master node on the "end_effector" face's centroid

Built from the same planar layout as the 2-D continuum model
(:func:`flexfem.geometry.eightbar.flexure.eightbar_layout`): each of the ten flexures is a
beam of its length, in-plane width and root fillets (a tapered section through the fillets),
out-of-plane width ``thickness``; the links (cranks, rockers, couplers, end-effector) are
rigid bodies with their masses; flexures O, C are clamped at their anchors. Root extension:
see :mod:`flexfem.reduced.layout` (0.38 x root thickness per root by default).
"""
from dataclasses import fields
import functools

import numpy as np

from ..fem.materials import material as material_named
from .layout import ROOT_EXTENSION, layout_beam_model
from ..geometry.eightbar.flexure import EightBarFlexureParams, eightbar_layout

EE_LINK = "end_effector"
# the material library is a data file read on each lookup; a sweep builds thousands of models
_material = functools.lru_cache(maxsize=16)(material_named)


def unchecked_params(base: EightBarFlexureParams, **changes) -> EightBarFlexureParams:
    """``base`` with ``changes`` (its own fields) *without* the validity checks of
    EightBarFlexureParams (the clearance check over the travel costs ~0.4 s, four times the
    beam model's linear design point): for large sweeps of the beam model only. A design a
    sweep keeps must be rebuilt with ``dataclasses.replace`` (which checks it) before it is
    trusted; an infeasible layout still raises ValueError when the model is built."""
    params = object.__new__(EightBarFlexureParams)
    for f in fields(EightBarFlexureParams):
        value = changes.pop(f.name, getattr(base, f.name))
        object.__setattr__(params, f.name, float(value) if isinstance(value, int) else value)
    if changes:
        raise ValueError(f"unknown eight-bar parameter(s) {sorted(changes)}")
    return params


def eightbar_beam_model(params: EightBarFlexureParams, n_per_flexure: int = 24,
                        root_extension: float = ROOT_EXTENSION, shear: bool = True) -> tuple:
    """(BeamModel, info) of the suspension in its drawn pose, with the continuum mesh's groups
    "fixed" (the anchors' clamped nodes) and "end_effector" (the end-effector link's master,
    on its bottom face's centroid, with that face's extent). info: "end_effector",
    "ground" (clamped nodes), "masters" {link: node}, "flexures" {joint: (first, last
    element)}."""
    layout = eightbar_layout(params)
    edge = np.asarray(layout.edges["end_effector"], float)
    face = edge.mean(axis=0)  # end_effector_point
    model, info = layout_beam_model(
        layout, _material(params.material), params.thickness,
        fillet_radius=params.root_fillet_radius, n_per_flexure=n_per_flexure,
        root_extension=root_extension, anchors={EE_LINK: face}, shear=shear)
    info["end_effector"] = info["masters"][EE_LINK]
    model.add_group("fixed", info["ground"])
    model.add_group("end_effector", [info["end_effector"]], edge[-1] - edge[0])
    return model, info
