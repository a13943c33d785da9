"""The DBMA's study entry: ``evaluate(params, model="continuum" | "beam", **options)``
(:func:`flexfem.studies.dbma.analysis.evaluate`: one analysis, the model's builder chosen by
``model``). A study file selects the beam model with ``options = { model = "beam" }``.
"""
from .analysis import evaluate

__all__ = ["evaluate", "UNITS"]

_LENGTHS = ("c", "a", "d", "l", "e", "ls", "ll", "b", "h", "elongation", "output_displacement",
            "root_extension")
_STIFFNESSES = ("k_in", "k_out", "Ke_eq14", "K_in_enhanced", "K_out_enhanced",
                "K_out_free_input_enhanced")
#: Units of the DBMA's parameters (DBMAParams) and metrics, for plot axes.
UNITS = {**dict.fromkeys(_LENGTHS, "m"), **dict.fromkeys(_STIFFNESSES, "N/m"),
         "R_*": "-", "E": "Pa", "nu": "-", "rho": "kg/m^3", "max_von_mises": "Pa",
         "safety_factor": "-", "fn_*": "Hz", "me_eq19": "kg", "force_N": "N", "dofs": "-",
         "working_mode": "-"}
