"""The DBMA's study entry: ``evaluate(params, model="continuum" | "beam", **options)``.

``model="continuum"`` (default) is the FEM (:func:`flexfem.studies.dbma.analysis.evaluate`,
unchanged); ``model="beam"`` the reduced beam model
(:func:`flexfem.studies.dbma.beam.evaluate_beam`), same metric names. A study file selects it
with ``options = { model = "beam" }``.
"""
import inspect

from ..engine.validate import dispatch_signature
from . import analysis, beam

MODELS = ("continuum", "beam")


def check_model(model) -> str:
    if model not in MODELS:
        raise ValueError(f"model = {model!r} must be one of {MODELS}")
    return model


def evaluate(params_dict: dict, model: str = "continuum", **options) -> dict:
    """Study-registry entry: the continuum or the beam model's metrics of ``params_dict``."""
    if check_model(model) == "beam":
        return beam.evaluate_beam(params_dict, **options)
    return analysis.evaluate(params_dict, **options)


# the options a study may give: the selector and every option either model declares
evaluate.__signature__ = dispatch_signature(
    inspect.Parameter("model", inspect.Parameter.KEYWORD_ONLY, default="continuum"),
    analysis.evaluate, beam.evaluate_beam)
