"""The engine's own check for the report, on the toy cantilever: a sweep against the closed
form and a convergence study against the known order 2 and the exact taper integral."""
import csv
from pathlib import Path

from ..engine.convergence import converge, default_levels, plot_convergence
from ..engine.store import export_csv
from ..engine.sweep import Study, plot_metric, run_study
from .model import CantileverParams, evaluate, tip_deflection_exact


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
                overlay=["tip_deflection_analytical"])
    taper = {"thickness_tip_m": 0.001}
    conv = converge(evaluate, "tip_deflection", default_levels(4 if quick else 6), params=taper, tol=0.005)
    plot_convergence(conv, out / "toy_convergence.png", theoretical_order=2.0)
    with (out / "toy_convergence.csv").open("w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["size_factor", "h_m", "dofs", "tip_deflection_m"])
        writer.writerows([lv["size_factor"], h, d, v]
                         for lv, h, d, v in zip(conv.levels, conv.sizes, conv.dofs, conv.values))
    case = next(c for c in result.cases if c.params == {"length_m": 0.1, "width_m": 0.01})
    exact = tip_deflection_exact(CantileverParams(**taper))
    rows = [("toy tip deflection L = 0.1 m, 8 elements (m)", case.metrics["tip_deflection"],
             case.metrics["tip_deflection_analytical"],
             "vs P L^3/(3 E I), not a published value; trapezoid error h^2/(2 L^2) = +0.78 %"),
            ("toy taper observed order", conv.order, 2.0, "theory: trapezoid rule, O(h^2)"),
            ("toy taper Richardson tip deflection (m)", conv.extrapolated, exact,
             f"vs the exact integral; GCI {100 * conv.gci:.2g} %")]
    return {"comparisons": [{"quantity": q, "flexfem": f, "published": p, "rel_diff": f / p - 1,
                             "note": n} for q, f, p, n in rows],
            "figures": ["toy_tip_deflection.png", "toy_convergence.png"],
            "tables": ["toy_sweep.csv", "toy_convergence.csv"],
            "notes": [f"{len(result.cases)} toy cases, {len(result.failed)} failed, "
                      f"{result.wall_time_s:.2f} s"]}
