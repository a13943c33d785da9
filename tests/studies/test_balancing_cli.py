"""`flexfem balance` and the reproduction section of the balancing study."""
import json

import numpy as np
import pytest
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
    assert "K_Nm_per_rad" in text and "spring " not in text and text.count("torsion") == 4


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


def test_reproduce_quick_writes_tables_and_figure(tmp_path):
    summary = reproduce(tmp_path, quick=True)
    for name in summary["tables"] + summary["figures"]:
        assert (tmp_path / name).stat().st_size > 0
    assert {"balancing_fig10.png", "balancing_pivot_fem.png"} <= set(summary["figures"])
    assert all(r["safety_factor_fem"] > 1.0 for r in summary["pivot_fem"])  # below yield
    rows = summary["comparisons"]
    assert len(rows) == 3 * 4 * 4
    for r in rows:
        assert set(r) == {"quantity", "flexfem", "published", "rel_diff", "note"}
        assert np.isfinite(r["flexfem"])
    json.dumps(summary)           # JSON-able as returned (floats, lists, dicts)
    # the pivots: sized where K > 0, negative-stiffness preload where K < 0
    for p in summary["pivots"]:
        assert ("at_mid_range" in p) == (p["K_Nm_per_rad"] > 0)
