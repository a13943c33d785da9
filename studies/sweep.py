"""Parameter studies of any mechanism: a grid, a list of cases or a space-filling sample.

A ``Study`` names a mechanism (see registry.py), a base design (parameters that override the
mechanism's own defaults), the evaluate options, and the designs to evaluate: the union of a
``grid`` (cartesian product of value lists), explicit ``cases`` and a ``sample`` (Latin
hypercube or Sobol, seeded, over [low, high] ranges). ``run_study`` evaluates the cases not
yet in the SQLite store (store.py), in parallel (executors.py), recording each as it completes;
a failing case is recorded with its error and never stops the study. Failed cases are not
re-run unless asked (``retry_failed``): a deterministic error would only fail again.
"""
from dataclasses import dataclass, field
import itertools
import math
import os
from pathlib import Path
import socket
import time
import tomllib
import traceback

from .executors import make_executor
from .progress import Progress
from .registry import check_mechanism, get_evaluator
from .store import (CaseResult, ResultStore, case_key, export_csv,
                                   export_parquet, flexfem_version, parquet_available)

SAMPLE_METHODS = ("lhs", "sobol")
STUDY_KEYS = {"mechanism", "name", "base", "options", "grid", "cases", "sample", "plots"}
SAMPLE_KEYS = {"method", "n", "seed", "ranges"}
PLOT_KEYS = {"metric", "parameter", "overlay"}


def _check_keys(table: dict, allowed: set, where: str) -> None:
    if not isinstance(table, dict):
        raise ValueError(f"{where or 'study'} must be a table, got {table!r}")
    unknown = sorted(set(table) - allowed)
    if unknown:
        prefix = f"{where}." if where else ""
        raise ValueError(f"unknown key {prefix}{unknown[0]}; allowed: {sorted(allowed)}")


@dataclass(frozen=True)
class Sample:
    """A space-filling sample of ``n`` designs over ``ranges`` ({name: (low, high)}, SI),
    by scipy.stats.qmc Latin hypercube ("lhs") or scrambled Sobol ("sobol"), seeded."""

    ranges: dict
    n: int
    method: str = "lhs"
    seed: int = 0

    def __post_init__(self):
        if self.method not in SAMPLE_METHODS:
            raise ValueError(f"sample.method = {self.method!r} must be one of {SAMPLE_METHODS}")
        if not isinstance(self.n, int) or self.n < 1:
            raise ValueError(f"sample.n = {self.n!r} must be an integer >= 1")
        if not self.ranges:
            raise ValueError("sample.ranges is empty: give at least one parameter range")
        for name, bounds in self.ranges.items():
            if not (isinstance(bounds, (list, tuple)) and len(bounds) == 2
                    and all(isinstance(b, (int, float)) for b in bounds)):
                raise ValueError(f"sample.ranges.{name} = {bounds!r} must be [low, high]")
            if not bounds[0] < bounds[1]:
                raise ValueError(f"sample.ranges.{name} = {list(bounds)!r}: lower bound "
                                 f"{bounds[0]} must be < upper bound {bounds[1]} (empty range)")

    def points(self) -> list[dict]:
        """The ``n`` sampled designs, {name: value}."""
        import warnings
        from scipy.stats import qmc

        names = list(self.ranges)
        if self.method == "lhs":
            sampler = qmc.LatinHypercube(d=len(names), seed=self.seed)
        else:
            sampler = qmc.Sobol(d=len(names), scramble=True, seed=self.seed)
        with warnings.catch_warnings():  # Sobol balance warning when n is not a power of 2
            warnings.simplefilter("ignore", UserWarning)
            unit = sampler.random(self.n)
        low = [self.ranges[k][0] for k in names]
        high = [self.ranges[k][1] for k in names]
        scaled = qmc.scale(unit, low, high)
        return [{k: float(v) for k, v in zip(names, row)} for row in scaled]


@dataclass(frozen=True)
class PlotSpec:
    """A figure of a study: ``metric`` against ``parameter``, with ``overlay`` metrics dashed."""

    metric: str
    parameter: str
    overlay: tuple = ()


@dataclass(frozen=True)
class Study:
    """A mechanism, its base design, evaluate options and the designs to vary (see module)."""

    mechanism: str
    name: str = "study"
    base: dict = field(default_factory=dict)
    options: dict = field(default_factory=dict)
    grid: dict = field(default_factory=dict)
    cases: tuple = ()
    sample: Sample | None = None
    plots: tuple = ()

    def __post_init__(self):
        check_mechanism(self.mechanism)
        if not isinstance(self.name, str) or not self.name.strip() or "/" in self.name:
            raise ValueError(f"name = {self.name!r} must be a non-empty name without '/'")
        for name, values in self.grid.items():
            if not isinstance(values, (list, tuple)):
                raise ValueError(f"grid.{name} = {values!r} must be a list of values")
            if len(values) == 0:
                raise ValueError(f"grid.{name} is empty: give at least one value")
        for i, case in enumerate(self.cases):
            if not isinstance(case, dict):
                raise ValueError(f"cases[{i}] = {case!r} must be a table of parameters")


def study_from_dict(data: dict) -> Study:
    """A Study from the parsed TOML layout (see docs/studies.md); ValueError names bad keys."""
    _check_keys(data, STUDY_KEYS, "")
    if "mechanism" not in data:
        raise ValueError("missing key mechanism (a registered name or 'module:function')")
    for key in ("base", "options", "grid"):
        _check_keys(data.get(key, {}), set(data.get(key, {})), key)
    sample = None
    if "sample" in data:
        table = data["sample"]
        _check_keys(table, SAMPLE_KEYS, "sample")
        for key in ("n", "ranges"):
            if key not in table:
                raise ValueError(f"missing key sample.{key}")
        sample = Sample(ranges=dict(table["ranges"]), n=table["n"],
                        method=table.get("method", "lhs"), seed=table.get("seed", 0))
    plots = []
    for i, table in enumerate(data.get("plots", [])):
        _check_keys(table, PLOT_KEYS, f"plots[{i}]")
        if "metric" not in table or "parameter" not in table:
            raise ValueError(f"plots[{i}] needs both metric and parameter")
        plots.append(PlotSpec(table["metric"], table["parameter"], tuple(table.get("overlay", ()))))
    return Study(mechanism=data["mechanism"], name=data.get("name", "study"),
                 base=dict(data.get("base", {})), options=dict(data.get("options", {})),
                 grid=dict(data.get("grid", {})), cases=tuple(data.get("cases", ())),
                 sample=sample, plots=tuple(plots))


def load_study(path) -> Study:
    """Read a study TOML file (FileNotFoundError if missing, ValueError if invalid)."""
    path = Path(path)
    with path.open("rb") as f:
        try:
            data = tomllib.load(f)
        except tomllib.TOMLDecodeError as error:
            raise ValueError(f"{path}: not valid TOML: {error}") from error
    data.setdefault("name", path.stem)
    return study_from_dict(data)


def design_points(study: Study) -> list[dict]:
    """Every design of the study, each the base merged with its varied values; duplicates
    kept (the runner drops them by key). Only the base when nothing is varied."""
    varied = []
    if study.grid:
        names = list(study.grid)
        varied += [dict(zip(names, values)) for values in itertools.product(*study.grid.values())]
    varied += [dict(case) for case in study.cases]
    if study.sample is not None:
        varied += study.sample.points()
    return [{**study.base, **point} for point in varied] or [dict(study.base)]


def study_tasks(study: Study, version: str | None = None) -> list[dict]:
    """One task {key, mechanism, params, options} per distinct design, in design order."""
    version = flexfem_version() if version is None else version
    tasks = {}
    for params in design_points(study):
        key = case_key(study.mechanism, params, study.options, version)
        tasks.setdefault(key, {"key": key, "mechanism": study.mechanism, "params": params,
                               "options": dict(study.options), "flexfem_version": version})
    return list(tasks.values())


def _as_metric(value):
    try:
        return float(value)
    except (TypeError, ValueError):
        return str(value)


def run_case(task: dict) -> dict:
    """Evaluate one task (in whatever process runs it); never raises for a failing case.

    Returns {status, metrics, error ("Type: message"), wall_time_s (s), dofs, worker}.
    """
    start = time.perf_counter()
    try:
        evaluate = get_evaluator(task["mechanism"])
        metrics = {str(k): _as_metric(v) for k, v in evaluate(dict(task["params"]),
                                                               **task["options"]).items()}
        status, error = "ok", None
    except Exception as exc:  # a failing case is a result, not the end of the study
        metrics, status = {}, "failed"
        error = f"{type(exc).__name__}: {exc}"
        last = traceback.extract_tb(exc.__traceback__)[-1:]
        if last:
            error += f" (at {Path(last[0].filename).name}:{last[0].lineno})"
    dofs = metrics.get("dofs")
    return {"status": status, "metrics": metrics, "error": error,
            "wall_time_s": time.perf_counter() - start,
            "dofs": int(dofs) if isinstance(dofs, float) and math.isfinite(dofs) else None,
            "worker": f"{socket.gethostname()}:{os.getpid()}"}


def _case_result(task: dict, result: dict | None, lost: str | None) -> CaseResult:
    if result is None:
        result = {"status": "failed", "metrics": {}, "error": lost}
    return CaseResult(key=task["key"], mechanism=task["mechanism"], params=task["params"],
                      options=task["options"], flexfem_version=task["flexfem_version"], **result)


@dataclass(frozen=True)
class StudyResult:
    """The cases of a study (stored earlier or now), how many were computed this run, how
    many were reused from the store, the executor used and the wall time (s)."""

    study: Study
    store_path: Path
    cases: list
    computed: int
    reused: int
    executor: str
    wall_time_s: float

    @property
    def failed(self) -> list:
        return [c for c in self.cases if not c.ok]


def run_study(study: Study, store_path, workers: int | None = None, scheduler: str | None = None,
              retry_failed: bool = False, progress: bool | None = None) -> StudyResult:
    """Evaluate the study's cases missing from the store at ``store_path`` (and the failed
    ones when ``retry_failed``), recording each as it completes.

    ``workers``: local processes (None: one per CPU; 1: in this process). ``scheduler``:
    a Dask address "tcp://HOST:PORT" (default: the FLEXFEM_SCHEDULER variable). ``progress``:
    draw a progress line on stderr (None: when stderr is a terminal). On Ctrl-C the cases in
    flight are stopped and KeyboardInterrupt propagates; what completed stays stored.
    """
    start = time.perf_counter()
    tasks = study_tasks(study)
    executor = make_executor(workers, scheduler)
    with ResultStore(store_path) as store:
        statuses = store.statuses()
        todo = [t for t in tasks if t["key"] not in statuses
                or (retry_failed and statuses[t["key"]] == "failed")]
        bar = Progress(len(todo), enabled=progress)
        try:
            if todo:
                with executor:
                    for task, result, lost in executor.run(run_case, todo):
                        case = _case_result(task, result, lost)
                        store.record(case)
                        bar.update(case.ok)
        finally:
            bar.close()
        cases = store.results([t["key"] for t in tasks])
    return StudyResult(study=study, store_path=Path(store_path), cases=cases, computed=len(todo),
                       reused=len(tasks) - len(todo), executor=executor.description,
                       wall_time_s=time.perf_counter() - start)


def plot_metric(cases, metric: str, parameter: str, path, overlay=()) -> Path:
    """PNG of ``metric`` against ``parameter`` over the successful ``cases`` (CaseResult),
    one line per combination of the other varied parameters, ``overlay`` metrics (e.g. the
    analytical value) dashed or dotted in the same colour; designs that share no line with
    another (a space-filling sample) as grey points."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ok = [c for c in cases if c.ok and parameter in c.params and metric in c.metrics]
    if not ok:
        raise ValueError(f"no successful case has both parameter {parameter!r} and metric {metric!r}")
    others = sorted({k for c in ok for k in c.params if k != parameter
                     and len({repr(d.params.get(k)) for d in ok}) > 1})
    groups = {}
    for case in ok:
        groups.setdefault(tuple(case.params.get(k) for k in others), []).append(case)
    lines = {k: v for k, v in groups.items() if len(v) > 1}
    scattered = [c for v in groups.values() if len(v) == 1 for c in v]
    styles = itertools.cycle(["--", ":", "-."])
    overlay_styles = {name: next(styles) for name in overlay}
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for (label_values, members), colour in zip(sorted(lines.items(), key=lambda g: repr(g[0])),
                                               itertools.cycle(plt.rcParams["axes.prop_cycle"].by_key()["color"])):
        members.sort(key=lambda c: c.params[parameter])
        x = [c.params[parameter] for c in members]
        label = ", ".join(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}"
                          for k, v in zip(others, label_values))
        ax.plot(x, [c.metrics[metric] for c in members], "o-", color=colour,
                label=f"{metric} {label}".strip())
        for name in overlay:
            ax.plot(x, [c.metrics.get(name, math.nan) for c in members], overlay_styles[name],
                    color=colour, label=f"{name} {label}".strip())
    if scattered:  # designs that share no line with another (e.g. a space-filling sample)
        ax.plot([c.params[parameter] for c in scattered], [c.metrics[metric] for c in scattered],
                "o", color="0.35", label=f"{metric}, other designs ({len(scattered)})")
    if len(lines) * (1 + len(overlay)) + bool(scattered) <= 12:
        ax.legend(fontsize="small")
    ax.set_xlabel(parameter)
    ax.set_ylabel(metric)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return Path(path)


def sweep(study, out_dir=None, workers: int | None = None, scheduler: str | None = None,
          retry_failed: bool = False, progress: bool | None = None) -> dict:
    """Run a study (a Study or the path of its TOML file) into ``out_dir`` (default: a folder
    named after the study): results.sqlite, results.csv (and .parquet with pyarrow), the
    study's plots. Returns a JSON-able summary with every case's row."""
    if not isinstance(study, Study):
        study = load_study(study)
    out = Path(out_dir if out_dir is not None else study.name)
    result = run_study(study, out / "results.sqlite", workers=workers, scheduler=scheduler,
                       retry_failed=retry_failed, progress=progress)
    tables = [export_csv(result.cases, out / "results.csv").name]
    if parquet_available():
        tables.append(export_parquet(result.cases, out / "results.parquet").name)
    figures = []
    for spec in study.plots:
        path = out / f"{spec.metric}_vs_{spec.parameter}.png"
        figures.append(plot_metric(result.cases, spec.metric, spec.parameter, path, spec.overlay).name)
    return {"name": study.name, "mechanism": study.mechanism, "out": str(out),
            "store": str(result.store_path), "executor": result.executor,
            "cases": len(result.cases), "computed": result.computed, "reused": result.reused,
            "failed": len(result.failed), "wall_time_s": result.wall_time_s,
            "tables": tables, "figures": figures,
            "failures": [{"params": c.params, "error": c.error} for c in result.failed],
            "results": [c.to_row() for c in result.cases]}


def reproduce(out_dir, quick: bool = False) -> dict:
    """The engine's own check for the reproduction report, on the toy cantilever: a sweep
    against the closed form, and a convergence study against the known order 2 and the exact
    taper integral. Writes CSV tables and PNG figures into ``out_dir``."""
    import csv
    from .convergence import converge, default_levels, plot_convergence
    from .toy import CantileverParams, tip_deflection_exact

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    lengths = [0.05, 0.1, 0.15] if quick else [0.04, 0.06, 0.08, 0.1, 0.12, 0.15]
    study = Study("toy", name="toy_sweep", grid={"length_m": lengths, "width_m": [0.005, 0.01]})
    result = run_study(study, out / "toy_sweep.sqlite", workers=1, progress=False)
    export_csv(result.cases, out / "toy_sweep.csv")
    plot_metric(result.cases, "tip_deflection", "length_m", out / "toy_tip_deflection.png",
                overlay=["tip_deflection_analytical"])
    taper = {"thickness_tip_m": 0.001}
    conv = converge("toy", "tip_deflection", default_levels(4 if quick else 6), params=taper, tol=0.005)
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
