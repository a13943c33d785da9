"""DBMA design search: a known constrained optimum on a surrogate, calibration to the check
mesh, infeasible specs, the case store, the CLI, and one real FEM search (slow)."""
import dataclasses
import json
import math
import sqlite3

import numpy as np
import pytest
from flexfem.geometry.dbma.params import paper_design
from flexfem.studies import cli
from flexfem.studies.dbma import enhanced as dbma_enhanced
from flexfem.studies.dbma import optimize as opt
from flexfem.studies.dbma.optimize_output import history_rows, run
from flexfem.studies.dbma.optimize_spec import (
    NAMES,
    InfeasibleSpecError,
    OptimizeSpec,
    constraint_table,
    constraints_of,
)
from scipy.optimize import linprog

P = paper_design()
REF = np.array([0.6e-3, 2.6e-3, 4.41e-3])  # the surrogate's reference design (b, h, l), m
YIELD = 250e6
# log-linear surrogate: metric = C * prod((x / REF) ** exponent), x = (b, h, l)
EXPONENTS = {"R_fem": (-0.5, -0.8, 0.3), "fn_working": (1.0, 0.3, -1.2),
             "k_out": (2.0, 0.5, -2.0), "max_von_mises": (0.5, -0.5, -0.5)}
CONSTANTS = {"R_fem": 8.0, "fn_working": 300.0, "k_out": 5e5, "max_von_mises": 1e8}
MESH_BIAS = 0.03  # the surrogate's frequency rises 3 % per unit of size_factor above 1
CALLS = {"n": 0, "fail_after": None}


def surrogate(params: dict, size_factor: float) -> dict:
    """The 'FEM': counts its calls and crashes after CALLS["fail_after"] when set."""
    CALLS["n"] += 1
    if CALLS["fail_after"] is not None and CALLS["n"] > CALLS["fail_after"]:
        raise RuntimeError("simulated crash")
    return surrogate_raw(params, size_factor)


def surrogate_raw(params: dict, size_factor: float) -> dict:
    """Raw metrics in the form of fem_metrics: elongation 20 um at 100 N, so the stress at a
    20 um stroke is max_von_mises itself."""
    x = np.array([params[n] for n in NAMES]) / REF
    m = {k: CONSTANTS[k] * float(np.prod(x ** np.array(e))) for k, e in EXPONENTS.items()}
    m["fn_working"] *= 1 + MESH_BIAS * (size_factor - 1)
    return {**m, "force": 100.0, "elongation": 20e-6, "k_in": 5e6,
            "max_von_mises_element": 1.3 * m["max_von_mises"], "working_mode": 2,
            "yield_strength": YIELD, "dofs": 1}


def biased_estimator(p, stroke):
    """An 'analytical model' 20 % off in R and 10 % off in frequency: the FEM must decide."""
    raw = design(surrogate_raw({n: getattr(p, n) for n in NAMES}, 1.0), stroke)
    return {"R_fem": 1.2 * raw["R_fem"], "fn_working": 1.1 * raw["fn_working"],
            "k_out": raw["k_out"], "von_mises_at_stroke": raw["von_mises_at_stroke"]}


def design(raw, stroke):
    return opt.design_metrics(raw, stroke)


def reference_optimum(spec: OptimizeSpec) -> tuple[np.ndarray, float]:
    """The exact optimum: in y = log(x / REF) the surrogate is linear, so the search is a
    linear program (HiGHS), solved here independently of the search."""
    E = {k: np.array(v) for k, v in EXPONENTS.items()}
    A = [-E["fn_working"], -E["k_out"], E["max_von_mises"]]
    b = [-math.log(spec.min_frequency_hz / CONSTANTS["fn_working"]),
         -math.log(spec.min_output_stiffness / CONSTANTS["k_out"]),
         math.log(YIELD / spec.safety_factor / CONSTANTS["max_von_mises"]
                  * 20e-6 / spec.stroke_m)]
    bounds = list(zip(np.log(spec.lower / REF), np.log(spec.upper / REF)))
    lp = linprog(-E["R_fem"], A_ub=np.array(A), b_ub=b, bounds=bounds, method="highs")
    assert lp.success
    return REF * np.exp(lp.x), CONSTANTS["R_fem"] * math.exp(-lp.fun)


SPEC = OptimizeSpec(min_frequency_hz=300.0, safety_factor=1.5, min_output_stiffness=3e5,
                    max_evaluations=40, n_seed=256)


def test_search_finds_the_constrained_optimum_of_a_surrogate():
    x_ref, R_ref = reference_optimum(SPEC)
    r = opt.optimize(SPEC, evaluator=surrogate, estimator=biased_estimator)
    x = np.array([r["optimum"][n] for n in NAMES])
    # COBYQA stops at a trust radius of 0.005 of each range; the optimum is a vertex where
    # R changes by <= 0.8 |dlog x| per variable, so 1 % in R and 3 % of a range in x
    assert r["R_fem"] == pytest.approx(R_ref, rel=1e-2)
    assert r["R_fem"] <= R_ref * (1 + 1e-3)  # feasible points cannot beat the LP optimum
    assert np.all(np.abs(x - x_ref) <= 0.03 * (SPEC.upper - SPEC.lower))
    assert all(c["met"] for c in r["constraints"])
    # the LP's binding constraints are the ones reported active
    active_ref = {name for name, key, bound, kind in constraints_of(SPEC, YIELD)
                  if abs(design(surrogate_raw(dict(zip(NAMES, x_ref)), 1.0), SPEC.stroke_m)[key]
                         / bound - 1) < 1e-6}
    assert set(r["active_constraints"]) == active_ref and active_ref
    assert r["n_fem_evaluations"] <= SPEC.max_evaluations + 4
    # the biased model put the seed elsewhere; the report says by how much
    assert r["seed"]["analytical_vs_fem"]["R_fem"] == pytest.approx(0.2, rel=1e-9)


def test_search_on_a_coarse_mesh_is_calibrated_to_the_check_mesh():
    spec = dataclasses.replace(SPEC, search_size_factor=2.0, check_size_factor=1.0)
    x_ref, R_ref = reference_optimum(spec)
    r = opt.optimize(spec, evaluator=surrogate, estimator=biased_estimator)
    assert r["corrections"]["fn_working"] == pytest.approx(1 / (1 + MESH_BIAS), rel=1e-9)
    # the uncorrected search mesh overstates fn by 3 %: the optimum, checked at size_factor
    # 1, must still meet 300 Hz and be the true optimum (1 % as above)
    assert r["metrics"]["fn_working"] >= 300.0
    assert r["R_fem"] == pytest.approx(R_ref, rel=1e-2)
    assert r["n_check_evaluations"] >= 2  # the seed's calibration and the final check


def test_infeasible_constraints_raise_before_any_fem():
    with pytest.raises(InfeasibleSpecError, match="frequency.*best over the bounds"):
        opt.optimize(dataclasses.replace(SPEC, min_frequency_hz=3000.0),
                     evaluator=lambda *a: pytest.fail("FEM called"))


@pytest.mark.parametrize("change, name", [
    ({"b_min": -1e-3}, "b_min"), ({"h_max": 0.4e-3}, "h_max"), ({"safety_factor": 0.5}, "safety_factor"),
    ({"stroke_m": 0.0}, "stroke_m"), ({"min_frequency_hz": -1.0}, "min_frequency_hz"),
    ({"max_evaluations": 5}, "max_evaluations"), ({"l_max": float("nan")}, "l_max"),
    ({"n_seed": 2.5}, "n_seed"),
])
def test_bad_spec_raises_naming_the_field(change, name):
    with pytest.raises(ValueError, match=name):
        OptimizeSpec(**change)


def test_bounds_must_give_buildable_designs():
    # h + b must stay below c - ... (DBMAParams: h <= c - b = 10 - 1.2 mm)
    with pytest.raises(ValueError, match=r"b_max, h_max, l_max.*h = 0\.009"):
        opt.optimize(OptimizeSpec(h_max=9e-3), evaluator=surrogate)
    with pytest.raises(ValueError, match="arm length"):  # l < e = 19.9 mm
        opt.optimize(OptimizeSpec(l_max=25e-3), evaluator=surrogate)


def test_store_makes_a_rerun_free_and_keeps_evaluations_of_a_crash(tmp_path):
    store = tmp_path / "cache.sqlite"
    spec = dataclasses.replace(SPEC, max_evaluations=20)
    CALLS.update(n=0, fail_after=7)
    try:
        with pytest.raises(RuntimeError, match="simulated crash"):
            opt.optimize(spec, store, evaluator=surrogate, estimator=biased_estimator)
    finally:
        CALLS.update(n=0, fail_after=None)
    with sqlite3.connect(store) as db:
        assert db.execute("SELECT COUNT(*) FROM cases").fetchone()[0] == 7
    first = opt.optimize(spec, store, evaluator=surrogate, estimator=biased_estimator)
    assert CALLS["n"] == first["n_fem_computed"] == first["n_fem_evaluations"] - 7
    CALLS["n"] = 0
    again = opt.optimize(spec, store, evaluator=surrogate, estimator=biased_estimator)
    assert CALLS["n"] == 0 and again["n_fem_computed"] == 0
    assert again["optimum"] == first["optimum"]
    assert all(r["cached"] for r in again["history"])


def test_metrics_scale_with_the_stroke():
    raw = surrogate_raw(dict(zip(NAMES, REF)), 1.0)
    one, two = design(raw, 20e-6), design(raw, 40e-6)
    assert two["von_mises_at_stroke"] == pytest.approx(2 * one["von_mises_at_stroke"], rel=1e-12)
    assert one["von_mises_at_stroke"] == pytest.approx(raw["max_von_mises"], rel=1e-12)
    # Thevenin source at the output: free stroke R s, stiffness k_out, blocked force their product
    assert two["blocked_output_force"] == pytest.approx(raw["k_out"] * raw["R_fem"] * 40e-6)
    assert two["actuator_force"] == pytest.approx(200.0)  # 100 N gave 20 um


def test_hinge_stress_estimate_matches_the_rigid_arm_closed_form():
    # with a very wide arm (c = 100 mm) the arm is rigid: the hinges carry N and M = N h / 2
    # and delta = N l (2 / (E A) + h^2 / (2 E I)) (docs/dbma-analytical.md), so the largest
    # stress is N / A + (N h / 2) (b / 2) / I; the arm's residual compliance is < 1e-3
    p = dataclasses.replace(P, c=100e-3)
    stroke = 20e-6
    A, I = p.d * p.b, p.d * p.b**3 / 12
    N = stroke / 2 / (p.l * (2 / (p.E * A) + p.h**2 / (2 * p.E * I)))
    est = opt.analytical_estimates(p, stroke)
    assert est["von_mises_at_stroke"] == pytest.approx(N / A + N * p.h / 2 * p.b / 2 / I, rel=5e-3)
    assert est["R_fem"] == pytest.approx(dbma_enhanced.amplification_ratio_enhanced(p) / 2, rel=1e-12)
    assert est["k_out"] == pytest.approx(dbma_enhanced.output_stiffness_enhanced(p), rel=1e-12)


def _main(argv, monkeypatch):
    return cli.main(argv)


def test_cli_json_and_outputs(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(opt, "fem_metrics", surrogate)
    monkeypatch.setattr(opt, "analytical_estimates", biased_estimator)
    rc = _main(["optimize", "dbma", "--quick", "--json", "--out", str(tmp_path),
                "--min-frequency", "310", "--stroke", "1e-5"], monkeypatch)
    out = capsys.readouterr().out
    assert rc == 0 and out.count("\n") == 1
    r = json.loads(out)
    assert r["spec"]["min_frequency_hz"] == 310.0 and r["spec"]["stroke_m"] == 1e-5
    assert r["spec"]["max_evaluations"] == 12 and r["n_search_evaluations"] <= 12
    assert r["metrics"]["fn_working"] >= 310.0
    assert {"optimum", "R_fem", "constraints", "active_constraints", "n_fem_evaluations",
            "history"} <= set(r)
    lines = (tmp_path / "optimize_history.csv").read_text().splitlines()
    assert len(lines) == 1 + len(r["history"]) and lines[0].startswith("evaluation,stage")
    assert (tmp_path / "optimize_history.png").stat().st_size > 1000
    rc = _main(["optimize", "dbma", "--out", str(tmp_path), "--min-frequency", "5000"], monkeypatch)
    assert rc == 2 and "min_frequency" not in capsys.readouterr().out


def test_fem_metrics_of_the_paper_design_coarse():
    # the same model and load as dbma_fem.evaluate: identical R, k_in and stress
    from flexfem.studies.dbma.analysis import evaluate
    params = {n: getattr(P, n) for n in NAMES}
    raw = opt.fem_metrics(params, 2.83)
    ref = evaluate(params, 2, 2.83, modes=True, force=100.0)
    for key in ("R_fem", "k_in", "max_von_mises"):
        assert raw[key] == pytest.approx(ref[key], rel=1e-9)
    assert raw["fn_working"] == pytest.approx(ref["fn_working"], rel=1e-6)
    # the beam model's hinges (length l between rigid blocks) miss the FEM's hinge roots:
    # an effective length within +-10 % moves a l^-3 stiffness by about +-30 %
    assert raw["k_out"] == pytest.approx(dbma_enhanced.output_stiffness_enhanced(P), rel=0.3)


@pytest.mark.slow
def test_real_fem_quick_search(tmp_path):
    r = run(OptimizeSpec(), tmp_path, quick=True)
    assert r["feasible"] and all(c["met"] for c in r["constraints"])
    assert r["check_size_factor"] == 1.0
    # the paper's design lies in the box and meets the default constraints (docs/dbma.md):
    # the search may not return anything worse
    paper = opt.design_metrics(opt.fem_metrics({n: getattr(P, n) for n in NAMES}, 1.0), 20e-6)
    assert all(c["met"] for c in constraint_table(paper, constraints_of(OptimizeSpec(), YIELD)))
    assert r["R_fem"] > paper["R_fem"]
    assert r["metrics"]["working_mode"] == 2  # the in-plane working mode, 2nd in 2-D
    rows = history_rows(r)
    assert len(rows) == r["n_fem_evaluations"]


def test_report_section_skips_the_search_in_a_quick_report(tmp_path):
    """A quick report skips the FEM design search (no comparisons) and shows only the
    beam-screened Pareto front, written under front/."""
    from flexfem.studies.dbma.optimize_output import reproduce
    summary = reproduce(tmp_path, quick=True)
    assert summary["comparisons"] == []
    assert [f["file"] for f in summary["figures"]] == ["front/dbma_front.png"]
    assert "flexfem optimize dbma" in summary["notes"][0]
    assert [p.name for p in tmp_path.iterdir()] == ["front"]  # no search written
