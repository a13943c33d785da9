"""The DBMA's reduced beam model as a builder for its analyses (:mod:`.analysis`): the planar
beam model with the continuum mesh's groups, and the stress at its hinges' roots."""
from ...reduced.layout import ROOT_EXTENSION
from ...reduced.dbma import dbma_beam_model
from ...geometry.dbma.drawing import DBMALayout
from ...geometry.dbma.params import DBMAParams
from .beam_stress import dbma_fillet_stress, dbma_notch_stress
from .material import dbma_material


def beam_model(p: DBMAParams, layout: DBMALayout | None = None,
               root_extension: float | None = None) -> tuple:
    """(BeamModel with the mesh's groups, peak_stress): ``peak_stress(result)`` the root
    stress of filleted or circular-notch hinges from the nominal beam stress (None for
    sharp leaves: the nominal stress is what the beam model reports)."""
    layout = layout or DBMALayout()
    extension = ROOT_EXTENSION if root_extension is None else root_extension
    model, info = dbma_beam_model(p, layout, extension, material=dbma_material(p))
    peak = {"filleted": lambda r: dbma_fillet_stress(p, layout, r.model, r.state),
            "circular": lambda r: dbma_notch_stress(p, layout, r.model, info, r.state),
            }.get(layout.hinge_profile)
    return model, peak
