"""The DBMA's study entry: ``evaluate(params, model="continuum" | "beam", **options)``.

``model="continuum"`` (default) is the FEM (:func:`flexfem.studies.dbma.analysis.evaluate`);
``model="beam"`` the reduced beam model (:func:`flexfem.studies.dbma.beam.evaluate_beam`),
same metric names. A study file selects it with ``options = { model = "beam" }``.
"""
from ..engine.choice import ModelChoice
from . import analysis, beam

evaluate = ModelChoice("continuum", continuum=analysis.evaluate, beam=beam.evaluate_beam)
