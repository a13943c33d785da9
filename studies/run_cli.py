"""``flexfem sweep`` and ``flexfem converge``: parameter and mesh-convergence studies."""
from .engine.executors import MAX_WORKERS
from .lazy import Lazy
from .options import count, deferred, json_object, tolerance, whole_number

# the studies, imported when a command runs (the study engine imports plotting)
convergence_folder = Lazy(".run:convergence_folder", __package__)
run_convergence = Lazy(".run:run_convergence", __package__)
run_front = Lazy(".run:run_front", __package__)
sweep = Lazy(".run:sweep", __package__)


def register(subparsers):
    p = subparsers.add_parser("sweep", help="run a parameter study declared in a TOML file")
    deferred(p, _sweep_arguments)  # its --max-cases default is the study engine's
    c = subparsers.add_parser("converge", help="mesh-convergence study of one metric of a mechanism")
    _converge_arguments(c)
    register_front(subparsers)


def _sweep_arguments(p) -> None:
    from .engine.sweep import MAX_CASES

    p.add_argument("study", help="study file (TOML): mechanism, base, grid / cases / sample")
    p.add_argument("--out", help="output folder (default: ./<study name>)")
    p.add_argument("--workers", type=whole_number(1, MAX_WORKERS), help="local worker processes (default: one per CPU; 1: in-process)")
    p.add_argument("--scheduler", help="Dask scheduler tcp://HOST:PORT (default: $FLEXFEM_SCHEDULER)")
    p.add_argument("--retry-failed", action="store_true", help="re-run cases stored as failed")
    p.add_argument("--allow-code", action="store_true",
                   help="let the study name a Python 'module:function' as its mechanism, and "
                        "its model files' .geo run programs or read outside their folders: "
                        "that code runs with the study's values; only for files you trust")
    p.add_argument("--max-cases", type=count, default=MAX_CASES,
                   help=f"refuse a study of more cases than this (default {MAX_CASES:,})")
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    p.set_defaults(run=_run_sweep, summarize=summarize_sweep)


def _converge_arguments(c) -> None:
    c.add_argument("mechanism", help="registered mechanism name (toy, dbma, eightbar) or a "
                                     "model file (MODEL.toml)")
    c.add_argument("--metric", required=True, help="metric returned by the mechanism's evaluate")
    c.add_argument("--tol", default="0.5%", type=tolerance,
                   help="relative tolerance, '0.5%%' or 0.005 (default 0.5%%)")
    c.add_argument("--levels", type=whole_number(3, 12), default=4,
                   help="refinement levels, 3 to 12 (default 4)")
    c.add_argument("--ratio", type=float, default=2.0, help="refinement ratio between levels (default 2)")
    c.add_argument("--start", type=float, default=None,
                   help="size_factor of the coarsest level (default: the mechanism's, 4 for dbma)")
    c.add_argument("--params", type=json_object, default=None,
                   help='design parameters as JSON, e.g. \'{"length_m": 0.05}\' (default: the base design)')
    c.add_argument("--out", help="output folder: each level's result as it completes "
                                 "(levels.sqlite: a rerun reuses them) and the log-log plot "
                                 "(default: ./convergence_<mechanism or model file's name>)")
    c.add_argument("--max-dofs", type=count, default=None,
                   help="mesh budget of every level in DOFs (default: what half the available "
                        "memory affords); every level is checked before the first is meshed")
    c.add_argument("--allow-code", action="store_true",
                   help="trust the model file: its .geo may run programs and read outside "
                        "its folder")
    c.add_argument("--json", action="store_true", help="print the result as one JSON object")
    c.set_defaults(run=_run_converge, summarize=summarize_convergence)


def register_front(subparsers):
    f = subparsers.add_parser("front", help="Pareto front of a mechanism's design: several "
                                            "objectives, constraints (NSGA-II, pymoo)")
    f.add_argument("front", metavar="FRONT.toml", help="the front file (docs/studies.md)")
    f.add_argument("--out", help="output folder (default: ./<file name>)")
    f.add_argument("--allow-code", action="store_true",
                   help="let the file name a Python 'module:function' mechanism")
    f.add_argument("--json", action="store_true", help="print the result as one JSON object")
    f.set_defaults(run=lambda a: run_front(a.front, a.out, a.allow_code), summarize=summarize_front)


def summarize_front(result: dict) -> str:
    names = [m for m, _ in result["objectives"]]
    lines = [f"front {result['name']} ({result['mechanism']}): {len(result['designs'])} designs "
             f"on the front, {result['evaluations']} evaluations ({result['failed']} failed)"]
    if result.get("first_failure"):
        lines.append(f"  a failed design: {result['first_failure']}")
    for d in result["designs"][:20]:
        values = ", ".join(f"{m} {d['objectives'][m]:.4g}" for m in names)
        margins = ", ".join(f"{m} {v:+.3g}" for m, v in d["margins"].items())
        lines.append(f"  {values}" + (f"  (margins: {margins})" if margins else ""))
    for ref in result.get("references", []):
        values = ", ".join(f"{m} {ref['objectives'][m]:.4g}" for m in names)
        lines.append(f"  reference {ref['name']}: {values}; {ref['dominated_by']} front "
                     "design(s) dominate it")
    lines.append(f"results in {result['out']}: front.json" + "".join(
        f", {f}" for f in result.get("figures", [])))
    return "\n".join(lines)


def _run_sweep(args) -> dict:
    return sweep(args.study, args.out, workers=args.workers, scheduler=args.scheduler,
                 retry_failed=args.retry_failed, allow_code=args.allow_code,
                 max_cases=args.max_cases)


def _run_converge(args) -> dict:
    out = args.out if args.out is not None else convergence_folder(args.mechanism)
    return run_convergence(args.mechanism, args.metric, tol=args.tol, n_levels=args.levels,
                           ratio=args.ratio, params=args.params, out_dir=out,
                           start=args.start, allow_code=args.allow_code,
                           max_dofs=args.max_dofs)


def summarize_sweep(result: dict) -> str:
    lines = [f"study {result['name']} ({result['mechanism']}): {result['cases']} cases, "
             f"{result['computed']} computed, {result['reused']} reused, {result['failed']} failed "
             f"on {result['executor']} in {result['wall_time_s']:.1f} s"]
    if result.get("errors"):
        lines.append(f"  {result['errors']} case(s) failed by the environment (status 'error'):"
                     " they are computed again by the next run")
    lines += [f"  {f.get('status', 'failed')} {f['params']}: {f['error']}"
              for f in result["failures"][:10]]
    for metric, m in result.get("tolerances", {}).get("metrics", {}).items():
        total = m["total_order"][m["dominant"]]
        lines.append(f"  {metric}: {m['mean']:.4g} +- {3 * m['std']:.3g} (3 sigma); the "
                     f"tolerance that matters most: {m['dominant']} (total-order index "
                     f"{total:.2f})")
    if result.get("tolerances", {}).get("failed"):
        lines.append(f"  {result['tolerances']['failed']} toleranced design(s) failed: no "
                     "Sobol indices until every design has a result")
    files = result["tables"] + result["figures"]
    lines.append(f"results in {result['out']}: {', '.join(files)}")
    return "\n".join(lines)


def _level(level: dict) -> str:
    return ", ".join(f"{k} {v:g}" if isinstance(v, float) else f"{k} {v}" for k, v in level.items())


def summarize_convergence(result: dict) -> str:
    lines = [f"{result['mechanism']} {result['metric']}: level, {result['size_key']}, dofs, value"]
    for i, (size, dofs, value) in enumerate(zip(result["sizes"], result["dofs"], result["values"])):
        lines.append(f"  {i}  {_level(result['levels'][i])}  {size:.4g}  {dofs}  {value:.6g}")
    tol, within = 100 * result["tol"], result["coarsest_within_tol"]
    if result["behaviour"] in ("converged", "exact"):
        lines.append(f"converged within {100 * result['gci']:.2g} % on every level (tolerance "
                     f"{tol:.3g} %); order not measurable")
    elif result["behaviour"] == "divergent":
        lines.append("diverging (singular): the changes do not shrink under refinement, so "
                     "the finest value is no converged value and none is within tolerance; a "
                     "stress at a sharp re-entrant corner grows without bound (give it a "
                     "fillet), otherwise refine further or check the model")
    else:
        lines.append(f"observed order {result['order']:.3g} ({result['behaviour']}); "
                     f"extrapolated {result['extrapolated']:.6g} +- "
                     f"{result['error_estimate']:.2g} (GCI {100 * result['gci']:.2g} %)")
    if result["behaviour"] != "divergent":  # a diverging series has no level to recommend
        lines.append(f"coarsest level within {tol:.3g} %: "
                     + (f"{within} ({_level(result['levels'][within])})" if within is not None
                        else "none: refine further"))
    if result.get("store"):
        reused = result.get("reused") or []
        lines.append(f"levels stored in {result['store']}" + (
            f"; level(s) {', '.join(str(i) for i in reused)} reused" if reused else ""))
    return "\n".join(lines)
