"""Trade-offs: the Pareto front of a mechanism's design over its parameters, several objectives
and constraints, by NSGA-II (pymoo, a maintained implementation; Deb et al., IEEE Trans. Evol.
Comput. 6(2), 2002), screened by one model and confirmed by another.

A front file::

    mechanism = { model = "guide.toml" }    # or a registered name
    [base]                                   # the fixed parameters
    [options]                                # the screening model's options (model = "beam")
    [variables]                              # the searched parameters: name = [low, high]
    t = [0.5e-3, 1.5e-3]
    [[objectives]]                           # metric, "min" or "max"
    metric = "stiffness_stage_x"
    goal = "min"
    [[constraints]]                          # metric <= or >= a bound
    metric = "f1_hz"
    at_least = 100.0
    [search]
    population = 40
    generations = 30
    seed = 0
    [confirm]                                # options of the confirming model (optional)
    model = "continuum"
    [[reference]]                            # designs to place beside the front (optional)
    name = "paper"
    params = { t = 1e-3 }                    # over the base

Every evaluation is stored as it completes (the study store): a re-run with the same file and
seed asks for the same designs and finds them there. The front's designs are re-evaluated by
the confirming model where one is given, and each design carries its constraint margins
(positive: satisfied, in the metric's units). Each reference design is evaluated as well and
placed: its objectives, margins, and how many front designs dominate it (better or equal in
every objective, better in one).
"""
from dataclasses import dataclass, field
import math

import numpy as np

from ...geometry.user_model.quantities import si_value
from .store import CaseResult, ResultStore, case_key, flexfem_version
from .checks import warn_stale
from .validate import check_metric_names, check_parameter_names, normalise_options, \
    result_problems

GOALS = ("min", "max")


@dataclass(frozen=True)
class Front:
    """A front search: mechanism, base, options, variables {name: (low, high)}, objectives
    ((metric, goal), ...), constraints ((metric, "<=" | ">=", bound), ...), population,
    generations, seed, confirm (the confirming model's options, or None)."""

    mechanism: str
    variables: dict
    objectives: tuple
    constraints: tuple = ()
    base: dict = field(default_factory=dict)
    options: dict = field(default_factory=dict)
    population: int = 40
    generations: int = 30
    seed: int = 0
    confirm: dict | None = None
    references: tuple = ()

    def __post_init__(self):
        if not self.variables:
            raise ValueError("[variables] is empty: give at least one searched parameter")
        for name, bounds in self.variables.items():
            if not (isinstance(bounds, (list, tuple)) and len(bounds) == 2 and all(
                    isinstance(b, (int, float)) and math.isfinite(b) for b in bounds)
                    and bounds[0] < bounds[1]):
                raise ValueError(f"variables.{name} = {bounds!r} must be [low, high], low < high")
        if len(self.objectives) < 2:
            raise ValueError("a front needs at least two [[objectives]]")
        for metric, goal in self.objectives:
            if goal not in GOALS:
                raise ValueError(f"objective {metric!r}: goal = {goal!r} must be min or max")
        for metric, sense, bound in self.constraints:
            if sense not in ("<=", ">=") or not math.isfinite(bound):
                raise ValueError(f"constraint {metric!r}: give at_most or at_least a number")
        for name, low in (("population", 4), ("generations", 1)):
            value = getattr(self, name)
            if not (isinstance(value, int) and low <= value <= 10_000):
                raise ValueError(f"search.{name} = {value!r} must be an integer from {low} "
                                 "to 10000")
        if not (isinstance(self.seed, int) and not isinstance(self.seed, bool)
                and self.seed >= 0):
            raise ValueError(f"search.seed = {self.seed!r} must be an integer >= 0")


def _bound(value, where: str) -> float:
    """A constraint's bound: a number (SI) or a quantity string such as '0.5 mm'."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return float(value)
    if isinstance(value, str) and " " in value.strip():
        number, unit = value.strip().split(None, 1)
        return si_value(number, unit, None, where)
    raise ValueError(f"{where} = {value!r} must be a number (SI) or a quantity ('0.5 mm')")


def front_from_dict(data: dict) -> Front:
    """A Front from a parsed front file (mechanism already resolved to a name)."""
    allowed = {"mechanism", "name", "base", "options", "variables", "objectives", "constraints",
               "search", "confirm", "reference"}
    unknown = sorted(set(data) - allowed)
    if unknown:
        raise ValueError(f"unknown key(s) {unknown}; allowed: {sorted(allowed)}")
    for o in data.get("objectives", []):
        if not isinstance(o, dict) or set(o) != {"metric", "goal"}:
            extra = sorted(set(o) - {"metric", "goal"}) if isinstance(o, dict) else []
            raise ValueError(f"objective {o!r} must be {{ metric, goal = 'min' | 'max' }}"
                             + (f"; unknown key(s) {extra}" if extra else ""))
    objectives = tuple((o["metric"], o["goal"]) for o in data.get("objectives", []))
    constraints = []
    for c in data.get("constraints", []):
        if set(c) - {"metric", "at_most", "at_least"} or len(c) != 2 or "metric" not in c:
            raise ValueError(f"constraint {c!r} must be {{ metric, at_most | at_least }}")
        sense, key = ("<=", "at_most") if "at_most" in c else (">=", "at_least")
        constraints.append((c["metric"], sense, _bound(c[key], f"constraint {c['metric']!r} "
                                                                f"{key}")))
    search = data.get("search", {})
    unknown = sorted(set(search) - {"population", "generations", "seed"})
    if unknown:
        raise ValueError(f"[search]: unknown key(s) {unknown}; the keys are population, "
                         "generations and seed")
    references = []
    for r in data.get("reference", []):
        if not (isinstance(r, dict) and set(r) == {"name", "params"}
                and isinstance(r["params"], dict)):
            raise ValueError(f"reference {r!r} must be {{ name = \"...\", params = {{ ... }} }}")
        references.append((str(r["name"]), dict(r["params"])))
    return Front(data["mechanism"], dict(data.get("variables", {})), objectives,
                 tuple(constraints), dict(data.get("base", {})), dict(data.get("options", {})),
                 search.get("population", 40), search.get("generations", 30),
                 search.get("seed", 0), data.get("confirm"), tuple(references))


def check_front(front: Front, evaluate) -> None:
    """Refuse, before any evaluation, an option the evaluate does not take (screening or
    confirming) and a parameter it does not declare (base, variables, references), naming
    the key, the known names and the nearest (validate.py)."""
    normalise_options(evaluate, front.options, front.mechanism)
    if front.confirm:
        normalise_options(evaluate, {**front.options, **front.confirm}, front.mechanism,
                          where="confirm")
    named = [(f"base.{k}", k) for k in front.base]
    named += [(f"variables.{k}", k) for k in front.variables]
    named += [(f"reference {r!r} params.{k}", k) for r, params in front.references
              for k in params]
    check_parameter_names(evaluate, named, front.mechanism)
    check_metric_names(evaluate, [("objective", m) for m, _ in front.objectives]
                       + [("constraint", m) for m, _, _ in front.constraints], front.mechanism)


def _cached(evaluate, front: Front, store: ResultStore, options: dict):
    """evaluate(params) through the store: a stored design is not computed again, unless it
    fails the checks of a fresh result or lacks an objective's or a constraint's metric."""
    version = flexfem_version()
    done = {c.key: c for c in store.results()}
    required = [m for m, _ in front.objectives] + [m for m, _, _ in front.constraints]

    def run(params: dict) -> dict:
        key = case_key(front.mechanism, params, options, version)
        if key in done and done[key].ok:
            stale = result_problems(done[key].metrics, evaluate, required)
            if not stale:
                return done[key].metrics
            warn_stale({key: stale}, store.path)
        try:
            metrics = evaluate(dict(params), **options)
            problems = result_problems(metrics, evaluate, required)
            if problems:
                raise ValueError(f"result check: {'; '.join(problems)}")
            case = CaseResult(key, front.mechanism, params, options, "ok",
                              {k: v for k, v in metrics.items()
                               if isinstance(v, (int, float))}, flexfem_version=version)
        except ValueError as error:  # an infeasible design: stored, never retried
            metrics = None
            case = CaseResult(key, front.mechanism, params, options, "failed", {},
                              f"ValueError: {error}", flexfem_version=version)
        store.record(case)
        done[key] = case
        return case.metrics if metrics is not None else None
    return run


def search_front(front: Front, evaluate, store_path) -> dict:
    """The Pareto front: {"designs": [{params, objectives {metric: value}, margins {metric:
    margin}, confirmed {metric: value} (with a confirming model)}], "evaluations",
    "failed", "first_failure" (a failed design's error, when one failed)} sorted by the
    first objective. Failed designs count as infeasible."""
    from pymoo.algorithms.moo.nsga2 import NSGA2
    from pymoo.core.problem import ElementwiseProblem
    from pymoo.optimize import minimize

    check_front(front, evaluate)
    names = list(front.variables)
    lows = np.array([front.variables[n][0] for n in names], float)
    highs = np.array([front.variables[n][1] for n in names], float)
    signs = np.array([1.0 if goal == "min" else -1.0 for _, goal in front.objectives])
    n_con = len(front.constraints)
    with ResultStore(store_path) as store:
        run = _cached(evaluate, front, store, dict(front.options))
        counts = {"evaluations": 0, "failed": 0}

        def point(x) -> dict:
            return {**front.base, **{n: float(v) for n, v in zip(names, x)}}

        class FrontProblem(ElementwiseProblem):
            def __init__(self):
                super().__init__(n_var=len(names), n_obj=len(signs), n_ieq_constr=n_con,
                                 xl=lows, xu=highs)

            def _evaluate(self, x, out, *args, **kwargs):
                metrics = run(point(x))
                counts["evaluations"] += 1
                if metrics is None:
                    counts["failed"] += 1
                    if counts["failed"] == counts["evaluations"] == front.population:
                        first = next((c.error for c in store.results()
                                      if c.status != "ok" and c.error), "")
                        raise ValueError(f"every design of the first generation "
                                         f"({front.population}) failed, so the search stops "
                                         f"(they are stored); the first: {first}")
                    out["F"] = np.full(len(signs), 1e30)
                    out["G"] = np.ones(n_con) if n_con else []
                    return
                out["F"] = signs * np.array([metrics[m] for m, _ in front.objectives])
                out["G"] = [_violation(metrics[m], sense, bound)
                            for m, sense, bound in front.constraints]

        result = minimize(FrontProblem(), NSGA2(pop_size=front.population),
                          ("n_gen", front.generations), seed=front.seed, verbose=False)
        designs = []
        for x in np.atleast_2d(result.X) if result.X is not None else []:
            params = point(x)
            metrics = run(params)
            designs.append({"params": params,
                            "objectives": {m: metrics[m] for m, _ in front.objectives},
                            "margins": {m: -_violation(metrics[m], s, b)
                                        for m, s, b in front.constraints}})
        if front.confirm is not None:
            check = _cached(evaluate, front, store, {**front.options, **front.confirm})
            for design in designs:
                metrics = check(design["params"])
                design["confirmed"] = ({m: metrics[m] for m, _ in front.objectives}
                                       if metrics is not None else None)
        references = []
        for name, params in front.references:
            metrics = run({**front.base, **params})
            if metrics is None:
                raise ValueError(f"reference {name!r}: its design could not be evaluated")
            objectives = {m: metrics[m] for m, _ in front.objectives}
            references.append({"name": name, "params": {**front.base, **params},
                               "objectives": objectives,
                               "margins": {m: -_violation(metrics[m], s, b)
                                           for m, s, b in front.constraints},
                               "dominated_by": sum(_dominates(d["objectives"], objectives,
                                                              front.objectives)
                                                   for d in designs)})
        if counts["failed"]:  # why, in the design's own words
            counts["first_failure"] = next((c.error for c in store.results()
                                            if c.status != "ok" and c.error), None)
    first = front.objectives[0][0]
    designs.sort(key=lambda d: d["objectives"][first])
    return {"designs": designs, "references": references, **counts}


def _dominates(a: dict, b: dict, objectives) -> bool:
    """True where objectives ``a`` are at least as good as ``b`` in all and better in one."""
    better = [(a[m] - b[m]) * (1 if goal == "min" else -1) for m, goal in objectives]
    return all(x <= 0 for x in better) and any(x < 0 for x in better)


def _violation(value: float, sense: str, bound: float) -> float:
    """pymoo's G <= 0 form of ``value sense bound``."""
    return value - bound if sense == "<=" else bound - value
