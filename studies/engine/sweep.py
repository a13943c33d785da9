"""Parameter studies of any mechanism: a grid, a list of cases or a space-filling sample.

A ``Study`` names a mechanism (studies/mechanisms.py resolves the name), a base design (parameters that override the
mechanism's own defaults), the evaluate options, and the designs to evaluate: the union of a
``grid`` (cartesian product of value lists), explicit ``cases`` and a ``sample`` (Latin
hypercube or Sobol, seeded, over [low, high] ranges). ``run_study`` evaluates the cases not
yet in the SQLite store (store.py), in parallel (executors.py), recording each as it completes;
a failing case is recorded with its error and never stops the study. Failed cases are not
re-run unless asked (``retry_failed``): a deterministic error would only fail again. A case
that the environment failed (status "error": a lost worker, an OSError, MemoryError,
ImportError or RuntimeError -- flexfem raises ValueError subclasses for a bad design) is
recorded with its cause and computed again by the next run.
"""
import itertools
import math
import os
import socket
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path

import tomllib

from ...fem import checks
from .checks import check_study, required_metrics, stale_rows, warn_stale
from .executors import make_executor
from .plots import plot_metric, pyplot  # noqa: F401  (engine.sweep.plot_metric, as before)
from .progress import Progress
from .tolerance import Tolerances, tolerances_from_dict
from .store import (
    CaseResult,
    ResultStore,
    canonical_json,
    case_key,
    flexfem_version,
)
from .validate import check_value, result_problems

SAMPLE_METHODS = ("lhs", "sobol")
STUDY_KEYS = {"mechanism", "name", "base", "options", "grid", "cases", "sample", "plots",
              "tolerances"}
SAMPLE_KEYS = {"method", "n", "seed", "ranges"}
PLOT_KEYS = {"metric", "parameter", "overlay"}
MAX_CASES = 100_000  # designs a study may expand to unless run_study(max_cases=...) says more
MAX_KEYS = 1_000  # names a study's base, options, grid or sample ranges may hold: a mechanism
#                   has tens of parameters; more is a generated file gone wrong


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
        checks.one_of("sample.method", self.method, SAMPLE_METHODS)
        checks.count("sample.n", self.n)
        if not self.ranges:
            raise ValueError("sample.ranges is empty: give at least one parameter range")
        for name, bounds in self.ranges.items():
            if not (isinstance(bounds, (list, tuple)) and len(bounds) == 2
                    and all(isinstance(b, (int, float)) and not isinstance(b, bool)
                            and math.isfinite(b) for b in bounds)):
                raise ValueError(f"sample.ranges.{name} = {bounds!r} must be [low, high], "
                                 "finite numbers")
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
    tolerances: Tolerances | None = None

    def __post_init__(self):
        if not isinstance(self.mechanism, str) or not self.mechanism.strip():
            raise ValueError(f"mechanism = {self.mechanism!r} must be a mechanism's name")
        if (not isinstance(self.name, str) or not self.name.strip() or self.name in (".", "..")
                or any(c in self.name for c in "/\\\0")):
            raise ValueError(f"name = {self.name!r} must be a non-empty file name (no '/', "
                             "'\\', '.' or '..'): the study's default output folder")
        for name, values in self.grid.items():
            if not isinstance(values, (list, tuple)):
                raise ValueError(f"grid.{name} = {values!r} must be a list of values")
            if len(values) == 0:
                raise ValueError(f"grid.{name} is empty: give at least one value")
        for i, case in enumerate(self.cases):
            if not isinstance(case, dict):
                raise ValueError(f"cases[{i}] = {case!r} must be a table of parameters")
        self._check_values()

    def _check_values(self) -> None:
        """No number written as a string anywhere (it would hash as another case), and
        nothing that cannot be part of a case key (store.canonical_json)."""
        named = [(f"{table}.{name}", value) for table in ("base", "options")
                 for name, value in getattr(self, table).items()]
        named += [(f"grid.{name}", value) for name, values in self.grid.items() for value in values]
        named += [(f"cases[{i}].{name}", value) for i, case in enumerate(self.cases)
                  for name, value in case.items()]
        for where, value in named:
            check_value(where, value)
            try:
                canonical_json(value)
            except ValueError as error:
                raise ValueError(f"{where} = {value!r}: {error}") from None

    def case_count(self) -> int:
        """How many designs the study expands to (before duplicates are dropped), computed
        without expanding it."""
        grid = math.prod(len(v) for v in self.grid.values()) if self.grid else 0
        total = grid + len(self.cases) + (self.sample.n if self.sample is not None else 0)
        return max(total, 1)


def study_from_dict(data: dict) -> Study:
    """A Study from the parsed TOML layout (see docs/studies.md); ValueError names bad keys."""
    _check_keys(data, STUDY_KEYS, "")
    if "mechanism" not in data:
        raise ValueError("missing key mechanism (a registered name or 'module:function')")
    for key in ("base", "options", "grid"):
        table = data.get(key, {})
        if isinstance(table, dict) and len(table) > MAX_KEYS:
            raise ValueError(f"[{key}] has {len(table):,} entries; a study names at most "
                             f"{MAX_KEYS:,} parameters (a mechanism has tens)")
        _check_keys(table, set(table), key)
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
    tolerances = (tolerances_from_dict(data["tolerances"]) if "tolerances" in data else None)
    return Study(mechanism=data["mechanism"], name=data.get("name", "study"),
                 base=dict(data.get("base", {})), options=dict(data.get("options", {})),
                 grid=dict(data.get("grid", {})), cases=tuple(data.get("cases", ())),
                 sample=sample, plots=tuple(plots), tolerances=tolerances)


def read_study_file(path) -> dict:
    """The parsed TOML of a study file, named after the file unless it names itself
    (FileNotFoundError if missing, ValueError if not TOML)."""
    path = Path(path)
    with path.open("rb") as f:
        try:
            data = tomllib.load(f)
        except tomllib.TOMLDecodeError as error:
            raise ValueError(f"{path}: not valid TOML: {error}") from error
    data.setdefault("name", path.stem)
    return data


def load_study(path) -> Study:
    """Read a study file (docs/studies.md).

    Parameters
    ----------
    path : str or os.PathLike
        The study TOML file: its evaluate target, base design and what it varies (values in
        the units of the target's parameters, SI for flexfem's own).

    Returns
    -------
    Study
        The checked study, for :func:`run_study`.

    Raises
    ------
    FileNotFoundError
        The file does not exist.
    ValueError
        One line naming what is wrong in it.
    """
    return study_from_dict(read_study_file(path))


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
    if study.tolerances is not None:
        varied += study.tolerances.points()
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


# raised by the machine, not the design: the case is computed again by the next run
ENVIRONMENT_ERRORS = (OSError, MemoryError, ImportError, RuntimeError, SystemError)


def failure_status(exc: BaseException) -> str:
    """"error" when ``exc`` comes from the environment (ENVIRONMENT_ERRORS, but not
    NotImplementedError, or an error marked ``environmental``: a mesh above this machine's
    memory budget), else "failed" (the design)."""
    environment = (isinstance(exc, ENVIRONMENT_ERRORS) and not isinstance(exc, NotImplementedError)
                   or getattr(exc, "environmental", False) is True)
    return "error" if environment else "failed"


def run_case(task: dict) -> dict:
    """Evaluate one task (in whatever process runs it); never raises for a failing case.

    Returns {status ("ok", "failed" or "error", see failure_status), metrics, error
    ("Type: message"), wall_time_s (s), dofs, worker}.
    """
    start = time.perf_counter()
    try:
        metrics = {str(k): _as_metric(v) for k, v in task["evaluate"](dict(task["params"]),
                                                                      **task["options"]).items()}
        problems = result_problems(metrics, task["evaluate"])  # as a stored row's (checks.py)
        if problems:
            raise ValueError(f"result check: {'; '.join(problems)}")
        status, error = "ok", None
    except Exception as exc:  # a failing case is a result, not the end of the study
        metrics, status = {}, failure_status(exc)
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
        result = {"status": "error", "metrics": {}, "error": lost}
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


def run_study(study: Study, store_path, evaluate, workers: int | None = None,
              scheduler: str | None = None, retry_failed: bool = False,
              progress: bool | None = None, max_cases: int = MAX_CASES) -> StudyResult:
    """Evaluate the study's cases missing from the store, recording each as it completes.

    Parameters
    ----------
    study : Study
        The study (:func:`load_study`): its base design, the grid or samples varied (values in
        the units of ``evaluate``'s parameters, SI for flexfem's own) and the options.
    store_path : str or os.PathLike
        The SQLite case store; a case stored earlier (and passing the checks of a fresh
        result, checks.py) is reused, not recomputed.
    evaluate : callable
        ``evaluate(params, **options) -> {metric: value}``, a module-level function (worker
        processes import it); its options are normalised to the types it declares
        (validate.normalise_options) and the names checked before any case runs.
    workers : int, optional
        Local processes (None: one per CPU; 1: in this process).
    scheduler : str, optional
        A Dask address "tcp://HOST:PORT" (None: the FLEXFEM_SCHEDULER variable, else local).
    retry_failed : bool
        Run again the cases stored as failed.
    progress : bool, optional
        Draw a progress line on stderr (None: when stderr is a terminal).
    max_cases : int
        A study of more designs (-) is refused before it is expanded.

    Returns
    -------
    StudyResult
        The cases (stored earlier or now), how many were computed and reused, the executor
        and the wall time (s). On Ctrl-C the cases in flight are stopped and
        KeyboardInterrupt propagates; what completed stays stored.
    """
    start = time.perf_counter()
    count = study.case_count()
    if count > max_cases:
        raise ValueError(f"study {study.name!r} has {count:,} cases, above the limit of "
                         f"{max_cases:,}: split it, or raise the limit (--max-cases)")
    study = check_study(study, evaluate)  # names and options, before any case (checks.py)
    tasks = [{**task, "evaluate": evaluate} for task in study_tasks(study)]
    executor = make_executor(workers, scheduler)
    with ResultStore(store_path) as store:
        statuses = store.statuses()
        stale = stale_rows(store, [t["key"] for t in tasks if statuses.get(t["key"]) == "ok"],
                           evaluate, required_metrics(study))
        warn_stale(stale, store_path)
        todo = [t for t in tasks if statuses.get(t["key"], "error") == "error"
                or (retry_failed and statuses[t["key"]] == "failed") or t["key"] in stale]
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
