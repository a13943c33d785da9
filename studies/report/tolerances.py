"""A tolerance study in a mechanism's report section: the study (a study file's table, as
examples/*_tolerances.toml declare it) run into the section's folder by the study engine, its
spread and Sobol indices as one short key table, one figure and a sentence naming the
tolerance that matters most; optionally its extremes re-checked by a confirming model
(engine/tolerance.py, ``[tolerances.confirm]``).

    result = tolerance_report(study_table, evaluate, out_dir / "tolerances", OUTPUTS, LABELS,
                              "the tolerances", n=8)
    add_to_section(section_summary, result)   # its note, table(s), figure and files

``OUTPUTS`` {metric: (label, unit)} chooses and names the outputs shown; ``LABELS``
{parameter: label} names the toleranced parameters. SI units throughout.
"""
import contextlib
from dataclasses import replace
from pathlib import Path
import time

import numpy as np

from ..engine.store import export_csv
from .figures import pyplot, save
from .format import number


def one_blas_thread():
    """A context running BLAS on one thread (threadpoolctl, where installed; else nothing):
    the beam models' small banded solves run ~10x faster so in this process than on
    OpenBLAS's threads, which spin against the other busy cores (the DBMA: 0.02 s a design
    instead of 0.15-2 s). Worker processes are limited by the engine already."""
    try:
        from threadpoolctl import threadpool_limits
    except ImportError:
        return contextlib.nullcontext()
    return threadpool_limits(limits=1)


def run_tolerances(table: dict, evaluate, folder: Path, n: int | None = None,
                   workers: int | None = 1, confirm: bool = False) -> tuple:
    """(study, summary, confirmation or None): the study of the parsed study-file ``table``
    (its base Saltelli sample replaced by ``n`` where given) run with ``evaluate`` (the
    mechanism's) into ``folder`` (a store, results.csv); the summary of
    :func:`..engine.tolerance.summarize`, the confirmation of
    :func:`..engine.tolerance.confirm_extremes` when ``confirm`` and the study declares
    ``[tolerances.confirm]``."""
    from ..engine.sweep import run_study, study_from_dict
    from ..engine.tolerance import confirm_extremes, summarize

    study = study_from_dict(table)
    if n is not None:
        study = replace(study, tolerances=replace(study.tolerances, n=n))
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)

    def run(s):
        return run_study(s, folder / "results.sqlite", evaluate, workers=workers,
                         progress=False)

    with one_blas_thread():
        result = run(study)
        export_csv(result.cases, folder / "results.csv")
        summary = summarize(result.study, result.cases)
        checked = None
        if confirm and study.tolerances.confirm is not None:
            checked = confirm_extremes(result.study, run)
    return study, summary, checked


def _tolerance_text(spec: dict, unit: str = "m") -> str:
    kind = "3σ" if spec["distribution"] == "normal" else "uniform"
    return f"±{number(spec['tolerance'], unit)} ({kind})"


def key_table(summary: dict, outputs: dict, labels: dict, title: str) -> dict:
    """One row per output: its mean, its ±3σ scatter (and as % of the mean), and per
    toleranced parameter its first- and total-order Sobol indices."""
    names = list(summary["parameters"])
    columns = ["output", "mean", "scatter ±3σ"] + [
        f"{labels.get(k, k)} {_tolerance_text(summary['parameters'][k])}: S1 / ST"
        for k in names]
    rows = []
    for metric, (label, unit) in outputs.items():
        m = summary["metrics"].get(metric)
        if m is None:
            continue
        spread = 3 * m["std"]
        share = f" ({100 * spread / abs(m['mean']):.2g} %)" if m["mean"] else ""
        rows.append([label, number(m["mean"], unit), f"±{number(spread, unit)}{share}"] + [
            f"{m['first_order'][k]:.2f} / {m['total_order'][k]:.2f}" for k in names])
    return {"title": title, "columns": columns, "rows": rows}


def dominant(summary: dict, outputs: dict) -> str | None:
    """The toleranced parameter that matters most over ``outputs``: the one with the largest
    total-order index in most outputs (ties: the largest mean total-order index)."""
    shown = [summary["metrics"][m] for m in outputs if m in summary["metrics"]]
    if not shown:
        return None
    names = list(summary["parameters"])
    wins = {k: sum(m["dominant"] == k for m in shown) for k in names}
    mean = {k: float(np.mean([m["total_order"][k] for m in shown])) for k in names}
    return max(names, key=lambda k: (wins[k], mean[k]))


def _scatter(m: dict, unit: str) -> str:
    """An output's 3σ scatter as a % of its mean (absolute for a zero mean)."""
    if m["mean"]:
        return f"{100 * 3 * m['std'] / abs(m['mean']):.2g} %"
    return number(3 * m["std"], unit)


def sentence(summary: dict, outputs: dict, labels: dict, what: str) -> str:
    """'Of <what>, <the tolerance> matters most: ...' with each output's scatter and the share
    of its variance the dominant tolerance carries (its total-order Sobol index)."""
    top = dominant(summary, outputs)
    if top is None:
        return f"The tolerance study of {what} gave no analysable output."
    shown = {metric: summary["metrics"][metric] for metric in outputs
             if metric in summary["metrics"]}
    if len({m["dominant"] for m in shown.values()}) > 1:  # each output its own
        parts = [f"{outputs[metric][0]} scatters ±{_scatter(m, outputs[metric][1])} (3σ), "
                 f"{m['total_order'][m['dominant']]:.0%} of it from the "
                 f"{labels.get(m['dominant'], m['dominant'])} tolerance "
                 f"({_tolerance_text(summary['parameters'][m['dominant']])})"
                 for metric, m in shown.items()]
        return (f"Of {what}, the one that matters most depends on the output: "
                + "; ".join(parts) + f" (total-order Sobol indices, {summary['n_designs']} "
                "designs).")
    spec = summary["parameters"][top]
    parts = []
    for metric, (label, unit) in outputs.items():
        m = summary["metrics"].get(metric)
        if m is None:
            continue
        parts.append(f"{label} scatters ±{_scatter(m, unit)} (3σ), "
                     f"{m['total_order'][top]:.0%} of it from "
                     f"this tolerance" + ("" if m["dominant"] == top else
                                          f" ({labels.get(m['dominant'], m['dominant'])} "
                                          f"{m['total_order'][m['dominant']]:.0%})"))
    return (f"Of {what}, the {labels.get(top, top)} tolerance "
            f"({_tolerance_text(spec)}) matters most: " + "; ".join(parts)
            + f" (total-order Sobol indices, {summary['n_designs']} designs).")


def plot_indices(summary: dict, outputs: dict, labels: dict, path, caption: str) -> dict:
    """Per output, each tolerance's total-order Sobol index (bar, with SALib's 95 %
    bootstrap interval) and first-order index (dot)."""
    plt = pyplot()
    names = list(summary["parameters"])
    shown = [(metric, label) for metric, (label, _) in outputs.items()
             if metric in summary["metrics"]]
    fig, ax = plt.subplots(figsize=(6.4, 3.4))
    width = 0.8 / max(len(names), 1)
    for j, name in enumerate(names):
        x = np.arange(len(shown)) + (j - (len(names) - 1) / 2) * width
        m = [summary["metrics"][metric] for metric, _ in shown]
        ax.bar(x, [v["total_order"][name] for v in m], width * 0.9,
               yerr=[v["total_order_conf"][name] for v in m], capsize=3,
               label=f"{labels.get(name, name)} {_tolerance_text(summary['parameters'][name])}")
        ax.plot(x, [v["first_order"][name] for v in m], "k.", ms=8)
    ax.plot([], [], "k.", ms=8, label="first-order index S1")
    ax.set_xticks(np.arange(len(shown)), [label for _, label in shown])
    ax.set_ylabel("total-order Sobol index ST")
    ax.set_ylim(min(0.0, ax.get_ylim()[0]), max(1.05, ax.get_ylim()[1]))
    ax.axhline(0, color="0.5", lw=0.5)
    ax.grid(axis="y", alpha=0.3)
    ax.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=2, fontsize="small",
              frameon=False)
    fig.tight_layout()
    return save(fig, path, caption)


def confirm_table(checked: dict, outputs: dict, title: str) -> dict:
    """The extremes of each output by the screening and the confirming model."""
    rows = []
    for metric, (label, unit) in outputs.items():
        row = checked["metrics"].get(metric)
        if row is None:
            continue
        for end in ("low", "high"):
            r = row[end]
            diff = "-" if r["rel_diff"] is None else f"{100 * r['rel_diff']:+.2g} %"
            rows.append([f"{label}, {'lowest' if end == 'low' else 'highest'} sample",
                         number(r["screen"], unit), number(r["confirm"], unit), diff])
    model = ", ".join(f"{k} = {v}" for k, v in checked["options"].items())
    return {"title": title, "columns": ["design", "screening model", f"confirming ({model})",
                                        "difference"], "rows": rows}


def tolerance_report(table: dict, evaluate, folder, outputs: dict, labels: dict, what: str,
                     n: int | None = None, workers: int | None = 1, confirm: bool = False,
                     figure: str = "tolerances_sobol.png", prefix: str = "") -> dict:
    """Run the study of ``table`` with ``evaluate`` into ``folder`` (see
    :func:`run_tolerances`) and return
    {"summary" (with its "wall_time_s", s), "confirm", "table" (key table), "confirm_table"
    (with ``confirm``), "figure"
    (figure entry, file relative to the section folder), "sentence", "tables" (files
    relative to the section folder)}; ``prefix``: ``folder``'s path inside the section."""
    start = time.perf_counter()
    folder = Path(folder)
    study, summary, checked = run_tolerances(table, evaluate, folder, n, workers, confirm)
    (folder / "tolerances.json").write_text(__import__("json").dumps(
        {**summary, "confirm": checked}, indent=1, default=float))
    model = ", ".join(f"{k} = {v}" for k, v in study.options.items())
    text = sentence(summary, outputs, labels, what)
    caption = (f"Tolerance study of {what}: per output, the share of its variance each "
               f"tolerance carries (total-order Sobol index, bars with SALib's 95 % bootstrap "
               f"interval; dots: first-order), {summary['n_designs']} designs ({model}).")
    fig = plot_indices(summary, outputs, labels, folder / figure, caption)
    widths = [w for m in outputs if m in summary["metrics"]
              for w in summary["metrics"][m]["total_order_conf"].values()]
    conf = f"; total-order indices ±{max(widths):.2f} at 95 %" if widths else ""
    result = {"summary": summary, "confirm": checked, "sentence": text,
              "figure": {**fig, "file": f"{prefix}{fig['file']}"},
              "table": key_table(summary, outputs, labels,
                                 f"Tolerances: {what} ({summary['n_designs']} designs{conf})"),
              "tables": [f"{prefix}results.csv", f"{prefix}tolerances.json"]}
    if checked is not None:
        result["confirm_table"] = confirm_table(
            checked, outputs, "Tolerance extremes re-checked by the confirming model")
    result["summary"]["wall_time_s"] = time.perf_counter() - start
    return result


def add_to_section(summary: dict, result: dict, before: str | None = None) -> dict:
    """Put a :func:`tolerance_report` ``result`` into a section's ``summary``: its sentence
    (a note), its key table(s), its figure (last, or before the figure entry whose file is
    ``before``: printed figures go two a row) and its files; returns {"summary", "confirm"}
    for the section's JSON."""
    summary.setdefault("notes", []).append(result["sentence"])
    summary.setdefault("key_tables", []).append(result["table"])
    if "confirm_table" in result:
        summary["key_tables"].append(result["confirm_table"])
    figures = summary.setdefault("figures", [])
    at = next((i for i, f in enumerate(figures) if f["file"] == before), len(figures))
    figures.insert(at, result["figure"])
    summary.setdefault("tables", []).extend(result["tables"])
    return {"summary": result["summary"], "confirm": result["confirm"]}

