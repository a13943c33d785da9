"""The DBMA's reduced beam model as a builder for its analyses (:mod:`.analysis`), and the
beam model's report-level results.

    model, peak = beam_model(paper_design())        # the groups of the continuum's mesh
    static_response(model, 100.0, peak)             # the same analysis as the continuum's

The beam model (:func:`flexfem.reduced.dbma.dbma_beam_model`) carries the mesh's groups
("fixed", "input_a", "input_b", "input", "output"), so the continuum's loadings apply as they
are (:mod:`flexfem.fem.beam.face`): the pads pushed apart with member 11 held; the output
pushed with the pads held along x (a pad face spans y, so its rotation is held too, as the
continuum's every pad node is). The beam stress is |N|/A + |M|c/I: no stress concentration at
the sharp hinge roots, where the continuum's von Mises peak is singular (mesh-dependent); with
filleted hinges the peak is that nominal stress times the shoulder fillet's published K_t,
with circular notches times the neck's K_t from the notch's 2-D model (:mod:`.beam_stress`).
SI units.
"""
import math

import numpy as np

from ...reduced.layout import ROOT_EXTENSION
from ...geometry.dbma.drawing import DBMALayout
from ...geometry.dbma.params import DBMAParams
from .analysis import evaluate, modal_response, output_stiffness, static_response
from .beam_model import beam_model
from .figures import analytical_metrics


def beam_modal3d(p: DBMAParams, layout: DBMALayout, n_modes: int,
                 root_extension: float = ROOT_EXTENSION) -> dict:
    """modal_response's keys from the spatial beam model (in-plane and out-of-plane modes;
    effective_mass n x 3), the hinges' torsion with Vlasov's warping restraint where they
    are leaves ("torsion": "Vlasov" or "Saint-Venant")."""
    from ..mode_pairing import working_index
    from .dbma_modes3d import beam_modes3d

    leaf = layout.hinge_profile == "leaf"
    modes = beam_modes3d(p, layout, n_modes, warping=leaf, root_extension=root_extension)
    fraction = np.array(modes["mass_fraction"])
    k = working_index(modes) + 1
    note = ("out-of-plane modes from the spatial beam model: with Vlasov's warping restraint "
            "on leaf hinges the four lowest within about 3 % of the 3-D solid on the paper's "
            "design, the torsion modes above them up to about 5.5 % high; Saint-Venant torsion "
            "(notch and filleted hinges) reads 12-18 % low on the two lowest and 30-48 % above "
            "(docs/beam.md); decide with --model continuum")
    return {"frequencies_hz": modes["f_hz"],
            "effective_mass": (fraction * modes["total_mass_kg"]).tolist(), "working_mode": k,
            "fn_working": modes["f_hz"][k - 1], "torsion": "Vlasov" if leaf else "Saint-Venant",
            "validity_notes": [note]}


def analyze_dbma_beam(p: DBMAParams, layout: DBMALayout | None = None, force: float = 100.0,
                      n_modes: int = 6, root_extension: float = ROOT_EXTENSION,
                      dim: int = 2) -> dict:
    """Static, output stiffness and modal results of the beam model beside the analytical
    models (the keys of the continuum analyze_dbma). ``dim`` 3: the modes of the spatial beam
    model (:func:`beam_modal3d`: out-of-plane modes too, their accuracy in its note and
    docs/beam.md); the statics are in-plane either way."""
    if dim not in (2, 3):
        raise ValueError(f"dim = {dim!r} must be 2 or 3")
    layout = layout or DBMALayout()
    model, peak = beam_model(p, layout, root_extension)
    out = {**analytical_metrics(p), **static_response(model, force, peak),
           "k_out": output_stiffness(model), "dofs": int(model.n_dofs),
           "model": "beam", "root_extension": root_extension}
    if n_modes:
        out.update(modal_response(model, n_modes)[0] if dim == 2 else
                   beam_modal3d(p, layout, n_modes, root_extension))
    return out


def beam_estimates(p: DBMAParams, stroke: float) -> dict:
    """The optimiser's screening estimates from the beam model, keyed like
    :func:`flexfem.studies.dbma.optimize.analytical_estimates`: R_fem, k_out (N/m),
    fn_working (Hz), von_mises_at_stroke (Pa, the beam stress at the actuator stroke, m)."""
    model, _ = beam_model(p)
    static = static_response(model, 100.0)
    scale = stroke / static["elongation"]
    von_mises = static["max_von_mises"] * scale
    return {"R_fem": static["R_fem"], "k_out": output_stiffness(model),
            "fn_working": modal_response(model, 4)[0]["fn_working"],
            "von_mises_at_stroke": von_mises if math.isfinite(von_mises) else math.inf}


def evaluate_beam(params_dict: dict | None = None, **options) -> dict:
    """:func:`.analysis.evaluate` of the beam model (``model="beam"``)."""
    return evaluate(params_dict, model="beam", **options)
