"""Design search of the DBMA hinges (b, h, l): maximise the amplification ratio, FEM decides.

Maximise R_fem (output / actuator elongation, 2-D plane-stress FEM; R_fem_per_side = 2 R_fem
is the paper's reading) over b, h, l in a box, subject to
  * frequency: working-mode frequency >= min_frequency_hz (2-D modal solve, mounting face held,
    pads held along x; the working mode is in-plane, so plane stress gives it);
  * stress: max von Mises (nodal, L2-projected) at the actuator stroke <= yield / safety_factor;
    the stroke is the actuator elongation (pad to pad) in m, the model is linear, so the stress
    is the 100 N solve's scaled by stroke / elongation;
  * output stiffness: k_out = F / u_out for a force F on the output face along y with the
    mounting face held and the pads held along x (actuator rigid, holding its stroke) >=
    min_output_stiffness (N/m). Seen from its output the DBMA is then a source of free stroke
    R_fem * stroke and stiffness k_out: blocked force k_out R_fem stroke.
Steps: (1) screen a Sobol sample of the box with the elastic-beam model (dbma_enhanced) and a
beam estimate of the hinge stress: the best design is the analytical seed; (2) FEM of the seed
on the search and the check mesh; the FEM/analytical ratios there re-rank the sample (the
start), the check/search ratios calibrate the search mesh (1 when, as by default, both are the
default mesh, size_factor 1); (3) COBYQA (scipy, derivative-free, bounds and nonlinear
constraints) on the calibrated search mesh from the start; (4) FEM on the check mesh of the
best calibrated-feasible design, re-calibrated at it and repeated (3 times at most) if it
fails. Every FEM evaluation is stored in an SQLite case store (studies/store.py) keyed by its
design and mesh: a re-run is free, a crash loses only the case in flight. The spec and the
constraints are in :mod:`.optimize_spec`. SI units.
"""
import math
import time
from dataclasses import asdict, replace

import numpy as np

from ...fem import Force, solve_static
from ...geometry.dbma.params import DBMAParams, paper_design
from ..engine.store import CaseResult, ResultStore, case_key
from . import analysis as dbma_fem
from . import enhanced as en
from . import prbm as prbm
from .analysis import dbma_material
from .optimize_spec import (
    NAMES,
    InfeasibleSpecError,
    OptimizeSpec,
    at_bounds,
    check_box,
    constraint_table,
    constraints_of,
    margins,
)

FORCE = 100.0  # N, the actuator force of the linear solves (results are scaled to the stroke)
SCREEN_TOL = 0.30  # screening: analytical models miss FEM by up to ~20 % (docs/dbma.md)
ROUND_M = 1e-7  # designs are rounded to 0.1 um: stable store keys, far below any tolerance


# ---- analytical screening ----------------------------------------------------------------

def analytical_estimates(p: DBMAParams, stroke: float) -> dict:
    """Elastic-beam (dbma_enhanced) predictions, keyed like ``design_metrics``: R_fem
    (= R_enhanced / 2, output over elongation), k_out (input blocked, N/m), fn_working (Eq. 11
    with k_out and Eq. 19's mass at R_enhanced, Hz), von_mises_at_stroke: the largest
    N / (b d) + 6 M / (d b^2) in the two hinges of a quarter at the stroke (Pa)."""
    R = en.amplification_ratio_enhanced(p)
    k_out = en.output_stiffness_enhanced(p)
    fn = prbm.natural_frequency(k_out, prbm.equivalent_mass(R, **prbm.arm_masses(p)))
    xy = [(0.0, 0.0), (p.l, 0.0), (p.l + p.e, p.h), (2 * p.l + p.e, p.h)]
    members = [(0, 1, "hinge"), (1, 2, "arm"), (2, 3, "hinge")]
    u, _ = en.solve_frame(p, xy, members, {0: -stroke / 2, 1: 0.0, 2: 0.0, 9: 0.0, 11: 0.0}, {})
    area, inertia = p.d * p.b, p.d * p.b**3 / 12
    stress = 0.0
    for i, j in ((0, 1), (2, 3)):  # the hinges lie along x: global = local end forces
        dofs = [3 * i, 3 * i + 1, 3 * i + 2, 3 * j, 3 * j + 1, 3 * j + 2]
        end = en.frame_element_stiffness(*xy[i], *xy[j], p.E, area, inertia) @ u[dofs]
        moment = max(abs(end[2]), abs(end[5]))
        stress = max(stress, abs(end[0]) / area + moment * p.b / 2 / inertia)
    return {"R_fem": R / 2, "k_out": k_out, "fn_working": fn, "von_mises_at_stroke": stress}


def sobol_designs(spec: OptimizeSpec) -> np.ndarray:
    """(n_seed, 3) scrambled Sobol points of the box (m), rounded to 0.1 um."""
    from scipy.stats import qmc
    n = 2 ** math.ceil(math.log2(spec.n_seed))
    unit = qmc.Sobol(3, seed=spec.seed).random(n)[:spec.n_seed]
    return _round(spec.lower + unit * (spec.upper - spec.lower))


def screen(spec: OptimizeSpec, base: DBMAParams, designs: np.ndarray,
           estimator=analytical_estimates) -> list[dict]:
    """Analytical estimates of each design (rows with b, h, l and the metrics)."""
    return [{**dict(zip(NAMES, map(float, x))),
             **estimator(replace(base, **dict(zip(NAMES, map(float, x)))), spec.stroke_m)}
            for x in designs]


def pick(rows: list[dict], constraints: list[tuple], scale: dict | None = None) -> tuple[int, float]:
    """Index of the best row: the largest R among those meeting every constraint (metrics
    multiplied by ``scale``), else the least-violating; and that row's worst margin."""
    scale = scale or {}
    scaled = [{k: r[k] * scale.get(k, 1.0) for k in CALIBRATED} for r in rows]
    worst = np.array([margins(r, constraints).min() for r in scaled])
    R = np.array([r["R_fem"] for r in scaled])
    ok = worst >= 0
    i = int(np.argmax(np.where(ok, R, -np.inf))) if ok.any() else int(np.argmax(worst))
    return i, float(worst[i])


# the spec fields each constraint's bound comes from (:func:`constraints_of`)
BOUND_OF = {"stress": "yield / safety_factor", "frequency": "min_frequency_hz",
            "output_stiffness": "min_output_stiffness"}


def infeasible_message(rows: list[dict], constraints: list[tuple]) -> str:
    """Say which constraint cannot be met over the box, with its best screened value."""
    parts = []
    for name, key, bound, kind in constraints:
        values = [r[key] for r in rows]
        best = max(values) if kind == ">=" else min(values)
        if (best < bound) if kind == ">=" else (best > bound):
            parts.append(f"{name}: {key} {kind} {bound:.4g} ({BOUND_OF[name]}), best over the "
                         f"bounds {best:.4g}")
    why = "; ".join(parts) or "each constraint can be met alone, not all together"
    return ("no design within the bounds meets the constraints within "
            f"{100 * SCREEN_TOL:.0f} % by the analytical screening ({why}); "
            "relax a bound or a constraint")


# ---- FEM evaluation and its cache --------------------------------------------------------

def fem_metrics(params: dict, size_factor: float) -> dict:
    """Raw 2-D FEM metrics of the paper's design with ``params`` (b, h, l in m) replaced: the
    static response at FORCE (N), k_out (N/m, module docstring), the working mode (Hz)."""
    p = replace(paper_design(), **params)
    model = dbma_fem.build_model(p, None, 2, size_factor)
    static = dbma_fem.static_response(model, FORCE)
    probe = solve_static(model, dbma_fem.modal_supports(), [Force("output", (0.0, FORCE))])
    modal, _ = dbma_fem.modal_response(model, n_modes=4)
    keep = ("force", "elongation", "R_fem", "k_in", "max_von_mises", "max_von_mises_element")
    return {**{k: float(static[k]) for k in keep},
            "k_out": FORCE / float(probe.mean_displacement("output")[1]),
            "fn_working": modal["fn_working"], "working_mode": modal["working_mode"],
            "yield_strength": model.material.yield_strength, "dofs": int(model.n_dofs)}


def design_metrics(raw: dict, stroke: float) -> dict:
    """Metrics at the actuator stroke (m) from the linear solve at raw['force']: R_fem,
    R_fem_per_side, fn_working (Hz), working_mode (1-based), k_out (N/m), von_mises_at_stroke (Pa, nodal; _element: at
    a quadrature point), actuator_force (N), free_output (m), blocked_output_force (N)."""
    scale = stroke / raw["elongation"]
    return {"R_fem": raw["R_fem"], "R_fem_per_side": 2 * raw["R_fem"],
            "fn_working": raw["fn_working"], "working_mode": raw["working_mode"], "k_out": raw["k_out"],
            "von_mises_at_stroke": raw["max_von_mises"] * scale,
            "von_mises_element_at_stroke": raw["max_von_mises_element"] * scale,
            "actuator_force": raw["force"] * scale, "free_output": raw["R_fem"] * stroke,
            "blocked_output_force": raw["k_out"] * raw["R_fem"] * stroke}


class Evaluations:
    """FEM evaluations through the case store (or a dict when ``store_path`` is None), and the
    history of every request: stage, mesh, design, metrics, whether it was cached."""

    def __init__(self, evaluator, stroke: float, store_path=None):
        self.evaluator, self.stroke = evaluator, stroke
        self.store = None if store_path is None else ResultStore(store_path)
        self.memory, self.history, self.computed = {}, [], 0
        self.tag = f"{evaluator.__module__}.{evaluator.__qualname__}"

    def __call__(self, x, size_factor: float, stage: str) -> dict:
        params = dict(zip(NAMES, (float(v) for v in _round(x))))
        options = {"evaluator": self.tag, "dim": 2, "size_factor": float(size_factor), "force": FORCE}
        key = case_key("dbma_optimize", params, options)
        if key in self.memory:  # asked again in this run: not a new evaluation
            return design_metrics(self.memory[key], self.stroke)
        raw, cached, wall = None, True, 0.0
        if raw is None and self.store is not None:
            found = self.store.results([key])
            raw = found[0].metrics if found and found[0].ok else None
        if raw is None:
            cached, start = False, time.perf_counter()
            raw = self.evaluator(params, size_factor)
            wall = time.perf_counter() - start
            self.computed += 1
            if self.store is not None:
                self.store.record(CaseResult(key, "dbma_optimize", params, options, "ok", raw,
                                             wall_time_s=wall, dofs=raw.get("dofs")))
        self.memory[key] = raw
        metrics = design_metrics(raw, self.stroke)
        self.history.append({"evaluation": len(self.history) + 1, "stage": stage,
                             "size_factor": float(size_factor), **params, **metrics,
                             "yield_strength": raw["yield_strength"], "cached": cached,
                             "wall_time_s": wall})
        return metrics

    def close(self):
        if self.store is not None:
            self.store.close()


def _round(x):
    return np.round(np.asarray(x, dtype=float) / ROUND_M) * ROUND_M


CALIBRATED = ("R_fem", "fn_working", "k_out", "von_mises_at_stroke")


def ratios(num: dict, den: dict) -> dict:
    return {k: num[k] / den[k] for k in CALIBRATED}


# ---- the search --------------------------------------------------------------------------

def optimize(spec: OptimizeSpec | None = None, store_path=None, evaluator=None,
             estimator=None) -> dict:
    """Run the design search (module docstring) and return a JSON-able summary: optimum
    (b, h, l in m), its check-mesh metrics, each constraint (value, bound, active), the
    analytical seed beside the FEM, n_fem_evaluations and the history. ``store_path``: SQLite
    file caching the FEM evaluations. ``evaluator(params, size_factor) -> raw metrics`` and
    ``estimator(DBMAParams, stroke) -> metrics`` replace the FEM (default ``fem_metrics``) and
    the screening (default ``analytical_estimates``), for tests.
    Raises InfeasibleSpecError when the screening or the FEM finds no feasible design."""
    spec = spec or OptimizeSpec()
    evaluator, estimator = evaluator or fem_metrics, estimator or analytical_estimates
    base = paper_design()
    check_box(spec, base)
    cons = constraints_of(spec, dbma_material(base).yield_strength)
    start = time.perf_counter()
    designs = sobol_designs(spec)
    rows = screen(spec, base, designs, estimator)
    i0, worst = pick(rows, cons)
    if worst < -math.log(1 + SCREEN_TOL):
        raise InfeasibleSpecError(infeasible_message(rows, cons))
    ev = Evaluations(evaluator, spec.stroke_m, store_path)
    try:
        result = _fem_search(spec, cons, ev, designs, rows, i0)
        result["analytical_at_optimum"] = estimator(
            replace(base, **result["optimum"]), spec.stroke_m)
    finally:
        ev.close()
    result.update(spec=asdict(spec), n_screened=len(rows), wall_time_s=time.perf_counter() - start)
    return result


def _fem_search(spec, cons, ev, designs, rows, i0) -> dict:
    from scipy.optimize import Bounds, NonlinearConstraint, minimize
    search, check = spec.search_size_factor, spec.check_size_factor
    analytic = {k: rows[i0][k] for k in CALIBRATED}
    coarse0 = ev(designs[i0], search, "seed")
    fine0 = ev(designs[i0], check, "calibration")
    corr = ratios(fine0, coarse0)
    i1, _ = pick(rows, cons, ratios(fine0, analytic))  # the screening re-ranked by the FEM
    lo, hi = spec.lower, spec.upper

    def calibrated(z):
        m = ev(lo + np.clip(z, 0, 1) * (hi - lo), search, "search")
        return {k: m[k] * corr[k] for k in CALIBRATED}

    opt = minimize(lambda z: -math.log(calibrated(z)["R_fem"]), (designs[i1] - lo) / (hi - lo),
                   method="COBYQA", bounds=Bounds(0, 1),
                   constraints=NonlinearConstraint(lambda z: margins(calibrated(z), cons), 0, np.inf),
                   options={"maxfev": spec.max_evaluations - 1, "initial_tr_radius": 0.1,
                            "final_tr_radius": 1e-3, "feasibility_tol": 1e-3})
    checked = [(designs[i0], fine0)]
    for _ in range(3):  # check the best calibrated-feasible design; re-calibrate if it fails
        tried = {tuple(_round(x)) for x, _ in checked}
        pool = [r for r in ev.history if r["size_factor"] == search
                and tuple(_round([r[n] for n in NAMES])) not in tried]
        if not pool:
            break
        i, worst = pick(pool, cons, corr)
        if worst < 0:
            break
        x = np.array([pool[i][n] for n in NAMES])
        fine = ev(x, check, "check")
        checked.append((x, fine))
        if margins(fine, cons).min() >= 0:
            break
        corr = ratios(fine, pool[i])
    feasible = [(x, m) for x, m in checked if margins(m, cons).min() >= 0]
    if not feasible:
        x, m = max(checked, key=lambda xm: margins(xm[1], cons).min())
        table = "; ".join(f"{c['constraint']} {c['value']:.4g} vs {c['bound']:.4g}"
                          for c in constraint_table(m, cons) if not c["met"])
        raise InfeasibleSpecError(f"the FEM found no feasible design in {len(ev.memory)} "
                                  f"evaluations; the least violating, (b, h, l) = {tuple(x)} m, "
                                  f"misses {table}")
    x, best = max(feasible, key=lambda xm: xm[1]["R_fem"])
    table = constraint_table(best, cons)
    stages = [r["stage"] for r in ev.history]
    return {"optimum": dict(zip(NAMES, map(float, x))), "R_fem": best["R_fem"],
            "R_fem_per_side": best["R_fem_per_side"], "metrics": best, "constraints": table,
            "active_constraints": [c["constraint"] for c in table if c["active"]],
            "feasible": True, "check_size_factor": check, "search_size_factor": search,
            "seed": {"design": dict(zip(NAMES, map(float, designs[i0]))), "analytical": analytic,
                     "fem": {k: fine0[k] for k in CALIBRATED},
                     "analytical_vs_fem": {k: analytic[k] / fine0[k] - 1 for k in CALIBRATED}},
            "seed_to_optimum": {n: float(x[j] - designs[i0][j]) for j, n in enumerate(NAMES)},
            "R_gain_over_seed": best["R_fem"] / fine0["R_fem"] - 1,
            "corrections": corr, "n_fem_evaluations": len(ev.memory),
            "n_fem_computed": ev.computed,
            "n_search_evaluations": stages.count("seed") + stages.count("search"),
            "n_check_evaluations": stages.count("calibration") + stages.count("check"),
            "at_bounds": at_bounds(spec, x),
            "start": dict(zip(NAMES, map(float, designs[i1]))),
            "cobyqa": {"success": bool(opt.success), "message": str(opt.message),
                       "nfev": int(opt.nfev)},
            "history": ev.history}

