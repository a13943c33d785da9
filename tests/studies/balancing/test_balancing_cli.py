"""`flexfem balance` and the reproduction section of the balancing study."""
import json

import numpy as np
import pytest

from flexfem.data import load_toml
from flexfem.studies.balancing.report import balance_robot, default_workspace, reproduce
from flexfem.studies.cli import main


def test_balance_json_all_methods(capsys):
    assert main(["balance", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    rows = out["results"]
    assert len(rows) == 12 and {r["method"] for r in rows} == {"spring", "torsion", "counterweight"}
    assert {r["motor"] for r in rows} == {2, 3, 4, 5}
    for r in rows:
        assert set(r) == {"motor", "method", "params", "rms_reduction_pct", "max_reduction_pct"}
        assert 0.0 < r["rms_reduction_pct"] < 100.0


def test_balance_summary_one_method(capsys):
    assert main(["balance", "--method", "torsion"]) == 0
    text = capsys.readouterr().out
    assert "N m/rad" in text and " deg" in text and "spring " not in text
    assert text.count("torsion") == 4


def test_invalid_method_is_an_argparse_error(capsys):
    with pytest.raises(SystemExit) as error:
        main(["balance", "--method", "magnet"])
    assert error.value.code != 0
    with pytest.raises(ValueError, match="method = 'magnet'"):
        balance_robot("magnet")


def test_spring_and_counterweight_reductions_coincide():
    """Section V.C: the counterweight problem is the spring problem (Tables III and V)."""
    rows = balance_robot("all", default_workspace(quick=True))["results"]
    by = {(r["method"], r["motor"]): r for r in rows}
    for m in (2, 3, 4, 5):
        assert by["spring", m]["rms_reduction_pct"] == pytest.approx(
            by["counterweight", m]["rms_reduction_pct"], abs=1e-9)


def test_reproduce_quick_writes_tables_and_figure(tmp_path, section_contract):
    summary = reproduce(tmp_path, quick=True)
    section_contract(tmp_path, summary)
    assert {"balancing_fig10.png", "balancing_pivot_fem.png", "balancing_stroke_limits.png"} <= {
        f["file"] for f in summary["figures"]}
    # stroke limits beside the cross-spring pivots' for the compressed leaves of motors 2 and 4
    leaves = [s for s in summary["stroke_limits"] if "compressed-leaf" in s["stroke"]]
    assert [s["stroke"][:7] for s in leaves] == ["motor 2", "motor 4"]
    assert all(s["stroke_limit_yield_reached"] and s["stroke_limit_fatigue_reached"]
               for s in leaves)
    assert all(r["safety_factor_fem"] > 1.0 for r in summary["pivot_fem"])  # below yield
    fitted = [r for r in summary["comparisons"] if r["quantity"].startswith("fitted workspace")]
    rows = [r for r in summary["comparisons"] if r not in fitted]
    assert len(rows) == 3 * 4 * 4
    # the workspace fitted on Table III is a calibration, shown apart and never as a headline;
    # it fits better than the placement by hand, and what it predicts is judged as usual
    assert all(r["kind"] == "calibrated" and not r["headline"]
               for r in fitted if r["source"] == "Table III")
    fit = summary["calibration"]
    assert fit["rms_misfit_after_pp"] < fit["rms_misfit_before_pp"]
    assert {r["verdict"] for r in fitted if r["source"] != "Table III"} <= {"agrees", "differs"}
    # angles and reductions are compared by their absolute difference; every spring C is read
    # against Table V's C (Table III's is in other units), never against Table III's
    table5 = {m: c for m, c in zip(load_toml("balancing_robot.toml")["table5_counterweight"]["motor"],
                                   load_toml("balancing_robot.toml")["table5_counterweight"]["C_Nm"])}
    for r in rows:
        assert np.isfinite(r["flexfem"])
        if r["unit"] in ("deg", "%"):
            assert r["difference_kind"] == "absolute"
        if r["quantity"].startswith("C, motor") and r["quantity"].endswith("spring"):
            motor = int(r["quantity"].split()[2].rstrip(","))
            assert r["reference"] == table5[motor] and r["source"] == "Table V"
    json.dumps(summary)           # JSON-able as returned (floats, lists, dicts)
    # the pivots: sized where K > 0, negative-stiffness preload where K < 0
    for p in summary["pivots"]:
        assert ("at_mid_range" in p) == (p["K_Nm_per_rad"] > 0)
