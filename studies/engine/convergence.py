"""Mesh-convergence studies of any mechanism and metric, with Richardson extrapolation.

The mechanism's evaluate is called at a sequence of refinements (``levels``: evaluate options
such as {"size_factor": s}), coarse to fine, and must return the metric and a mesh size: "h"
(characteristic element size, m) or "dofs" (then h ~ dofs^(-1/dim)). From the last three
levels (coarse c, medium m, fine f; ratios r_cm = h_c/h_m, r_mf = h_m/h_f):

- observed order p: Celik et al. (2008), "Procedure for estimation and reporting of uncertainty
  due to discretization in CFD applications", J. Fluids Eng. 130, 078001, eqs. (3a-c):
  p = |ln|e_cm/e_mf| + q(p)| / ln r_mf,  q(p) = ln((r_mf^p - s)/(r_cm^p - s)),  s = sign(e_cm/e_mf),
  with e_cm = f_m - f_c, e_mf = f_f - f_m; for a constant ratio r, q = 0 and
  p = ln(|f_c - f_m| / |f_m - f_f|) / ln r;
- Richardson extrapolation (eq. 4): f_ext = (r_mf^p f_f - f_m) / (r_mf^p - 1);
- the fine-grid convergence index (eq. 5-6): GCI = 1.25 |f_f - f_m| / (|f_f| (r_mf^p - 1)),
  reported as relative and absolute (1.25 |f_f - f_m| / (r_mf^p - 1)) error estimates;
- the coarsest level whose value is within a relative tolerance of f_ext.
"""
import math
import sys
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

from ...fem.budget import BudgetError, Estimated, estimate_only
from ..report.figures import legend_outside, pyplot
from .store import CaseResult, ResultStore, case_key, flexfem_version

SAFETY_FACTOR = 1.25  # Roache's factor for three grids (Celik et al. 2008, eq. 6)


def parse_tolerance(text) -> float:
    """A relative tolerance from "0.5%" or 0.005 (or "0.005"); ValueError outside (0, 1)."""
    raw = text
    if isinstance(text, str):
        text = text.strip()
        scale = 0.01 if text.endswith("%") else 1.0
        try:
            value = float(text.rstrip("%")) * scale
        except ValueError as error:
            raise ValueError(f"tol = {raw!r} is not a number or a percentage like '0.5%'") from error
    else:
        value = float(text)
    if not 0 < value < 1:
        raise ValueError(f"tol = {raw!r} must be a relative tolerance in (0, 1), e.g. 0.005 or '0.5%'")
    return value


def default_levels(n: int, ratio: float = 2.0, key: str = "size_factor", start: float = 1.0) -> list[dict]:
    """``n`` refinement levels {key: start / ratio^i}, coarse to fine."""
    if int(n) < 3:
        raise ValueError(f"levels = {n!r} must be >= 3 (the observed order needs three)")
    if not ratio > 1:
        raise ValueError(f"ratio = {ratio!r} must be > 1")
    return [{key: start / ratio**i} for i in range(int(n))]


def observed_order(f_coarse: float, f_medium: float, f_fine: float, r_cm: float, r_mf: float,
                   iterations: int = 200) -> float:
    """Observed order p from three solutions (Celik et al. 2008, eqs. 3a-c); nan when two
    levels agree exactly (no change left to measure)."""
    e_cm, e_mf = f_medium - f_coarse, f_fine - f_medium
    if e_cm == 0 or e_mf == 0:
        return math.nan
    s = math.copysign(1.0, e_cm / e_mf)
    log_ratio = math.log(abs(e_cm / e_mf))
    p = abs(log_ratio) / math.log(r_mf)
    if math.isclose(r_cm, r_mf, rel_tol=1e-12):
        return log_ratio / math.log(r_mf) if s > 0 else p
    for _ in range(iterations):  # fixed point of eq. (3b), as Celik et al. suggest
        q = math.log((r_mf**p - s) / (r_cm**p - s))
        new = abs(log_ratio + q) / math.log(r_mf)
        if abs(new - p) < 1e-12 * max(1.0, p):
            return new
        p = new
    return p


def richardson_extrapolate(f_medium: float, f_fine: float, r_mf: float, p: float) -> float:
    """f_ext = (r^p f_fine - f_medium) / (r^p - 1) (Celik et al. 2008, eq. 4a)."""
    return (r_mf**p * f_fine - f_medium) / (r_mf**p - 1)


def _describe(options: dict) -> str:
    return ", ".join(f"{k} {v:g}" if isinstance(v, float) else f"{k} {v}"
                     for k, v in options.items())


#: Below this observed order a monotone sequence is not extrapolated: it is called divergent.
MIN_ORDER = 0.5


def diverging(f_coarse: float, f_medium: float, f_fine: float, p: float) -> bool:
    """True for three levels whose changes do not shrink: the last change at least as large
    as the one before (the ratio of differences >= 1, whatever their signs), or changes of
    one sign shrinking slower than order :data:`MIN_ORDER` (p <= 0 included), or an order
    that cannot be measured although the levels differ."""
    e_cm, e_mf = f_medium - f_coarse, f_fine - f_medium
    if e_mf == 0:
        return False
    if e_cm == 0 or abs(e_mf) >= abs(e_cm) or math.isnan(p):
        return True
    return e_cm * e_mf > 0 and p < MIN_ORDER


def grid_convergence_index(f_medium: float, f_fine: float, r_mf: float, p: float) -> float:
    """Relative fine-grid convergence index 1.25 |(f_f - f_m)/f_f| / (r^p - 1) (eq. 6)."""
    return SAFETY_FACTOR * abs((f_fine - f_medium) / f_fine) / (r_mf**p - 1)


def coarsest_within(values, reference: float, tol: float) -> int | None:
    """Index of the first (coarsest) value within ``tol`` (relative) of ``reference``."""
    for i, value in enumerate(values):
        if abs(value - reference) <= tol * abs(reference):
            return i
    return None


@dataclass(frozen=True)
class ConvergenceResult:
    """A convergence study of ``metric`` (SI units of the metric): per level its options,
    value, size h (m, or dofs^(-1/dim) when sized by dofs), dofs and wall time (s); the
    observed order, the extrapolated value with its absolute error estimate and relative GCI,
    the behaviour ("monotone", "oscillatory", "divergent", "exact", or "converged": every level
    within ``tol`` of the finest, the order not measurable) and the coarsest level
    within ``tol`` of the extrapolated value (None: none is); ``dim`` relates dofs to h."""

    metric: str
    size_key: str
    levels: list
    values: list
    sizes: list
    dofs: list
    wall_times_s: list
    order: float
    extrapolated: float
    error_estimate: float
    gci: float
    behaviour: str
    tol: float | None
    coarsest_within_tol: int | None
    dim: int = 2
    reused: list = field(default_factory=list)
    estimates: list = field(default_factory=list)

    def to_dict(self) -> dict:
        return asdict(self)


def _mesh_sizes(outputs: list, key: str | None, dim: int) -> tuple[str, list]:
    if key is None:
        key = "h" if all("h" in o for o in outputs) else "dofs"
    if key not in ("h", "dofs"):
        raise ValueError(f"mesh_size_key = {key!r} must be 'h' or 'dofs'")
    missing = [i for i, o in enumerate(outputs) if key not in o]
    if missing:
        raise ValueError(f"level(s) {missing} returned no {key!r}: evaluate must return 'h' (m) "
                         "or 'dofs' for a convergence study")
    if key == "h":
        return key, [float(o["h"]) for o in outputs]
    return key, [float(o["dofs"]) ** (-1.0 / dim) for o in outputs]


def converge(evaluate, metric: str, levels: list, mesh_size_key: str | None = None,
             params: dict | None = None, tol: float | None = None, dim: int = 2,
             progress=None, store=None, mechanism: str = "evaluate") -> ConvergenceResult:
    """Evaluate ``metric`` at each mesh level; estimate its converged value (Richardson).

    Parameters
    ----------
    evaluate : callable
        ``evaluate(params, **options) -> {metric: value}``.
    metric : str
        The metric whose convergence is estimated (in ``evaluate``'s units).
    levels : list of dict
        The ``evaluate`` options of each level, coarse to fine (>= 3; e.g. ``size_factor``).
    mesh_size_key : str, optional
        "h" (element size, m) or "dofs" (unknowns, -); None: "h" when returned.
    params : dict, optional
        The design (``evaluate``'s parameters; None: its defaults).
    tol : float or str, optional
        The relative tolerance (-, or "1 %"): the coarsest level within it is reported.
    dim : int
        The dimension relating dofs to h (h ~ dofs^(-1/dim)).
    progress : file-like, optional
        A stream that gets a line per level as it completes (None: stderr when a terminal).
    store : str or os.PathLike, optional
        An SQLite file (engine/store.py) recording each level, keyed by ``mechanism``, the
        design and the level: a rerun reuses the stored levels.
    mechanism : str
        The name the store keys the levels by.

    Returns
    -------
    ConvergenceResult
        The values, sizes, observed order, extrapolated value, error estimate and GCI. Every
        level's mesh estimate is checked against its budget first (:func:`check_levels`).
    """
    if len(levels) < 3:
        raise ValueError(f"levels has {len(levels)} entries; the observed order needs >= 3")
    if tol is not None:
        tol = parse_tolerance(tol)
    stream = progress if progress is not None else (sys.stderr if sys.stderr.isatty() else None)
    outputs, times, reused, estimates = _run_levels(evaluate, levels, dict(params or {}),
                                                    store, mechanism, metric, stream)
    if any(metric not in o for o in outputs):
        reasons = outputs[0].get("not_available")
        why = f" (not available: {reasons})" if isinstance(reasons, str) and reasons else ""
        raise ValueError(f"metric = {metric!r} is not returned{why}; returned: "
                         f"{sorted(k for k, v in outputs[0].items() if k != 'not_available')}")
    key, sizes = _mesh_sizes(outputs, mesh_size_key, dim)
    if any(b >= a for a, b in zip(sizes, sizes[1:])):
        raise ValueError(f"levels must refine from coarse to fine, but the sizes are {sizes}")
    values = [float(o[metric]) for o in outputs]
    f_c, f_m, f_f = values[-3:]
    r_cm, r_mf = sizes[-3] / sizes[-2], sizes[-2] / sizes[-1]
    p = observed_order(f_c, f_m, f_f, r_cm, r_mf)
    steps = [b - a for a, b in zip(values, values[1:]) if b != a]
    one_way = all(s * steps[0] > 0 for s in steps)
    if f_f == f_m:
        behaviour, extrapolated, error, gci = "exact", f_f, 0.0, 0.0
    elif diverging(f_c, f_m, f_f, p):
        # the changes do not shrink, or so slowly that no extrapolation can be trusted: a
        # singular quantity (a stress at a sharp re-entrant corner grows as h^-0.46)
        behaviour, extrapolated, error, gci = "divergent", f_f, math.nan, math.nan
    else:
        behaviour = "monotone" if one_way else "oscillatory"
        extrapolated = richardson_extrapolate(f_m, f_f, r_mf, p)
        error = SAFETY_FACTOR * abs(f_f - f_m) / (r_mf**p - 1)
        gci = grid_convergence_index(f_m, f_f, r_mf, p)
    spread = max(abs(v - f_f) for v in values) / max(abs(f_f), 1e-300)
    if behaviour in ("divergent", "oscillatory") and tol is not None and spread <= tol:
        # every level within the tolerance of the finest: converged, the order lost in noise
        behaviour, extrapolated, error, gci = "converged", f_f, spread * abs(f_f), spread
    within = (coarsest_within(values, extrapolated, tol)
              if tol is not None and behaviour != "divergent" else None)  # no level of a
    # diverging series is "within tolerance": its finest value is no converged value
    return ConvergenceResult(
        metric=metric, size_key=key, levels=[dict(level) for level in levels], values=values,
        sizes=sizes, dofs=[o.get("dofs") for o in outputs], wall_times_s=times, order=p,
        extrapolated=extrapolated, error_estimate=error, gci=gci, behaviour=behaviour,
        tol=tol, coarsest_within_tol=within, dim=dim, reused=reused, estimates=estimates)


def _level_key(mechanism: str, params: dict, level: dict) -> str:
    return case_key(mechanism, params, {"convergence_level": dict(level)}, flexfem_version())


def _say(stream, text: str) -> None:
    if stream is not None:
        print(text, file=stream, flush=True)


def check_levels(evaluate, levels: list, params: dict, skip=(), on_computed=None) -> dict:
    """Every level's mesh estimate against its budget, before any level is meshed: each
    level's evaluate runs under fem/budget.py's ``estimate_only`` up to its first budget
    check. Returns {level: estimate (with "limit")}; BudgetError naming the first level that
    does not fit, its estimate and the budget. A level whose evaluate checks no budget (a
    closed form) is simply computed: ``on_computed(level, outputs, seconds)`` keeps it."""
    estimates = {}
    for i, options in enumerate(levels):
        if i in skip:
            continue
        start = time.perf_counter()
        try:
            with estimate_only():
                outputs = evaluate(dict(params), **options)
        except Estimated as e:
            estimates[i] = {**e.estimate, "limit": e.limit}
            if not e.fits:
                raise BudgetError(
                    f"level {i + 1}/{len(levels)} ({_describe(options)}) does not fit: "
                    f"{e.what} is about {e.estimate['dofs']:,} DOFs (~{e.memory_gib:.1f} GiB), above "
                    f"the budget of {e.limit:,} DOFs ({e.source}); refused before any level "
                    "was meshed: use " + (f"--levels {i} or fewer, " if i >= 3 else "")
                    + "a coarser --start, a smaller --ratio or raise the budget with "
                    "--max-dofs N") from None
            continue
        if on_computed is not None:
            on_computed(i, outputs, time.perf_counter() - start)
    return estimates


def _run_levels(evaluate, levels, params, store, mechanism, metric, stream):
    """(outputs, times, reused levels, estimates) of every level: those in ``store`` reused,
    the others estimated first (:func:`check_levels`), then computed and stored one by one."""
    outputs, times, reused = [None] * len(levels), [None] * len(levels), []
    keys = [_level_key(mechanism, params, level) for level in levels]
    db = ResultStore(store) if store is not None and Path(store).is_file() else None
    try:
        if db is not None:
            stored = {c.key: c for c in db.results(keys) if c.ok}
            for i, key in enumerate(keys):
                if key in stored:
                    outputs[i], times[i] = dict(stored[key].metrics), stored[key].wall_time_s
                    reused.append(i)
                    _say(stream, f"level {i + 1}/{len(levels)} reused ({_describe(levels[i])}, "
                                 f"from {store})")

        def keep(i, out, seconds):
            nonlocal db
            outputs[i], times[i] = out, seconds
            if store is not None:
                db = db or ResultStore(store)  # made with the first level it keeps
                dofs = out.get("dofs")
                db.record(CaseResult(keys[i], mechanism, params,
                                     {"convergence_level": dict(levels[i])}, metrics=dict(out),
                                     wall_time_s=seconds, flexfem_version=flexfem_version(),
                                     dofs=int(dofs) if isinstance(dofs, (int, float))
                                     and math.isfinite(dofs) else None))
            _say(stream, f"level {i + 1}/{len(levels)} ({_describe(levels[i])}): "
                         f"{out.get('dofs', '?')} DOFs, {metric} = {out.get(metric, '?')}, "
                         f"{seconds:.1f} s")

        found = check_levels(evaluate, levels, params, skip=set(reused), on_computed=keep)
        for i, options in enumerate(levels):
            if outputs[i] is None:
                start = time.perf_counter()
                out = evaluate(dict(params), **options)
                keep(i, out, time.perf_counter() - start)
    finally:
        if db is not None:
            db.close()
    return outputs, times, reused, [found.get(i) for i in range(len(levels))]


def plot_convergence(result: ConvergenceResult, path, theoretical_order: float | None = None) -> Path:
    """Log-log PNG of |f - f_ext| against h (or dofs), with the observed-order slope."""
    plt = pyplot()
    by_dofs = result.size_key == "dofs"
    x = [float(d) for d in result.dofs] if by_dofs else result.sizes
    errors = [abs(v - result.extrapolated) for v in result.values]
    shown = [(xi, e) for xi, e in zip(x, errors) if e > 0]
    fig, ax = plt.subplots(figsize=(5.6, 4.2))
    if shown:
        ax.loglog(*zip(*shown), "o-", label=f"|{result.metric} - extrapolated|")
        x0, e0 = shown[0]
        for order, style, name in ((result.order, ":", "observed"), (theoretical_order, "--", "theory")):
            if order is not None and math.isfinite(order):
                slope = -order / result.dim if by_dofs else order  # dofs ~ h^-dim
                ax.loglog([xi for xi, _ in shown], [e0 * (xi / x0) ** slope for xi, _ in shown],
                          style, color="gray", label=f"{name} order {order:.2f}")
    ax.set_xlabel("degrees of freedom" if by_dofs else "element size h (m)")
    ax.set_ylabel("|value - extrapolated value|")
    order = "not measurable" if not math.isfinite(result.order) else f"{result.order:.2f}"
    ax.set_title(f"{result.metric}: order {order}, GCI = {100 * result.gci:.2g} %")
    if shown:
        legend_outside(ax)
    else:
        ax.text(0.5, 0.5, "no change between levels", transform=ax.transAxes, ha="center")
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)
    return Path(path)

