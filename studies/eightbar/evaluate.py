"""The eight-bar's study entry: ``evaluate(params, model="continuum" | "beam", **options)``.

``model="continuum"`` (default) is the FEM
(:func:`flexfem.studies.eightbar.analysis.evaluate`); ``model="beam"`` the reduced beam model
(:func:`flexfem.studies.eightbar.beam.evaluate_beam`), same metric names, ~100x faster. A
study file selects it with ``options = { model = "beam" }``.
"""
from ..engine.choice import ModelChoice
from . import analysis, beam

evaluate = ModelChoice("continuum", continuum=analysis.evaluate, beam=beam.evaluate_beam)
