"""The eight-bar's study entry: ``evaluate(params, model="continuum" | "beam", **options)``.

``model="continuum"`` (default) is the 2-D FEM (:func:`flexfem.studies.eightbar.analysis.evaluate`,
unchanged); ``model="beam"`` the reduced beam model
(:func:`flexfem.studies.eightbar.beam.evaluate_beam`), same metric names, ~100x faster.
A study file selects it with ``options = { model = "beam" }``.
"""
import inspect

from ..engine.validate import dispatch_signature
from . import analysis, beam

MODELS = ("continuum", "beam")


def check_model(model) -> str:
    if model not in MODELS:
        raise ValueError(f"model = {model!r} must be one of {MODELS}")
    return model


def evaluate(params: dict | None = None, model: str = "continuum", **options) -> dict:
    """Study-registry entry: the continuum or the beam model's metrics of ``params``."""
    if check_model(model) == "beam":
        return beam.evaluate_beam(params, **options)
    return analysis.evaluate(params, **options)


# the options a study may give: the selector and every option either model declares
evaluate.__signature__ = dispatch_signature(
    inspect.Parameter("model", inspect.Parameter.KEYWORD_ONLY, default="continuum"),
    analysis.evaluate, beam.evaluate_beam)
