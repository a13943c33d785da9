"""A DBMA design search with its outputs: tables, figure and text of ``optimize.optimize``'s
result, and the report section."""
from pathlib import Path

from ...geometry.dbma.params import paper_design
from ..engine.tables import write_rows
from ..report.figures import entry, legend_outside, pyplot, save
from ..report.front import front_report
from .analysis import evaluate
from .beam import beam_estimates
from .optimize import Evaluations, fem_metrics, optimize
from .optimize_spec import (
    NAMES,
    OptimizeSpec,
    constraint_table,
    constraints_of,
    margins,
    quick_spec,
)

HISTORY_COLUMNS = ("evaluation", "stage", "size_factor", "b", "h", "l", "R_fem", "R_fem_per_side",
                   "fn_working", "k_out", "von_mises_at_stroke", "von_mises_element_at_stroke",
                   "actuator_force", "free_output", "blocked_output_force", "feasible", "cached",
                   "wall_time_s")

# screening models (optimize's estimator): None is optimize's default, the closed forms
# (analytical_estimates); "beam" the generated beam model
SCREENS = {"closed-form": None, "beam": beam_estimates}


def history_rows(result: dict) -> list[dict]:
    """The history with 'feasible': the row's own-mesh metrics meet every constraint."""
    spec = OptimizeSpec(**result["spec"])
    out = []
    for r in result["history"]:
        cons = constraints_of(spec, r["yield_strength"])
        out.append({**{k: r[k] for k in HISTORY_COLUMNS if k in r},
                     "feasible": bool(margins(r, cons).min() >= 0)})
    return out


def write_history_csv(result: dict, path) -> Path:
    """optimize_history.csv: one row per FEM evaluation (SI units)."""
    write_rows(path, history_rows(result), HISTORY_COLUMNS)
    return Path(path)


HISTORY_CAPTION = ("The DBMA design search: the amplification ratio of each FEM evaluation, "
                   "filled where the design meets every constraint on its own mesh; the search "
                   "mesh (circles) and the finer check mesh (squares).")


def plot_history(result: dict, path) -> Path:
    """R_fem_per_side against the evaluation number: filled where the design meets every
    constraint on its own mesh, hollow where not; search circles, checks squares."""
    plt = pyplot()
    rows = history_rows(result)
    fig, ax = plt.subplots(figsize=(6.5, 4))
    for stages, mesh, marker, label in (
            (("seed", "search"), result["search_size_factor"], "o", "search"),
            (("calibration", "check"), result["check_size_factor"], "s", "check")):
        for ok, face in ((True, None), (False, "none")):
            sel = [r for r in rows if r["stage"] in stages and r["feasible"] == ok]
            if not sel:
                continue
            ax.scatter([r["evaluation"] for r in sel], [r["R_fem_per_side"] for r in sel],
                       marker=marker, facecolors=face if face else ("tab:blue" if marker == "o" else "tab:red"),
                       edgecolors="tab:blue" if marker == "o" else "tab:red",
                       label=f"{label}, size_factor {mesh:g}, {'feasible' if ok else 'infeasible'}")
    ax.axhline(result["R_fem_per_side"], color="0.4", ls=":", lw=1,
               label=f"optimum R = {result['R_fem_per_side']:.3f}")
    ax.set_xlabel("FEM evaluation")
    ax.set_ylabel("R (output / one pad's motion)")
    legend_outside(ax)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, path, HISTORY_CAPTION)
    return Path(path)


def summary_rows(result: dict) -> list[dict]:
    """The optimum as a table: design (m), R, each constraint with its bound and activity."""
    rows = [{"quantity": f"{n} (m)", "value": v, "bound": None, "active": None}
            for n, v in result["optimum"].items()]
    rows += [{"quantity": "R_fem (output / elongation)", "value": result["R_fem"], "bound": None, "active": None},
             {"quantity": "R_fem_per_side", "value": result["R_fem_per_side"], "bound": None, "active": None}]
    rows += [{"quantity": f"{c['constraint']}: {c['metric']} {c['kind']}", "value": c["value"],
              "bound": c["bound"], "active": c["active"]} for c in result["constraints"]]
    return rows


def summarize(result: dict) -> str:
    """Human summary of ``optimize``'s result."""
    o, m = result["optimum"], result["metrics"]
    lines = [f"optimum b = {o['b'] * 1e3:.4f} mm, h = {o['h'] * 1e3:.4f} mm, l = {o['l'] * 1e3:.4f} mm: "
             f"R_fem = {result['R_fem']:.4f} (per side {result['R_fem_per_side']:.4f}), "
             f"check mesh size_factor {result['check_size_factor']:g}"]
    for c in result["constraints"]:
        lines.append(f"  {c['constraint']:17s} {c['metric']} = {c['value']:.4g} {c['kind']} {c['bound']:.4g}"
                     f" ({100 * c['margin']:+.2f} %){'  ACTIVE' if c['active'] else ''}")
    lines.append(f"  actuator force at the stroke {m['actuator_force']:.4g} N, free output "
                 f"{m['free_output'] * 1e6:.4g} um, blocked output force {m['blocked_output_force']:.4g} N")
    s = result["seed"]
    lines.append(f"analytical seed {', '.join(f'{n} = {v * 1e3:.3f} mm' for n, v in s['design'].items())}: "
                 + ", ".join(f"{k} {100 * d:+.1f} %" for k, d in s["analytical_vs_fem"].items())
                 + " vs FEM; optimum R "
                 f"{100 * result['R_gain_over_seed']:+.1f} % over the seed")
    lines.append(f"{result['n_fem_evaluations']} FEM evaluations ({result['n_search_evaluations']} search, "
                 f"{result['n_check_evaluations']} check, {result['n_fem_computed']} computed, the rest "
                 f"from the store) in {result['wall_time_s']:.1f} s"
                 + (f", at bounds: {', '.join(result['at_bounds'])}" if result["at_bounds"] else ""))
    return "\n".join(lines)


def write_rows_csv(rows: list[dict], path) -> Path:
    """A table of summary_rows as CSV (quantity, value, bound, active)."""
    return write_rows(path, rows, ["quantity", "value", "bound", "active"])


def run(spec: OptimizeSpec, out_dir=None, quick: bool = False,
        screen: str = "closed-form") -> dict:
    """``optimize`` with its store, optimize_history.csv and optimize_history.png in
    ``out_dir`` (when given); quick: ``quick_spec``; screen: "closed-form" (the elastic-beam
    formulas, default) or "beam" (the generated beam model, ~0.2 s a design: closer to the
    FEM, which still decides)."""
    if screen not in SCREENS:
        raise ValueError(f"screen = {screen!r} must be one of {tuple(SCREENS)}")
    spec = quick_spec(spec) if quick else spec
    out = None if out_dir is None else Path(out_dir)
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
    result = optimize(spec, None if out is None else out / "optimize_cache.sqlite",
                      estimator=SCREENS[screen])
    result["screening"] = screen
    if out is not None:
        result["tables"] = [write_history_csv(result, out / "optimize_history.csv").name]
        result["figures"] = [plot_history(result, out / "optimize_history.png").name]
        result["out"] = str(out)
    return result


# The trade-off of examples/dbma_front.toml (a test keeps the two the same): R against the
# working mode over b, h and l, a safety factor of 1.5 at the actuator's 800 N and an output
# stiffness of at least 3e5 N/m; the beam model screens, the 2-D continuum confirms.
FRONT = {
    "mechanism": "dbma", "options": {"model": "beam", "modes": True, "force": 800.0},
    "variables": {"b": [0.3e-3, 1.2e-3], "h": [0.5e-3, 4.0e-3], "l": [2.0e-3, 8.0e-3]},
    "objectives": [{"metric": "R_fem_per_side", "goal": "max"},
                   {"metric": "fn_working", "goal": "max"}],
    "constraints": [{"metric": "safety_factor", "at_least": 1.5},
                    {"metric": "k_out", "at_least": 3.0e5}],
    "search": {"population": 24, "generations": 20, "seed": 0},
    "confirm": {"model": "continuum"},
    "reference": [{"name": "paper", "params": {}}]}
FRONT_LABELS = {"R_fem_per_side": ("R (output / one pad)", "-"),
                "fn_working": ("working mode", "Hz"), "safety_factor": ("safety factor", "-"),
                "k_out": ("output stiffness", "N/m")}


def front_section(out_dir, quick: bool = False, optimum: dict | None = None) -> dict:
    """The DBMA's Pareto front (:data:`FRONT`) into ``out_dir``/front, with the paper's
    design and flexfem's single-objective ``optimum`` ({b, h, l}, where given) placed on
    it; ``quick``: 16 designs x 8 generations (~4 s), no continuum confirmation."""
    references = (("flexfem's single-objective optimum", optimum),) if optimum else ()
    return front_report(FRONT, evaluate, Path(out_dir) / "front", FRONT_LABELS,
                        "the DBMA's amplification against its working mode",
                        population=16 if quick else None, generations=8 if quick else None,
                        confirm=not quick, references=references, figure="dbma_front.png",
                        prefix="front/", defaults={n: getattr(paper_design(), n) for n in NAMES})


def reproduce(out_dir, quick: bool = False, full: bool = False) -> dict:
    """The default design search into ``out_dir``, beside the paper's design on the check
    mesh, and the Pareto front of R against the working mode (:func:`front_section`) with
    both designs placed on it; with ``quick`` only a small front (a smoke run of the report
    has no time for the search; ``flexfem optimize dbma`` runs it); ``full`` changes nothing.
    Summary: rows, comparisons (none: no source has a search), tables, figures, notes, the
    front's key table."""
    if quick:
        front = front_section(out_dir, quick=True)
        return {"comparisons": [], "tables": front["tables"], "figures": [front["figure"]],
                "notes": [front["sentence"] + " A smaller search in a --quick report (16 "
                          "designs x 8 generations, no continuum check); the single-objective "
                          "design search is not run: run `flexfem reproduce` or `flexfem "
                          "optimize dbma`."],
                "key_tables": [front["table"]], "front": front["result"]}
    out = Path(out_dir)
    result = run(OptimizeSpec(), out)
    p, spec = paper_design(), OptimizeSpec(**result["spec"])
    ev = Evaluations(fem_metrics, spec.stroke_m, out / "optimize_cache.sqlite")
    try:
        paper = ev([getattr(p, n) for n in NAMES], spec.check_size_factor, "paper design")
    finally:
        ev.close()
    paper_table = constraint_table(paper, constraints_of(spec, ev.history[-1]["yield_strength"]))
    rows = summary_rows(result)
    rows.append({"quantity": "paper design (b 0.6, h 2.6, l 4.41 mm) R_fem_per_side",
                 "value": paper["R_fem_per_side"], "bound": None, "active": None})
    write_rows_csv(rows, out / "optimize_optimum.csv")
    notes = [summarize(result).replace("\n", "; "),
             "Beyond the sources: the paper has no design search; nothing here is compared "
             "with a published number."]
    front = front_section(out, optimum=result["optimum"])
    notes.append(front["sentence"])
    return {"rows": rows, "comparisons": [],
            "tables": result["tables"] + ["optimize_optimum.csv"] + front["tables"],
            "figures": [entry(name, HISTORY_CAPTION) for name in result["figures"]]
            + [front["figure"]], "key_tables": [front["table"]], "front": front["result"],
            "notes": notes, "optimum": result["optimum"],
            "R_fem": result["R_fem"], "active_constraints": result["active_constraints"],
            "n_fem_evaluations": result["n_fem_evaluations"], "paper_design": paper,
            "paper_design_constraints": paper_table}
