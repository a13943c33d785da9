"""The eight-bar's study entry: ``evaluate(params, model="continuum" | "beam", **options)``.

``model="continuum"`` (default) is the FEM
(:func:`flexfem.studies.eightbar.analysis.evaluate`); ``model="beam"`` the reduced beam model
(:func:`flexfem.studies.eightbar.beam.evaluate_beam`), same metric names, ~100x faster. A
study file selects it with ``options = { model = "beam" }``.
"""
from ..engine.choice import ModelChoice
from . import analysis, beam

evaluate = ModelChoice("continuum", continuum=analysis.evaluate, beam=beam.evaluate_beam)

#: Units of the eight-bar's parameters (EightBarParams and EightBarFlexureParams: lengths) and
#: metrics, for plot axes.
UNITS = {**dict.fromkeys(
    ("ground_spacing", "crank_length", "coupler_length", "coupler_point_depth",
     "module_spacing", "ee_drop", "travel", "link_width", "base_flexure_length",
     "base_flexure_width", "flexure_length", "flexure_width", "thickness", "root_fillet_radius",
     "h"), "m"),
    "k_x": "N/m", "k_y": "N/m", "k_x_prbm": "N/m", "max_von_mises": "Pa",
    "max_von_mises_element": "Pa", "peak_von_mises_travel": "Pa", "safety_factor": "-",
    "dofs": "-"}
