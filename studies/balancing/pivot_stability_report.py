"""``reproduce()`` of the pivot-stability section: the negative-stiffness pivots' moment-
rotation curves through their limit point (rotation control, and moment-driven by arc-length:
:mod:`.pivot_arclength`), their margins, and the cross-spring pivot's centre shift beside the
closed form (:mod:`.pivot_stability`)."""
import math
from pathlib import Path

import numpy as np

from ..engine.tables import write_rows
from ..report.comparison import Comparison, rows as comparison_rows
from ..report.figures import axis_label, legend_outside, pyplot, save
from .pivot_arclength import arclength_curves
from .pivot_arclength_report import (arclength_comparisons, arclength_sentence,
                                     arclength_table_rows, plot_arclength)
from .pivot_stability import pivot_stability_study


def plot_curves(out: dict, path: Path) -> dict:
    """Left: hub moment against rotation (FEM, elastica); right: centre shift (FEM, closed)."""
    plt = pyplot()
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(13, 4),
                                  gridspec_kw={"width_ratios": (1, 1), "wspace": 0.9})
    for n in out["negative"]:
        th = np.degrees([r["theta_rad"] for r in n["rows"]])
        ax.plot(th, [r["moment_fem_Nm"] for r in n["rows"]], "o-",
                label=f"motor {n['motor']}: FEM")
        ax.plot(th, [r["moment_elastica_Nm"] for r in n["rows"]], "k--", lw=1,
                label=f"motor {n['motor']}: elastica")
        ax.axvline(math.degrees(n["theta_max_rad"]), color="g", ls=":", lw=1,
                   label="end of the working range")
        if math.isfinite(n["limit_rotation_rad"]):
            ax.plot(math.degrees(n["limit_rotation_rad"]), n["limit_moment_Nm"], "rx", ms=10,
                    label="limit point (dM/dtheta = 0)")
    ax.set_xlabel(axis_label("pivot rotation", "deg"))
    ax.set_ylabel(axis_label("hub moment", "N m"))
    legend_outside(ax)
    c = out.get("cross")
    if c:
        th = np.degrees([r["theta_rad"] for r in c["rows"]])
        ax2.plot(th, [r["shift_m"] * 1e6 for r in c["rows"]], "o-", label="FEM")
        ax2.plot(th, [r["shift_closed_m"] * 1e6 for r in c["rows"]], "k--",
                 label="L theta^2 / (12 cos(alpha/2))")
        ax2.set_xlabel(axis_label("pivot rotation", "deg"))
        ax2.set_ylabel(axis_label("centre shift", "um"))
        ax2.legend(fontsize="small")
    return save(fig, path, (
        "Left: compressed-leaf (negative-stiffness) pivots, hub moment against rotation at the "
        "design preload, FEM (rotation control, each point its own large-deflection solve) and "
        "the elastica; the moment's extremum is the limit point where a moment-driven pivot "
        "would snap. Right: the cross-spring pivot's centre shift (the motion of the hub point "
        "at the leaves' crossing) against rotation, FEM and the inextensible-leaf closed form."))


def comparisons(out: dict) -> list[Comparison]:
    C = Comparison
    rows = []
    for n in out["negative"]:
        last = [r for r in n["rows"] if r["fraction_of_theta_max"] <= 1.0][-1]
        rows += [
            C(f"negative pivot (motor {n['motor']}): hub moment at theta_max",
              last["moment_fem_Nm"], last["moment_elastica_Nm"], "N m",
              "compressed-leaf elastica (negative_pivot.py)", "derived", tolerance=0.01),
            C(f"negative pivot (motor {n['motor']}): limit-point rotation",
              n["limit_rotation_rad"], n["limit_rotation_elastica_rad"], "rad",
              "compressed-leaf elastica: largest |M| at the design preload", "derived",
              tolerance=0.03, note=f"moment there {n['limit_moment_Nm']:.4g} N m (elastica "
              f"{n['limit_moment_elastica_Nm']:.4g})"),
            C(f"negative pivot (motor {n['motor']}): limit-point rotation / theta_max",
              n["limit_margin"], 1.0, "-", "the working range", "derived", limit="lower",
              headline=n is out["negative"][0], note=f"dM/dtheta = 0 at {math.degrees(n['limit_rotation_rad']):.1f}"
              f" deg; stable with the rotation held over the working range: "
              f"{n['stable_over_working_range']}; preload margin (pi/kL)^2 = "
              f"{n['preload_margin']:.3g}"),
        ]
    c = out.get("cross")
    if c:
        rows.append(C("cross-spring pivot: centre shift at theta_max",
                      c["shift_at_theta_max_m"], c["shift_closed_at_theta_max_m"], "m",
                      "L theta^2 / (12 cos(alpha/2)), after Haringx 1949 / Wittrick 1951",
                      "derived", tolerance=0.03, headline=True,
                      note=f"L = {c['L_m'] * 1e3:.3g} mm, theta_max = "
                           f"{math.degrees(c['theta_max_rad']):.3g} deg"))
    return rows


def paragraph(out: dict) -> str:
    n = out["negative"][0]
    text = (
        "The pivots judged by their stability and parasitic motion. The compressed-leaf pivot "
        f"of motor {n['motor']} keeps its negative stiffness over the working range (dM/dtheta "
        f"= {n['tangent_stiffness_at_theta_max_Nm_per_rad']:.3g} N m/rad at theta_max), and its "
        "moment-rotation curve turns at "
        f"{math.degrees(n['limit_rotation_rad']):.0f} deg, {n['limit_margin']:.2g} times the "
        "working range: driven by a moment rather than held in rotation, it would snap there. "
        f"With the rotation held it is stable and could take {n['preload_margin']:.2g} times "
        "its preload before buckling sideways.")
    c = out.get("cross")
    if c:
        text += (f" The cross-spring pivot's hub centre moves {c['shift_at_theta_max_m'] * 1e6:.3g}"
                 f" um at {math.degrees(c['theta_max_rad']):.3g} deg, as the closed form "
                 f"L theta^2 / (12 cos(alpha/2)) gives ({c['shift_closed_at_theta_max_m'] * 1e6:.3g}"
                 " um).")
    return text


def reproduce(out_dir, quick: bool = False) -> dict:
    """Run :func:`.pivot_stability.pivot_stability_study`; figures, tables, summary."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    out = pivot_stability_study(quick=quick)
    arcs = arclength_curves(quick=quick)
    curve = [{"motor": n["motor"], **r} for n in out["negative"] for r in n["rows"]]
    write_rows(out_dir / "balancing_pivot_limit.csv", curve)
    write_rows(out_dir / "balancing_pivot_arclength.csv", arclength_table_rows(arcs))
    tables = ["balancing_pivot_limit.csv", "balancing_pivot_arclength.csv"]
    if "cross" in out:
        write_rows(out_dir / "balancing_cross_pivot_shift.csv", out["cross"]["rows"])
        tables.append("balancing_cross_pivot_shift.csv")
    summary = {"negative": [{k: v for k, v in n.items() if k != "rows"} for n in out["negative"]],
               "cross": {k: v for k, v in out.get("cross", {}).items() if k != "rows"},
               "arclength": [{k: v for k, v in a.items() if k != "rows"} for a in arcs]}
    return {"paragraph": paragraph(out) + arclength_sentence(arcs),
            "figures": [plot_curves(out, out_dir / "balancing_pivot_stability.png"),
                        plot_arclength(arcs, out["negative"],
                                       out_dir / "balancing_pivot_arclength.png")],
            "comparisons": comparison_rows(comparisons(out) + arclength_comparisons(
                arcs, out["negative"])), "tables": tables, "pivot_stability": summary}
