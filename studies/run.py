"""Studies of registered mechanisms by name: a study file or a convergence study, its
mechanism found in the registry (studies/mechanisms.py), run by the engine (studies/engine/)."""
import functools
import json
import math
import re
from pathlib import Path

from .engine import sweep as engine
from .engine.convergence import (
    converge,
    default_levels,
    parse_tolerance,
    plot_convergence,
)
from .engine.store import export_csv, export_parquet, parquet_available
from .engine.sweep import Study, plot_metric
from .engine.tolerance import confirm_extremes, summarize
from .engine.validate import check_metric_names, check_parameter_names, declared_options
from .out_folder import check_out, prepare_out
from .mechanisms import (
    MODEL_PREFIX,
    check_mechanism,
    coarsest_size_factor,
    get_evaluator,
    model_mechanism,
    quantity_units,
    verify_model_mechanism,
)


#: Options the command line owns: a study file cannot set them (studies_rights).
COMMAND_LINE_OPTIONS = {"allow_code": "--allow-code on the command line",
                        "file": "the model file the mechanism names"}
#: Value endings of a file: a study's values are numbers and names, never paths.
_FILE_SUFFIXES = (".toml", ".geo", ".step", ".stp", ".brep", ".msh", ".py", ".sqlite",
                  ".json", ".csv", ".parquet")


def _path_like(value) -> bool:
    return isinstance(value, str) and ("/" in value or "\\" in value
                                       or value.lower().endswith(_FILE_SUFFIXES))


def check_rights(data: dict, source: str = "study") -> None:
    """Refuse what only the command line may grant, in a parsed study or front file
    ``source``: an option the command line owns (allow_code, file), a path as any value, a
    mechanism named by path and digest ("model:...": a study names its model as
    ``{ model = "FILE.toml" }``). ValueError naming ``source`` and the key."""
    if not isinstance(data, dict):
        return
    mechanism = data.get("mechanism")
    if isinstance(mechanism, str) and mechanism.startswith(MODEL_PREFIX):
        raise ValueError(f"{source}: mechanism = {mechanism!r} names a model file by path and "
                         "digest; a study names its model inside its own folder, mechanism = "
                         "{ model = \"FILE.toml\" } (pass --allow-code to lift this)")
    tables = {key: data.get(key) for key in ("options", "confirm", "base")}
    tolerances = data.get("tolerances")
    if isinstance(tolerances, dict):
        tables["tolerances.confirm"] = tolerances.get("confirm")
    tables["grid"] = data.get("grid")
    cases = data.get("cases")
    for i, case in enumerate(cases if isinstance(cases, list) else ()):
        tables[f"cases[{i}]"] = case
    for where, table in tables.items():
        if not isinstance(table, dict):
            continue
        for name, value in table.items():
            if name in COMMAND_LINE_OPTIONS and where != "base":
                raise ValueError(f"{source}: {where}.{name} is not a study's to set: it is "
                                 f"{COMMAND_LINE_OPTIONS[name]} (a study cannot widen its own "
                                 "rights)")
            values = value if isinstance(value, list) else [value]
            if any(_path_like(v) for v in values):
                raise ValueError(f"{source}: {where}.{name} = {value!r} is a path; a study's "
                                 "values are numbers and names, its one file is its model "
                                 "(mechanism = { model = \"FILE.toml\" })")


def _mechanism_of(data: dict, base_dir, allow_code: bool, source: str):
    """The study's mechanism name: a model table resolved inside ``base_dir``; a "model:..."
    name (only with ``allow_code``) checked against its file's digest."""
    mechanism = data.get("mechanism") if isinstance(data, dict) else None
    if isinstance(mechanism, dict):
        if set(mechanism) != {"model"}:
            raise ValueError(f"{source}: mechanism = {mechanism!r}: a table must be "
                             "{ model = \"FILE.toml\" }")
        try:
            return model_mechanism(mechanism["model"], base_dir, allow_code)
        except ValueError as error:
            raise ValueError(f"{source}: {error}") from None
    if isinstance(mechanism, str) and mechanism.startswith(MODEL_PREFIX):
        try:
            return verify_model_mechanism(mechanism)
        except ValueError as error:
            raise ValueError(f"{source}: {error}") from None
    return mechanism


def study_from_dict(data: dict, base_dir=None, allow_code: bool = False,
                    source: str = "study") -> Study:
    """The engine's ``study_from_dict``, its mechanism checked against the registry (a
    "module:function" only with ``allow_code``, see studies/mechanisms.py); a
    ``mechanism = { model = "guide.toml" }`` table names a model file (relative to
    ``base_dir``, default the working directory). Without ``allow_code`` the study may not
    set what the command line owns (:func:`check_rights`). ValueError for any malformed
    value, naming ``source`` (the study file) where it is about rights."""
    named = data.get("mechanism") if isinstance(data, dict) else None
    if isinstance(named, str) and not named.startswith(MODEL_PREFIX):
        check_mechanism(named, allow_code=allow_code)  # code is refused first, by its name
    if not allow_code:
        check_rights(data, source)
    mechanism = _mechanism_of(data, base_dir, allow_code, source)
    if mechanism is not None:
        data = {**data, "mechanism": mechanism}
    try:
        study = engine.study_from_dict(data)
    except (TypeError, AttributeError) as error:  # a value of the wrong shape (cases = 3, ...)
        raise ValueError(f"malformed study: {error}") from None
    check_mechanism(study.mechanism, allow_code=allow_code)
    return study


def load_study(path, allow_code: bool = False) -> Study:
    """A study file, its mechanism checked against the registry (a model file it names is
    found relative to the study file)."""
    path = Path(path)
    return study_from_dict(engine.read_study_file(path), base_dir=path.parent,
                           allow_code=allow_code, source=str(path))


def run_study(study: Study, store_path, allow_code: bool = False, **options) -> engine.StudyResult:
    """The engine's ``run_study`` with the study's mechanism resolved by name (ValueError
    listing the known names for an unknown one, or for code without ``allow_code``);
    ``options`` as the engine's."""
    if not allow_code:
        confirm = study.tolerances.confirm if study.tolerances is not None else None
        check_rights({"options": study.options, "tolerances": {"confirm": confirm}},
                     f"study {study.name!r}")
    evaluate = get_evaluator(study.mechanism, allow_code=allow_code)
    return engine.run_study(study, store_path, evaluate, **options)


def sweep(study, out_dir=None, workers: int | None = None, scheduler: str | None = None,
          retry_failed: bool = False, progress: bool | None = None, allow_code: bool = False,
          max_cases: int = engine.MAX_CASES) -> dict:
    """Run a study (a Study or the path of its TOML file) into ``out_dir`` (default: a folder
    named after the study): results.sqlite, results.csv (and .parquet with pyarrow), the
    study's plots. Returns a JSON-able summary with every case's row. ``allow_code``: let the
    study name a "module:function" (Python code; see studies/mechanisms.py)."""
    if not isinstance(study, Study):
        study = load_study(study, allow_code=allow_code)
    out = check_out(out_dir if out_dir is not None else study.name)
    result = run_study(study, out / "results.sqlite", allow_code=allow_code, workers=workers,
                       scheduler=scheduler, retry_failed=retry_failed, progress=progress,
                       max_cases=max_cases)
    tables = [export_csv(result.cases, out / "results.csv").name]
    if parquet_available():
        tables.append(export_parquet(result.cases, out / "results.parquet").name)
    figures, units = [], quantity_units(study.mechanism)
    for spec in study.plots:
        path = out / f"{spec.metric}_vs_{spec.parameter}.png"
        figures.append(plot_metric(result.cases, spec.metric, spec.parameter, path, spec.overlay,
                                   units).name)
    extra = {}
    if study.tolerances is not None:
        extra["tolerances"] = summarize(study, result.cases)
        (out / "tolerances.json").write_text(json.dumps(extra["tolerances"], indent=1))
        tables.append("tolerances.json")
        if extra["tolerances"]["metrics"]:
            figures.append(plot_tolerances(extra["tolerances"], out / "tolerances.png").name)
        if study.tolerances.confirm is not None:  # the extremes re-run by the confirming model
            extra["tolerances"]["confirm"] = confirm_extremes(study, lambda s: run_study(
                s, out / "results.sqlite", allow_code=allow_code, workers=workers,
                scheduler=scheduler, progress=progress, max_cases=max_cases))
            (out / "tolerances.json").write_text(json.dumps(extra["tolerances"], indent=1))
    return {**extra, "name": study.name, "mechanism": study.mechanism, "out": str(out),
            "store": str(result.store_path), "executor": result.executor,
            "cases": len(result.cases), "computed": result.computed, "reused": result.reused,
            "failed": len(result.failed), "wall_time_s": result.wall_time_s,
            "tables": tables, "figures": figures,
            "errors": sum(c.status == "error" for c in result.cases),
            "failures": [{"params": c.params, "status": c.status, "error": c.error}
                         for c in result.failed],
            "results": [c.to_row() for c in result.cases]}


def plot_tolerances(summary: dict, path) -> Path:
    """Bar chart of each metric's total-order Sobol indices (what its scatter comes from)."""
    from .report.figures import pyplot

    plt = pyplot()
    metrics = list(summary["metrics"])
    names = list(summary["parameters"])
    fig, ax = plt.subplots(figsize=(6.4, 0.5 + 0.45 * len(metrics) * len(names)))
    labels, values = [], []
    for metric in metrics:
        for name in names:
            labels.append(f"{metric}: {name}")
            values.append(summary["metrics"][metric]["total_order"][name])
    ax.barh(range(len(values)), values, color="tab:blue")
    ax.set_yticks(range(len(values)), labels)
    ax.invert_yaxis()
    ax.set_xlabel("total-order Sobol index (share of the output's variance)")
    ax.set_xlim(0, max(1.0, max(values, default=1.0)))
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return Path(path)


def run_front(path, out_dir=None, allow_code: bool = False) -> dict:
    """The Pareto front of a front file (engine/front.py) into ``out_dir`` (default: a folder
    named after the file): front.json, front.png and the evaluation store."""
    from .engine.front import front_from_dict, search_front

    path = Path(path)
    data = engine.read_study_file(path)
    name = data.pop("name", path.stem)
    named = data.get("mechanism")
    if isinstance(named, str) and not named.startswith(MODEL_PREFIX):
        check_mechanism(named, allow_code=allow_code)  # code is refused first, by its name
    if not allow_code:
        check_rights(data, str(path))
    mechanism = _mechanism_of(data, path.parent, allow_code, str(path))
    check_mechanism(mechanism, allow_code=allow_code)
    front = front_from_dict({**data, "mechanism": mechanism})
    out = prepare_out(out_dir if out_dir is not None else name)
    result = search_front(front, get_evaluator(mechanism, allow_code=allow_code),
                          out / "evaluations.sqlite")
    summary = {"name": name, "mechanism": mechanism, "out": str(out),
               "objectives": [list(o) for o in front.objectives],
               "constraints": [list(c) for c in front.constraints], **result}
    (out / "front.json").write_text(json.dumps(summary, indent=1))
    summary["figures"] = [plot_front(summary, out / "front.png").name] if result["designs"] else []
    return summary


def plot_front(summary: dict, path) -> Path:
    """The front in its first two objectives (and the confirming model's, where given)."""
    from .report.figures import pyplot

    plt = pyplot()
    (a, _), (b, _) = summary["objectives"][:2]
    fig, ax = plt.subplots(figsize=(5.6, 4.2))
    designs = summary["designs"]
    ax.plot([d["objectives"][a] for d in designs], [d["objectives"][b] for d in designs], "o",
            label="front (screening model)")
    confirmed = [d["confirmed"] for d in designs if d.get("confirmed")]
    if confirmed:
        ax.plot([c[a] for c in confirmed], [c[b] for c in confirmed], "x",
                label="confirmed")
    for ref in summary.get("references", []):
        ax.plot(ref["objectives"][a], ref["objectives"][b], "*", markersize=12,
                label=f"{ref['name']} (dominated by {ref['dominated_by']})")
    ax.set_xlabel(a)
    ax.set_ylabel(b)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return Path(path)


def convergence_folder(mechanism: str) -> str:
    """The default output folder of a convergence study: convergence_<name> (a model file's
    stem for a model file)."""
    path = mechanism[len(MODEL_PREFIX):].rpartition("@")[0] if mechanism.startswith(
        MODEL_PREFIX) else mechanism if mechanism.endswith(".toml") else ""
    label = Path(path).stem if path else mechanism
    return "convergence_" + re.sub(r"\W", "_", label)


def run_convergence(mechanism: str, metric: str, tol="0.5%", n_levels: int = 4, ratio: float = 2.0,
                    params: dict | None = None, out_dir=None, dim: int = 2,
                    start: float | None = None, allow_code: bool = False,
                    max_dofs: int | None = None, progress=None) -> dict:
    """A convergence study of a registered mechanism on ``n_levels`` levels of size_factor
    start, start/ratio, ... (``start`` defaults to the mechanism's coarsest level, see
    the registry's coarsest_size_factor). Every level's mesh estimate is checked against the
    budget (``max_dofs``, None: half the available memory) before the first is meshed. With
    ``out_dir``: each level is stored as it completes in out_dir/levels.sqlite (a rerun reuses
    it) and convergence_<metric>.png is written there. JSON-able. ``allow_code``: a model
    file's .geo may run code (geo_guard.py)."""
    tolerance = parse_tolerance(tol)
    if not (math.isfinite(ratio) and 1 < ratio <= 10):
        raise ValueError(f"ratio = {ratio!r} must be in (1, 10]: the size factor between "
                         "levels (2 halves the element size)")
    if not isinstance(n_levels, int) or not 3 <= n_levels <= 12:
        raise ValueError(f"levels = {n_levels!r} must be a whole number from 3 to 12")
    if start is not None and not (math.isfinite(start) and 1e-3 <= start <= 1e3):
        raise ValueError(f"start = {start!r} must be a size_factor in [0.001, 1000] (1: the "
                         "mechanism's default mesh)")
    if str(mechanism).endswith(".toml"):  # a model file
        mechanism = model_mechanism(mechanism)
    if start is None:
        start = coarsest_size_factor(mechanism)
    if not (math.isfinite(start) and start > 0):
        raise ValueError(f"start = {start!r} must be a finite size_factor > 0")
    levels = default_levels(n_levels, ratio, start=start)
    evaluate = get_evaluator(mechanism, allow_code=allow_code)
    check_parameter_names(evaluate, [(f"params.{k}", k) for k in (params or {})], mechanism)
    check_metric_names(evaluate, [("metric", metric)], mechanism)
    if max_dofs is not None:
        if "max_dofs" not in declared_options(evaluate)[0]:
            raise ValueError(f"max_dofs = {max_dofs!r}: mechanism {mechanism!r} takes no mesh "
                             "budget (it meshes nothing)")
        evaluate = functools.partial(evaluate, max_dofs=max_dofs)  # not part of a level's key
    store = check_out(out_dir) / "levels.sqlite" if out_dir is not None else None
    result = converge(evaluate, metric, levels, params=params, tol=tolerance, dim=dim,
                      store=store, mechanism=mechanism, progress=progress)
    summary = {"mechanism": mechanism, **result.to_dict(), "figures": [],
               "store": str(store) if store is not None else None}
    if out_dir is not None:
        Path(out_dir).mkdir(parents=True, exist_ok=True)
        figure = plot_convergence(result, Path(out_dir) / f"convergence_{metric}.png")
        summary["figures"].append(str(figure))
    return summary
