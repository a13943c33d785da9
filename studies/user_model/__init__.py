"""A user's own model file, from Python: read it (:func:`load_model`), analyse it by the
continuum or the beam model (:func:`analyze`, a :class:`Report`), and for sweeps
``evaluate(params, file=...) -> flat metrics``; the ``analyze`` command (:mod:`.cli`) is a
thin layer over these. See docs/model_files.md.

    from flexfem.studies.user_model import analyze, load_model

    model = load_model("examples/bodies/guide.toml", set={"t": "0.8 mm"})
    report = analyze(model, fidelity="beam")
    report.stiffness["stage"]["x"]      # N/m
    print(report.summary(units="mm"))
    report.write("guide_out")           # summary.json, VTU fields, pictures, index.html

``analyze_model(spec) -> dict`` is the same analysis as a dict (``Report.to_dict()``).
"""
from ...fem.lazy_exports import lazy_exports
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # imported when first used (below): the command line's parsers import
    # .summary and .cli without the analyses
    from .analysis import analyze_model, build_model, evaluate, flat_metrics
    from .api import analyze, load_model
    from .model_report import Report

_EXPORTS = {"analyze_model": "analysis", "build_model": "analysis", "evaluate": "analysis",
            "flat_metrics": "analysis", "analyze": "api", "load_model": "api",
            "Report": "model_report"}

__all__ = ["Report", "analyze", "analyze_model", "build_model", "evaluate", "flat_metrics",
           "load_model"]

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
