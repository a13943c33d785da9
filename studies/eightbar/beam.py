"""The eight-bar's beam model by the names its callers know: :func:`.analysis.analyze_eightbar`
and :func:`.analysis.evaluate` with ``model="beam"`` (the builder: :mod:`.beam_model`)."""
from ...geometry.eightbar.flexure import EightBarFlexureParams
from .analysis import analyze_eightbar, evaluate


def analyze_eightbar_beam(params: EightBarFlexureParams | None = None, **options) -> dict:
    """:func:`.analysis.analyze_eightbar` of the beam model, the path's -x half mirrored."""
    return analyze_eightbar(params, model="beam", both_halves=False, **options)


def evaluate_beam(params: dict | None = None, **options) -> dict:
    """:func:`.analysis.evaluate` of the beam model (``model="beam"``)."""
    return evaluate(params, model="beam", **options)
