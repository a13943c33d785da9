"""Figures 9, 10, 13 (analytical), analytical_metrics and the reproduce contract."""
import csv
import json
import math

import numpy as np
import pytest

from flexfem.data import load_toml
from flexfem.geometry.dbma.params import paper_design
from flexfem.studies.dbma import figures as figs
from flexfem.studies.dbma import prbm as m


@pytest.fixture(scope="module")
def summary(tmp_path_factory):
    out = tmp_path_factory.mktemp("dbma_analytical")
    return out, figs.reproduce_analytical(out, quick=True)


def test_analytical_metrics_keys_and_values():
    metrics = figs.analytical_metrics(paper_design())
    for key in ("R_eq7", "Ke_eq14", "me_eq19", "fn_eq20", "R_enhanced", "R_rigid_arm",
                "R_kinematic", "K_out_enhanced", "K_out_free_input_enhanced", "K_in_enhanced",
                "fn_enhanced"):
        assert math.isfinite(metrics[key]) and metrics[key] > 0, key
    assert metrics["R_eq7"] == pytest.approx(12.80, abs=0.01)
    # Eq. 11 identity with the same mass model
    assert metrics["fn_eq20"] == pytest.approx(
        math.sqrt(metrics["Ke_eq14"] / metrics["me_eq19"]) / (2 * math.pi), rel=1e-12)
    json.dumps(metrics)  # JSON-able


def test_analytical_metrics_take_given_masses():
    p = paper_design()
    masses = dict(m.arm_masses(p), m4=0.02)
    assert figs.analytical_metrics(p, masses)["me_eq19"] == pytest.approx(
        figs.analytical_metrics(p)["me_eq19"] + 0.01, rel=1e-12)  # m4 enters as m4/2


def test_parameter_sweep_follows_the_formulas():
    p = paper_design()
    values = np.array([0.4e-3, 0.6e-3, 1.0e-3])
    sweep = figs.parameter_sweep(p, "b", values)
    assert np.array_equal(sweep["b"], values)
    assert sweep["R_eq7"][1] == pytest.approx(m.amplification_ratio(p), rel=1e-12)
    assert np.all(np.diff(sweep["R_eq7"]) < 0)  # Eq. 8: dR/db < 0
    assert np.all(np.diff(sweep["Ke_eq14"]) > 0)  # Eq. 15: dKe/db > 0


def test_reproduce_contract(summary, section_contract):
    out, result = summary
    section_contract(out, result)
    assert {"comparisons", "figures", "tables", "metrics", "paragraph"} <= set(result)
    assert {"fig9_R.png", "fig10_Ke.png", "fig13_analytical.png"} <= {
        f["file"] for f in result["figures"]}


def test_fig13_tables_span_the_published_ranges(summary):
    out, _ = summary
    for name, (low, high) in (("b", (0.4e-3, 1.0e-3)), ("h", (0.8e-3, 3.0e-3))):
        with open(out / f"fig13_R_vs_{name}.csv") as f:
            rows = list(csv.DictReader(f))
        column = [float(r[name]) for r in rows]
        assert column[0] == pytest.approx(low) and column[-1] == pytest.approx(high)
        assert {"R_eq7", "R_enhanced", "R_rigid_arm"} <= set(rows[0])


def test_comparisons_report_the_paper_discrepancies(summary):
    _, result = summary
    rows = {r["quantity"]: r for r in result["comparisons"]}
    implied = rows["R, Eq. 7 vs the theory value implied by FEM 15.3 and '6.06 %'"]
    # the paper prints FEM R and its difference from theory, not the theory value:
    # R_fem / (1 - 6.06 %) is that value, recomputed here from data/
    amp = load_toml("dbma_paper.toml")["amplification"]
    assert implied["reference"] == pytest.approx(
        amp["R_fem"] / (1 - amp["R_fem_vs_theory_rel_diff_pct"] / 100), rel=1e-12)
    assert implied["kind"] == "derived"
    # Eq. 7 as printed falls ~21 % short of it: reported, not hidden
    assert implied["difference"] < -0.15 and implied["verdict"] == "differs"
