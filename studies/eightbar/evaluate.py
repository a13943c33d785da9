"""The eight-bar's study entry: ``evaluate(params, model="continuum" | "beam", **options)``
(:func:`flexfem.studies.eightbar.analysis.evaluate`: one analysis, the model's builder chosen
by ``model``; the beam model ~100x faster). A study file selects it with
``options = { model = "beam" }``.
"""
from .analysis import evaluate

__all__ = ["evaluate", "UNITS"]

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
