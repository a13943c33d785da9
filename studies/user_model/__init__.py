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
from .analysis import analyze_model, build_model, evaluate, flat_metrics
from .api import analyze, load_model
from .model_report import Report

__all__ = ["Report", "analyze", "analyze_model", "build_model", "evaluate", "flat_metrics",
           "load_model"]
