"""A Pareto front in a mechanism's report section: a front file's table (as examples/*_front.toml
declare it) searched by the study engine's NSGA-II (engine/front.py) into the section's
folder, one figure with the reference designs placed on the front, one short key table and a
sentence.

    result = front_report(table, evaluate, out_dir / "front", labels, "the trade-off",
                          population=8, generations=3)

``labels`` {metric: (label, unit)} names the objectives and constraints. SI units.
"""
import json
from pathlib import Path
import time

from .figures import axis_label, pyplot, save
from .format import number
from .tolerances import one_blas_thread


def run_front(table: dict, evaluate, folder, population: int | None = None,
              generations: int | None = None, confirm: bool = True,
              references: tuple = ()) -> tuple:
    """(front, result): the front of the parsed front-file ``table`` (its search's
    population and generations replaced where given; without ``confirm`` its [confirm]
    dropped; ``references`` (name, params) added to its own) searched with ``evaluate`` (the
    mechanism's) into ``folder`` (evaluations.sqlite, front.json)."""
    from ..engine.front import front_from_dict, search_front

    table = dict(table)
    search = dict(table.get("search", {}))
    if population is not None:
        search["population"] = population
    if generations is not None:
        search["generations"] = generations
    table["search"] = search
    if not confirm:
        table.pop("confirm", None)
    table["reference"] = list(table.get("reference", [])) + [
        {"name": name, "params": dict(params)} for name, params in references]
    table.pop("name", None)
    front = front_from_dict(table)
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    with one_blas_thread():  # the beam model's small solves: ~10x faster on one thread
        result = search_front(front, evaluate, folder / "evaluations.sqlite")
    (folder / "front.json").write_text(json.dumps(result, indent=1, default=float))
    return front, result


def plot(front, result: dict, labels: dict, path, caption: str) -> dict:
    """The front in its first two objectives: the screening model's designs (dots, joined),
    the confirming model's values at them (crosses, joined to their screening point) and the
    references (stars and crosses, each with how many front designs dominate it)."""
    plt = pyplot()
    (a, _), (b, _) = front.objectives[:2]
    designs = sorted(result["designs"], key=lambda d: d["objectives"][a])
    fig, ax = plt.subplots(figsize=(6.4, 3.6))
    ax.plot([d["objectives"][a] for d in designs], [d["objectives"][b] for d in designs], "o-",
            ms=4, lw=0.8, label=f"front, screening model ({len(designs)})")
    confirmed = [(d["objectives"], d["confirmed"]) for d in designs if d.get("confirmed")]
    for k, (screen, check) in enumerate(confirmed):
        ax.plot([screen[a], check[a]], [screen[b], check[b]], "-", color="tab:orange", lw=0.6)
        ax.plot(check[a], check[b], "x", color="tab:orange",
                label="confirming model" if k == 0 else None)
    for ref, marker, colour in zip(result["references"], "*Ps^",
                                   ("tab:red", "tab:green", "tab:purple", "tab:brown")):
        feasible = all(v >= 0 for v in ref["margins"].values())
        ax.plot(ref["objectives"][a], ref["objectives"][b], marker, ms=13, color=colour,
                label=f"{ref['name']}: dominated by {ref['dominated_by']}"
                      f"{'' if feasible else ', infeasible'}")
    ax.set_xlabel(axis_label(*labels.get(a, (a, None))))
    ax.set_ylabel(axis_label(*labels.get(b, (b, None))))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    return save(fig, path, caption)


def key_table(front, result: dict, labels: dict, title: str, rows: int = 5,
              defaults: dict | None = None) -> dict:
    """At most ``rows`` designs spread along the front, then the references: the varied
    parameters (``defaults`` {name: value} for those a reference leaves to the mechanism),
    the objectives (the confirming model's beside where given) and the smallest
    constraint margin."""
    names = list(front.variables)
    defaults = defaults or {}
    designs = sorted(result["designs"], key=lambda d: d["objectives"][front.objectives[0][0]])
    if len(designs) > rows:
        step = (len(designs) - 1) / (rows - 1)
        designs = [designs[round(i * step)] for i in range(rows)]
    columns = ["design"] + [f"{n} (mm)" for n in names]
    for metric, _ in front.objectives:
        label, unit = labels.get(metric, (metric, ""))
        columns.append(label)
    columns.append("smallest constraint margin (< 0: missed)")

    def margin(m: dict) -> str:
        if not m:
            return "-"
        metric = min(m, key=lambda k: m[k] / max(abs(_bound(front, k)), 1e-300))
        label, unit = labels.get(metric, (metric, ""))
        return f"{label} {number(m[metric], unit)}"

    def cells(name, d, check=None):
        params = {**defaults, **d["params"]}
        out = [name] + [f"{params[n] * 1e3:.3f}" if n in params else "default" for n in names]
        for metric, _ in front.objectives:
            unit = labels.get(metric, (metric, ""))[1]
            value = number(d["objectives"][metric], unit)
            if check:
                value += f" ({number(check[metric], unit)})"
            out.append(value)
        return out + [margin(d["margins"])]

    body = [cells(f"front {i + 1}", d, d.get("confirmed")) for i, d in enumerate(designs)]
    body += [cells(r["name"], r) for r in result["references"]]
    return {"title": title, "columns": columns, "rows": body}


def _bound(front, metric: str) -> float:
    return next(bound for m, _, bound in front.constraints if m == metric)


def sentence(front, result: dict, labels: dict) -> str:
    """Where each reference sits against the front, and the front's span."""
    (a, _), (b, _) = front.objectives[:2]
    la, ua = labels.get(a, (a, ""))
    lb, ub = labels.get(b, (b, ""))
    designs = result["designs"]
    if not designs:
        return "The front search found no feasible design."
    span = (f"The front ({len(designs)} designs, {result['evaluations']} evaluations) trades "
            f"{la} from {number(min(d['objectives'][a] for d in designs), ua)} to "
            f"{number(max(d['objectives'][a] for d in designs), ua)} against {lb} from "
            f"{number(min(d['objectives'][b] for d in designs), ub)} to "
            f"{number(max(d['objectives'][b] for d in designs), ub)}")
    placed = []
    for ref in result["references"]:
        feasible = all(v >= 0 for v in ref["margins"].values())
        short = [f"{labels.get(m, (m, ''))[0]} short by {number(-v, labels.get(m, (m, ''))[1])}"
                 for m, v in ref["margins"].items() if v < 0]
        placed.append(f"{ref['name']} ({la} {number(ref['objectives'][a], ua)}, {lb} "
                      f"{number(ref['objectives'][b], ub)}) is "
                      + (f"dominated by {ref['dominated_by']} front designs"
                         if ref["dominated_by"] else "dominated by no front design")
                      + ("" if feasible else f" but infeasible ({', '.join(short)})"))
    return span + ("; " + "; ".join(placed) if placed else "") + "."


def front_report(table: dict, evaluate, folder, labels: dict, what: str,
                 population: int | None = None,
                 generations: int | None = None, confirm: bool = True, references: tuple = (),
                 figure: str = "front.png", prefix: str = "", defaults: dict | None = None) -> dict:
    """Search the front of ``table`` with ``evaluate`` into ``folder`` (see :func:`run_front`)
    and return
    {"result", "sentence", "figure" (entry relative to the section folder), "table" (key
    table), "tables" (files relative to the section folder)}; the result carries its
    "wall_time_s" (s)."""
    start = time.perf_counter()
    folder = Path(folder)
    front, result = run_front(table, evaluate, folder, population, generations, confirm,
                              references)
    model = ", ".join(f"{k} = {v}" for k, v in front.options.items())
    cons = "; ".join(f"{labels.get(m, (m, ''))[0]} {'≥' if s == '>=' else '≤'} "
                     f"{number(v, labels.get(m, (m, ''))[1])}" for m, s, v in front.constraints)
    checked = ""
    if front.confirm and any(d.get("confirmed") for d in result["designs"]):
        confirming = ", ".join(f"{k} = {v}" for k, v in front.confirm.items())
        checked = f"; crosses: the confirming model's values at the front's designs ({confirming})"
    caption = (f"The Pareto front of {what} by NSGA-II ({front.population} designs x "
               f"{front.generations} generations, {model}) under {cons}{checked}; the "
               "reference designs placed on it.")
    fig = plot(front, result, labels, folder / figure, caption)
    result["wall_time_s"] = time.perf_counter() - start
    return {"result": result, "sentence": sentence(front, result, labels),
            "figure": {**fig, "file": f"{prefix}{fig['file']}"},
            "table": key_table(front, result, labels,
                               f"Pareto front of {what} (objectives: confirming model's in "
                               "brackets where run)", defaults=defaults),
            "tables": [f"{prefix}front.json"]}
