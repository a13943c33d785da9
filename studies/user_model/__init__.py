"""Analysis of a user's model file (see flexfem.geometry.user_model and docs/model_files.md):
``analyze_model(spec) -> dict``, ``evaluate(params, model=...) -> flat metrics`` for sweeps,
and the ``analyze`` command (cli.register)."""
from .analysis import analyze_model, build_model, evaluate, flat_metrics

__all__ = ["analyze_model", "build_model", "evaluate", "flat_metrics"]
