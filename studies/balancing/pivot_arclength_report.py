"""The moment-driven compressed-leaf pivots traced by arc-length (:mod:`.pivot_arclength`) in
the pivot-stability section: figure, CSV rows, comparisons and a sentence."""
import math
from pathlib import Path

import numpy as np

from ..report.comparison import Comparison
from ..report.figures import axis_label, legend_outside, pyplot, save
from .pivot_arclength import against_rotation_control


def _rotation_rows(negative: list, motor) -> list:
    return next((n["rows"] for n in negative if n["motor"] == motor), [])


def plot_arclength(arcs: list, negative: list, path: Path) -> dict:
    """Hub moment against rotation of each arc-length path (stable and unstable states
    marked), its elastica, the rotation-controlled FEM states and the limit point."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for arc in arcs:
        th = np.degrees([r["theta_rad"] for r in arc["rows"]])
        m = np.array([r["moment_fem_Nm"] for r in arc["rows"]])
        stable = np.array([r["stable_moment_driven"] for r in arc["rows"]])
        line, = ax.plot(th, m, "-", lw=1, label=f"motor {arc['motor']}: FEM, arc-length")
        ax.plot(th[~stable], m[~stable], "o", mfc="none", color=line.get_color(),
                label="unstable when moment-driven")
        ax.plot(th[stable], m[stable], "o", color=line.get_color(),
                label="stable when moment-driven")
        ax.plot(th, [r["moment_elastica_Nm"] for r in arc["rows"]], "k--", lw=1,
                label="elastica at the same rotations")
        rot = _rotation_rows(negative, arc["motor"])
        ax.plot(np.degrees([r["theta_rad"] for r in rot]), [r["moment_fem_Nm"] for r in rot],
                "s", ms=7, mfc="none", color="tab:gray", label="FEM, rotation control")
        ax.plot(math.degrees(arc["limit_rotation_rad"]), arc["limit_moment_Nm"], "rx", ms=11,
                mew=2, label="limit point (arc-length)")
        ax.axvline(math.degrees(arc["theta_max_rad"]), color="g", ls=":", lw=1,
                   label="end of the working range")
    ax.set_xlabel(axis_label("pivot rotation", "deg"))
    ax.set_ylabel(axis_label("moment on the hub", "N m"))
    ax.grid(True, alpha=0.3)
    legend_outside(ax)
    return save(fig, path, (
        "Compressed-leaf (negative-stiffness) pivots driven by a moment: the axial preload "
        "applied first and held, the hub moment continued by arc-length (FEM, plane stress, "
        "large deflection) from the straight leaf through and past the limit point; open "
        "circles are states a moment alone cannot hold (one negative eigenvalue of the "
        "tangent), filled ones stable states. Beside them the elastica and the rotation-"
        "controlled FEM states of the same leaf."))


def arclength_comparisons(arcs: list, negative: list) -> list[Comparison]:
    C = Comparison
    rows = []
    for arc in arcs:
        name = f"negative pivot (motor {arc['motor']}), moment-driven by arc-length"
        rot = _rotation_rows(negative, arc["motor"])
        at_max = [r for r in rot if r.get("fraction_of_theta_max") == 1.0]
        rows += [
            C(f"{name}: limit-point rotation", arc["limit_rotation_rad"],
              arc["limit_rotation_elastica_rad"], "rad",
              "compressed-leaf elastica: largest |M| at the design preload (negative_pivot.py)",
              "derived", tolerance=0.01),
            C(f"{name}: limit-point moment", arc["limit_moment_Nm"],
              arc["limit_moment_elastica_Nm"], "N m",
              "compressed-leaf elastica (negative_pivot.py)",
              "derived", tolerance=0.005),
            C(f"{name}: limit-point rotation / theta_max (rotation margin)",
              arc["rotation_margin"], 1.0, "-", "the working range", "derived", limit="lower",
              note=f"moment margin |M_limit / M(theta_max)| = {arc['moment_margin']:.3g}; "
                   f"dM/dtheta at theta_max = "
                   f"{arc['tangent_stiffness_at_theta_max_Nm_per_rad']:.3g} N m/rad; unstable "
                   "when moment-driven over the working range: "
                   f"{arc['moment_driven_unstable_over_working_range']}"),
        ]
        if at_max:
            rows.append(C(f"{name}: hub moment at theta_max", arc["moment_at_theta_max_Nm"],
                          at_max[0]["moment_fem_Nm"], "N m",
                          "the same leaf by rotation control (pivot_stability.py)", "derived",
                          tolerance=1e-3, note="largest difference from the rotation-controlled "
                          f"states over |M_limit|: {against_rotation_control(arc, rot):.2g}"))
    return rows


def arclength_sentence(arcs: list) -> str:
    if not arcs:
        return ""
    a = arcs[0]
    return (f" Driven by a moment instead (the preload held, the moment continued by "
            f"arc-length), motor {a['motor']}'s leaf is unstable over its working range and "
            f"its moment peaks at {abs(a['limit_moment_Nm']):.3g} N m at "
            f"{math.degrees(a['limit_rotation_rad']):.0f} deg, {a['moment_margin']:.2g} times "
            "the moment at the end of the working range; past that limit point the path "
            "becomes stable.")


def arclength_table_rows(arcs: list) -> list[dict]:
    return [{"motor": a["motor"], **r} for a in arcs for r in a["rows"]]
