"""Tolerances of a study: a Monte Carlo of the outputs over the manufacturing scatter of its
parameters, their spread, and which tolerance matters most (first- and total-order Sobol
indices by SALib: Saltelli's sampling and Jansen/Saltelli estimators, not hand-written).

A study file declares, beside its base design::

    [tolerances]
    n = 256                  # Saltelli base sample: n (k + 2) designs for k toleranced names
    seed = 0
    [tolerances.parameters]
    flexure_width = { nominal = 0.3e-3, tolerance = 10e-6, distribution = "normal" }
    base_flexure_width = { nominal = 0.4e-3, tolerance = 10e-6 }   # normal by default

``tolerance`` is the half-width of the band a shop guarantees: for "normal" it is three
standard deviations (99.7 % of parts inside nominal +- tolerance), for "uniform" the band's
half-width (every value equally likely). The designs are ordinary cases of the study: stored
as they complete, resumable, on local workers or Dask. SI units.

Two optional keys::

    [tolerances]
    metrics = ["k_x", "f1_hz"]   # the outputs analysed (default: every varying one)
    [tolerances.confirm]         # options of a confirming model, over the study's options
    model = "continuum"

:func:`summarize` gives the spread and indices from the study's stored cases. With
``confirm``, :func:`confirm_extremes` re-runs the designs at the extremes of each
analysed output (its lowest and highest sample) with the confirming model, as cases of the
same store (resumable, local or Dask), and reports the screening model's value beside the
confirming one's at each: the beam model screens the Monte Carlo, the continuum re-checks
where the scatter ends.
"""
from dataclasses import dataclass, field, replace
import math

import numpy as np

from .store import case_key, flexfem_version

DISTRIBUTIONS = ("normal", "uniform")
KEYS = ("n", "seed", "parameters", "metrics", "confirm")


@dataclass(frozen=True)
class Tolerance:
    """One toleranced parameter: ``nominal`` +- ``tolerance`` (SI), ``distribution``."""

    nominal: float
    tolerance: float
    distribution: str = "normal"

    def __post_init__(self):
        for name in ("nominal", "tolerance"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) \
                    or not math.isfinite(value):
                raise ValueError(f"tolerance {name} = {value!r} must be a finite number")
        if not self.tolerance > 0:
            raise ValueError(f"tolerance = {self.tolerance!r} must be > 0")
        if self.distribution not in DISTRIBUTIONS:
            raise ValueError(f"distribution = {self.distribution!r} must be one of "
                             f"{DISTRIBUTIONS}")

    def salib(self) -> tuple[list, str]:
        """(bounds, dist) as SALib's problem takes them."""
        if self.distribution == "normal":
            return [self.nominal, self.tolerance / 3], "norm"
        return [self.nominal - self.tolerance, self.nominal + self.tolerance], "unif"


@dataclass(frozen=True)
class Tolerances:
    """The study's toleranced parameters {name: Tolerance}, Saltelli's base sample ``n`` (a
    power of two) and the scrambling ``seed``."""

    parameters: dict = field(default_factory=dict)
    n: int = 256
    seed: int = 0
    metrics: tuple = ()
    confirm: dict | None = None

    def __post_init__(self):
        if not self.parameters:
            raise ValueError("[tolerances.parameters] is empty: give at least one")
        if not (isinstance(self.n, int) and self.n >= 8 and self.n & (self.n - 1) == 0):
            raise ValueError(f"tolerances.n = {self.n!r} must be a power of two >= 8 "
                             "(Sobol' sequences balance only there)")
        if not (isinstance(self.seed, int) and self.seed >= 0):
            raise ValueError(f"tolerances.seed = {self.seed!r} must be an integer >= 0")
        if not (isinstance(self.metrics, (list, tuple))
                and all(isinstance(m, str) and m for m in self.metrics)):
            raise ValueError(f"tolerances.metrics = {self.metrics!r} must be a list of "
                             "metric names")
        if self.confirm is not None and not (isinstance(self.confirm, dict) and self.confirm):
            raise ValueError(f"[tolerances.confirm] = {self.confirm!r} must be a table of the "
                             "confirming model's options, e.g. { model = \"continuum\" }")

    @property
    def problem(self) -> dict:
        names = list(self.parameters)
        specs = [self.parameters[k].salib() for k in names]
        return {"num_vars": len(names), "names": names, "bounds": [b for b, _ in specs],
                "dists": [d for _, d in specs]}

    def points(self) -> list[dict]:
        """The n (k + 2) designs of Saltelli's scheme, {name: value}, in SALib's order."""
        from SALib.sample import sobol

        samples = sobol.sample(self.problem, self.n, calc_second_order=False,
                               scramble=True, seed=self.seed)
        return [dict(zip(self.problem["names"], map(float, row))) for row in samples]

    def analyze(self, outputs: list[dict]) -> dict:
        """{metric: {mean, std, low, high (the 0.135 and 99.865 percentiles: +-3 sigma),
        first_order {name: S1}, total_order {name: ST}, first_order_conf, total_order_conf
        (95 % bootstrap half-widths), dominant (the name of the largest ST)}} over the
        metrics every design returned as finite numbers; ``outputs`` in :meth:`points`' order."""
        from SALib.analyze import sobol

        names = self.problem["names"]
        metrics = sorted(set.intersection(*(set(o) for o in outputs)))
        if self.metrics:
            metrics = [m for m in self.metrics if m in metrics]
        out = {}
        for metric in metrics:
            y = np.array([o[metric] for o in outputs], dtype=float)
            if not np.all(np.isfinite(y)) or np.ptp(y) == 0:
                continue
            # SALib seeds its bootstrap only for a truthy seed (0 would draw at random):
            # seed + 1 makes the confidence intervals reproducible for every study seed
            s = sobol.analyze(self.problem, y, calc_second_order=False, seed=self.seed + 1)
            total = dict(zip(names, map(float, s["ST"])))
            out[metric] = {
                "mean": float(y.mean()), "std": float(y.std(ddof=1)),
                "low": float(np.percentile(y, 0.135)), "high": float(np.percentile(y, 99.865)),
                "first_order": dict(zip(names, map(float, s["S1"]))),
                "first_order_conf": dict(zip(names, map(float, s["S1_conf"]))),
                "total_order": total,
                "total_order_conf": dict(zip(names, map(float, s["ST_conf"]))),
                "dominant": max(total, key=total.get)}
        return out


def tolerances_from_dict(table) -> Tolerances:
    """The [tolerances] table of a study file; ValueError naming the bad key."""
    if not isinstance(table, dict):
        raise ValueError(f"[tolerances] must be a table, not {table!r}")
    unknown = sorted(set(table) - set(KEYS))
    if unknown:
        raise ValueError(f"[tolerances]: unknown key(s) {unknown}; allowed: {list(KEYS)}")
    raw = table.get("parameters", {})
    if not isinstance(raw, dict):
        raise ValueError("[tolerances.parameters] must be a table of "
                         "NAME = { nominal, tolerance, distribution }")
    parameters = {}
    for name, spec in raw.items():
        if not isinstance(spec, dict) or set(spec) - {"nominal", "tolerance", "distribution"} \
                or not {"nominal", "tolerance"} <= set(spec):
            raise ValueError(f"tolerances.parameters.{name} = {spec!r} must be "
                             "{ nominal = X, tolerance = DX, distribution = \"normal\" | "
                             "\"uniform\" }")
        try:
            parameters[name] = Tolerance(**spec)
        except (TypeError, ValueError) as error:
            raise ValueError(f"tolerances.parameters.{name}: {error}") from None
    metrics = table.get("metrics", ())
    return Tolerances(parameters, table.get("n", 256), table.get("seed", 0),
                      tuple(metrics) if isinstance(metrics, list) else metrics,
                      table.get("confirm"))


def varying(outputs: list) -> list:
    """The metrics every design with a result (not None) returns as a finite number that is
    not the same for all: those :meth:`Tolerances.analyze` would analyse."""
    done = [o for o in outputs if o is not None]
    if not done:
        return []
    out = []
    for metric in sorted(set.intersection(*(set(o) for o in done))):
        values = [o[metric] for o in done]
        if all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
               for v in values) and max(values) > min(values):
            out.append(metric)
    return out


def extreme_designs(points: list, outputs: list, metrics) -> dict:
    """{metric: {"low": i, "high": i}}: the indices of the designs with the lowest and the
    highest value of each metric among ``outputs`` (None: a design without a result);
    metrics that no design returns as a number are left out."""
    out = {}
    for metric in metrics:
        values = [(o[metric], i) for i, o in enumerate(outputs) if o is not None
                  and isinstance(o.get(metric), (int, float)) and math.isfinite(o[metric])]
        if values:
            out[metric] = {"low": min(values)[1], "high": max(values)[1]}
    return out


def summarize(study, cases) -> dict:
    """The tolerance analysis of ``study`` (a sweep Study with tolerances) from its stored
    ``cases`` (CaseResult, keyed with the study's options as run): {"n_designs", "failed"
    (designs without a result: no indices then), "parameters" {name: {nominal, tolerance,
    distribution}}, "metrics" {metric: spread and Sobol indices, see
    :meth:`Tolerances.analyze`}}."""
    by_key = {c.key: c for c in cases}
    version = flexfem_version()
    outputs, failed = [], 0
    for point in study.tolerances.points():
        case = by_key.get(case_key(study.mechanism, {**study.base, **point}, study.options,
                                   version))
        if case is None or not case.ok:
            failed += 1
        else:
            outputs.append(case.metrics)
    parameters = {k: vars(v) for k, v in study.tolerances.parameters.items()}
    metrics = study.tolerances.analyze(outputs) if not failed else {}
    return {"n_designs": len(outputs) + failed, "failed": failed, "parameters": parameters,
            "metrics": metrics}


def confirm_extremes(study, run) -> dict:
    """Re-check the extremes of a study's tolerances with its ``[tolerances.confirm]`` model.

    ``study``: a sweep Study whose tolerances declare ``confirm``; ``run(study) ->
    StudyResult`` runs a study into the store that holds (or will hold) its screening cases,
    e.g. ``lambda s: run_study(s, store, evaluate, workers=2)`` (engine/sweep.py: local
    workers or Dask, resumable). The screening cases are taken from it (those missing are
    computed first); per analysed metric (``metrics``, default those that vary, see
    :func:`varying`), the lowest and the highest design are evaluated again with the study's
    options updated by ``confirm``, as cases of the same store. Returns {"options" (the
    confirming model's), "designs" (how many distinct designs were re-run), "failed" (those
    the confirming model could not evaluate), "computed" (cases computed by this call,
    screening and confirming), "metrics" {metric: {"low" | "high": {"params" (the toleranced
    values), "screen", "confirm", "rel_diff" ((confirm - screen) / |screen|)},
    "spread_screen", "spread_confirm" (high - low by each model), "spread_ratio" (confirm /
    screen)}}}; a design that failed has confirm and rel_diff None."""
    tolerances = study.tolerances
    if tolerances is None or tolerances.confirm is None:
        raise ValueError("the study declares no [tolerances.confirm]: nothing to re-check")
    screened = run(study)
    version = flexfem_version()
    by_key = {c.key: c for c in screened.cases}
    points = tolerances.points()
    outputs = []
    for point in points:
        case = by_key.get(case_key(study.mechanism, {**study.base, **point},
                                   screened.study.options, version))
        outputs.append(case.metrics if case is not None and case.ok else None)
    extremes = extreme_designs(points, outputs, list(tolerances.metrics) or varying(outputs))
    chosen = sorted({i for ends in extremes.values() for i in ends.values()})
    check = replace(study, name=f"{study.name}_confirm", grid={}, sample=None, plots=(),
                    tolerances=None, options={**screened.study.options, **tolerances.confirm},
                    cases=tuple(points[i] for i in chosen))
    confirmed = run(check) if chosen else None
    results = {c.key: c for c in confirmed.cases} if confirmed is not None else {}
    out = {}
    failed = set()
    for metric, ends in extremes.items():
        row = {}
        for end, i in ends.items():
            case = results.get(case_key(study.mechanism, {**study.base, **points[i]},
                                        confirmed.study.options, version))
            screen = outputs[i][metric]
            value = (case.metrics.get(metric) if case is not None and case.ok else None)
            if value is None:
                failed.add(i)
            row[end] = {"params": dict(points[i]), "screen": screen, "confirm": value,
                        "rel_diff": (None if value is None or screen == 0
                                     else (value - screen) / abs(screen))}
        lo, hi = row["low"], row["high"]
        row["spread_screen"] = hi["screen"] - lo["screen"]
        row["spread_confirm"] = (None if None in (hi["confirm"], lo["confirm"])
                                 else hi["confirm"] - lo["confirm"])
        row["spread_ratio"] = (None if row["spread_confirm"] is None or row["spread_screen"] == 0
                               else row["spread_confirm"] / row["spread_screen"])
        out[metric] = row
    computed = screened.computed + (confirmed.computed if confirmed is not None else 0)
    return {"options": dict(tolerances.confirm), "designs": len(chosen), "failed": len(failed),
            "computed": computed, "metrics": out}
