"""The engine's own check for the report, on the toy cantilever: a sweep against the closed
form and a convergence study against the known order 2 and the exact taper integral."""
from pathlib import Path

from ..engine.convergence import converge, default_levels, plot_convergence
from ..engine.store import export_csv
from ..engine.tables import write_rows
from ..engine.sweep import Study, plot_metric, run_study
from ..report.comparison import Comparison, rows as comparison_rows
from ..report.figures import entry
from .model import UNITS, CantileverParams, evaluate, tip_deflection_exact

PARAGRAPH = ("The study engine checks itself on a closed form: a sweep of the toy cantilever "
             "against its exact deflection, and a convergence study whose observed order and "
             "Richardson extrapolation are known exactly. This is not a source document's "
             "result; it shows that the sweeps and convergence studies of the other sections "
             "can be trusted.")


def reproduce(out_dir, quick: bool = False) -> dict:
    """The engine's own check for the reproduction report, on the toy cantilever: a sweep
    against the closed form, and a convergence study against the known order 2 and the exact
    taper integral. Writes CSV tables and PNG figures into ``out_dir``."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    lengths = [0.05, 0.1, 0.15] if quick else [0.04, 0.06, 0.08, 0.1, 0.12, 0.15]
    study = Study("toy", name="toy_sweep", grid={"length_m": lengths, "width_m": [0.005, 0.01]})
    result = run_study(study, out / "toy_sweep.sqlite", evaluate, workers=1, progress=False)
    export_csv(result.cases, out / "toy_sweep.csv")
    plot_metric(result.cases, "tip_deflection", "length_m", out / "toy_tip_deflection.png",
                overlay=["tip_deflection_analytical"], units=UNITS)
    figures = [entry("toy_tip_deflection.png", "The study engine's sweep of the toy cantilever: "
                     "tip deflection (trapezoid rule, 8 elements) against length beside the "
                     "closed form, for two widths."),
               entry("toy_convergence.png", "Mesh convergence of the tapered toy cantilever's "
                     "tip deflection: the observed order against the trapezoid rule's 2, and "
                     "the Richardson-extrapolated value.")]
    taper = {"thickness_tip_m": 0.001}
    conv = converge(evaluate, "tip_deflection", default_levels(4 if quick else 6), params=taper, tol=0.005)
    plot_convergence(conv, out / "toy_convergence.png", theoretical_order=2.0)
    write_rows(out / "toy_convergence.csv",
               [{"size_factor": lv["size_factor"], "h_m": h, "dofs": d, "tip_deflection_m": v}
                for lv, h, d, v in zip(conv.levels, conv.sizes, conv.dofs, conv.values)])
    case = next(c for c in result.cases if c.params == {"length_m": 0.1, "width_m": 0.01})
    exact = tip_deflection_exact(CantileverParams(**taper))
    rows = comparison_rows([
        # the trapezoid rule's error on a uniform beam is exactly h^2 / (2 L^2) = +0.78 % with
        # 8 elements: 1 % holds it, and a wrong integrand would miss by far more
        Comparison("toy tip deflection, L = 0.1 m, 8 elements", case.metrics["tip_deflection"],
                   case.metrics["tip_deflection_analytical"], "m", "P L^3 / (3 E I)", "derived",
                   0.01, "not a published value: the closed form of the same beam",
                   headline=True),
        Comparison("toy taper, observed convergence order", conv.order, 2.0, "-",
                   "trapezoid rule, O(h^2)", "derived", 0.05),
        Comparison("toy taper, Richardson-extrapolated tip deflection", conv.extrapolated, exact,
                   "m", "exact taper integral", "derived", 1e-3,
                   f"grid convergence index {100 * conv.gci:.2g} %"),
    ])
    return {"paragraph": PARAGRAPH, "comparisons": rows, "figures": figures,
            "tables": ["toy_sweep.csv", "toy_convergence.csv"],
            "notes": [f"{len(result.cases)} toy cases, {len(result.failed)} failed, "
                      f"{result.wall_time_s:.2f} s"]}
