"""Where the beam model stops being trustworthy, as the DBMA's report shows it: the hinge
specimen of :mod:`flexfem.reduced.specimen` over its slenderness l/b (2 to 20), and the DBMA
itself with its hinges' b varied, beam model against the 2-D continuum. SI units.
"""
import numpy as np

from ...fem import Force
from ...reduced.specimen import TRUST_LIMIT
from ..report.figures import axis_label, legend_outside, pyplot, save

def _notch_t_over_r(x):
    """t / R = 2 b / l of a right-circular notch (R = l / 2) at slenderness l / b."""
    return 2 / np.maximum(np.asarray(x, float), 1e-9)


def plot_slenderness(rows: list, path, mechanism_rows: list | None = None) -> dict:
    """Beam / continuum - 1 of the hinge compliance against l/b (leaf and circular notch,
    bending and axial, the model as built and bare beam theory), the +-3 % band, and
    (``mechanism_rows``:
    [{"l_over_b", "<metric>_error"}]) the DBMA's own metrics."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7.5, 4.6))
    styles = {"leaf": "o", "circular": "s"}
    for profile in sorted({r["profile"] for r in rows}):
        mine = sorted((r for r in rows if r["profile"] == profile), key=lambda r: r["l_over_b"])
        x = [r["l_over_b"] for r in mine]
        for load, colour in (("bending", "tab:blue"), ("axial", "tab:orange")):
            ax.plot(x, [100 * r[f"{load}_error"] for r in mine], "-" + styles[profile],
                    color=colour, label=f"{profile}, {load}, as built")
            ax.plot(x, [100 * r[f"{load}_error_bare"] for r in mine], ":" + styles[profile],
                    color=colour, alpha=0.6, label=f"{profile}, {load}, bare beam theory")
    for metric, colour in (("R_fem", "tab:green"), ("k_out", "tab:red"), ("fn_working", "k")):
        mine = sorted(mechanism_rows or [], key=lambda r: r["l_over_b"])
        if mine:
            ax.plot([r["l_over_b"] for r in mine], [100 * r[f"{metric}_error"] for r in mine],
                    "-^", color=colour, label=f"DBMA {metric}")
    ax.axhspan(-100 * TRUST_LIMIT, 100 * TRUST_LIMIT, color="0.85", zorder=0)
    ax.set_xscale("log")
    ax.set_xticks([2, 3, 5, 10, 20], ["2", "3", "5", "10", "20"])
    ax.set_xticks([], minor=True)
    ax.set_xlabel(axis_label("hinge slenderness l / b", "-"))
    notch = ax.secondary_xaxis("top", functions=(_notch_t_over_r, _notch_t_over_r))
    notch.set_xticks([1, 2 / 3, 0.4, 0.2, 0.1], ["1", "0.67", "0.4", "0.2", "0.1"])
    notch.set_xticks([], minor=True)
    notch.set_xlabel(axis_label("circular notch: t / R = 2 b / l", "-"))
    ax.set_ylabel(axis_label("beam / continuum - 1", "%"))
    ax.set_ylim(-55, 15)
    ax.grid(True, alpha=0.3)
    legend_outside(ax)
    return save(fig, path, "Beam model against the 2-D continuum over the hinge slenderness: "
                "compliance error of one hinge between two blocks (bending and axial, leaf "
                "and circular notch) as the mechanisms' models build it (solid: the common "
                "root extension; a notch also corrected by its own 2-D model) and as bare beam "
                "theory (dotted), and the DBMA's own R, k_out and working frequency "
                "(triangles) where computed. Grey: the 3 % band. Top axis: the notch's t / R. "
                "Bare beam theory is too stiff by ~b / l (bending) and more axially: it leaves "
                "the band below l/b ~ 20. As built, a sharp-cornered leaf stays in it down to "
                "l/b ~ 2, a circular notch in bending at every l/b; axially the notch keeps "
                "part of its junction with blocks much taller than its ends (docs/beam_validation.md, "
                "\"Notch hinges: the 2-D patch\").")


def dbma_slenderness_rows(ratios=(2.0, 5.0, 10.0, 20.0), size_factor: float = 1.0) -> list:
    """The DBMA at hinge slenderness l/b (b varied, l = the paper's 4.41 mm): beam / 2-D
    continuum - 1 of R_fem, k_in, k_out and fn_working."""
    from dataclasses import replace

    from ...fem import solve_static as fe_static
    from ...geometry.dbma.params import paper_design
    from . import analysis as fem
    from .beam import analyze_dbma_beam

    rows = []
    for ratio in ratios:
        p = replace(paper_design(), b=paper_design().l / ratio)
        model = fem.build_model(p, None, 2, size_factor)
        static = fem.static_response(model, 100.0)
        probe = fe_static(model, fem.modal_supports(), [Force("output", (0.0, 100.0))])
        cont = {"R_fem": static["R_fem"], "k_in": static["k_in"],
                "k_out": 100.0 / float(probe.mean_displacement("output")[1]),
                "fn_working": fem.modal_response(model, 4)[0]["fn_working"]}
        beam = analyze_dbma_beam(p, n_modes=4)
        row = {"l_over_b": ratio, "b_m": p.b}
        for k, v in cont.items():
            row.update({f"{k}_continuum": v, f"{k}_beam": beam[k], f"{k}_error": beam[k] / v - 1})
        rows.append(row)
    return rows
