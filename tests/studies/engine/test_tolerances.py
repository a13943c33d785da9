"""Tolerance studies: a Monte Carlo over the declared scatter with SALib's Sobol indices,
checked on the Ishigami function's analytic indices; the study file's table validated."""
import math

import pytest
from flexfem.studies.engine.sweep import Study, design_points, study_from_dict
from flexfem.studies.engine.tolerance import Tolerance, Tolerances, tolerances_from_dict
from flexfem.studies.run import sweep
from ishigami import analytic_indices

pytest.importorskip("SALib", reason="SALib is a dependency of tolerance studies")

UNIFORM_PI = Tolerance(0.0, math.pi, "uniform")


def test_ishigami_indices_within_the_sampling_error(tmp_path):
    tolerances = Tolerances({k: UNIFORM_PI for k in ("x1", "x2", "x3")}, n=1024, seed=1)
    study = Study("ishigami:evaluate", name="ishigami", tolerances=tolerances)
    summary = sweep(study, tmp_path / "out", workers=1, progress=False, allow_code=True)
    assert summary["failed"] == 0 and summary["cases"] == 1024 * 5
    y = summary["tolerances"]["metrics"]["y"]
    first, total = analytic_indices()
    for name in ("x1", "x2", "x3"):
        assert abs(y["first_order"][name] - first[name]) <= 2 * y["first_order_conf"][name]
        assert abs(y["total_order"][name] - total[name]) <= 2 * y["total_order_conf"][name]
    assert y["dominant"] == "x1"  # x1 acts alone and with x3: the largest total index
    assert (tmp_path / "out" / "tolerances.json").is_file()
    # resumable: a second run computes nothing and gives the same indices
    again = sweep(study, tmp_path / "out", workers=1, progress=False, allow_code=True)
    assert again["computed"] == 0
    assert again["tolerances"]["metrics"]["y"]["total_order"] == y["total_order"]


def test_normal_tolerance_is_three_sigma():
    points = Tolerances({"t": Tolerance(0.5e-3, 10e-6)}, n=1024).points()
    values = [p["t"] for p in points]
    mean = sum(values) / len(values)
    std = math.sqrt(sum((v - mean) ** 2 for v in values) / (len(values) - 1))
    assert mean == pytest.approx(0.5e-3, rel=1e-4) and std == pytest.approx(10e-6 / 3, rel=0.05)


def test_the_study_file_table():
    study = study_from_dict({"mechanism": "toy", "base": {"length_m": 0.1}, "tolerances": {
        "n": 8, "parameters": {"thickness_tip_m": {"nominal": 0.002, "tolerance": 1e-5}}}})
    designs = design_points(study)
    assert len(designs) == 8 * 3 and all(d["length_m"] == 0.1 for d in designs)
    for bad, message in (({"parameters": {}}, "empty"),
                         ({"n": 100, "parameters": {"t": {"nominal": 1, "tolerance": 0.1}}},
                          "power of two"),
                         ({"parameters": {"t": {"nominal": 1, "tolerance": -1}}}, "> 0"),
                         ({"parameters": {"t": {"nominal": 1}}}, "nominal = X"),
                         ({"parameters": {"t": {"nominal": 1, "tolerance": 0.1,
                                                "distribution": "cauchy"}}}, "normal")):
        with pytest.raises(ValueError, match=message):
            tolerances_from_dict(bad)


def test_the_extremes_are_rechecked_by_the_confirming_model(tmp_path):
    """The toy screened on 4 elements, its extremes re-run on 400 ([tolerances.confirm]):
    the designs re-run are the lowest and highest of each metric, the confirming values are
    the fine model's at those designs (near the closed form), and a second call reuses the
    store."""
    from flexfem.studies.engine.sweep import run_study
    from flexfem.studies.engine.tolerance import confirm_extremes
    from flexfem.studies.toy.model import evaluate

    def run(s):
        return run_study(s, tmp_path / "store.sqlite", evaluate, workers=1, progress=False)

    study = study_from_dict({"mechanism": "toy", "options": {"n_elements": 4}, "tolerances": {
        "n": 8, "metrics": ["tip_deflection", "stiffness"], "confirm": {"n_elements": 400},
        "parameters": {"thickness_tip_m": {"nominal": 0.002, "tolerance": 2e-5},
                       "thickness_root_m": {"nominal": 0.002, "tolerance": 1e-5,
                                            "distribution": "uniform"}}}})
    result = confirm_extremes(study, run)
    assert result["options"] == {"n_elements": 400} and result["failed"] == 0
    assert result["computed"] == 8 * 4 + result["designs"]
    points = study.tolerances.points()
    coarse = [evaluate(p, n_elements=4) for p in points]
    for metric, row in result["metrics"].items():
        values = [c[metric] for c in coarse]
        assert row["low"]["screen"] == min(values) and row["high"]["screen"] == max(values)
        for end in ("low", "high"):
            fine = evaluate(row[end]["params"], n_elements=400)
            assert row[end]["confirm"] == pytest.approx(fine[metric], rel=1e-12)
            assert row[end]["rel_diff"] == pytest.approx(
                (fine[metric] - row[end]["screen"]) / abs(row[end]["screen"]))
        assert row["spread_ratio"] == pytest.approx(row["spread_confirm"] / row["spread_screen"])
    # 4 elements miss the closed form by ~3 %; 400 are within 1e-4 of it
    high = result["metrics"]["tip_deflection"]["high"]
    exact = evaluate(high["params"])["tip_deflection_analytical"]
    assert abs(high["rel_diff"]) > 0.01
    assert high["confirm"] == pytest.approx(exact, rel=1e-4)
    assert result["designs"] == 2  # the thinnest part is the softest: one design per end
    again = confirm_extremes(study, run)
    assert again["computed"] == 0 and again["metrics"] == result["metrics"]


def test_the_confirm_and_metrics_keys():
    table = {"parameters": {"t": {"nominal": 1, "tolerance": 0.1}}}
    tolerances = tolerances_from_dict({**table, "metrics": ["k"], "confirm": {"model": "x"}})
    assert tolerances.metrics == ("k",) and tolerances.confirm == {"model": "x"}
    for bad, message in (({"confirm": {}}, "confirming model"),
                         ({"confirm": "continuum"}, "confirming model"),
                         ({"metrics": "k"}, "list of metric names")):
        with pytest.raises(ValueError, match=message):
            tolerances_from_dict({**table, **bad})
    with pytest.raises(ValueError, match="no \\[tolerances.confirm\\]"):
        from flexfem.studies.engine.tolerance import confirm_extremes
        confirm_extremes(Study("toy", tolerances=tolerances_from_dict(table)), None)


def test_a_sweep_rechecks_the_extremes_it_declares(tmp_path):
    """flexfem sweep runs [tolerances.confirm] and writes it into tolerances.json."""
    import json

    from flexfem.studies.run import sweep

    study = study_from_dict({"mechanism": "toy", "options": {"n_elements": 4}, "tolerances": {
        "n": 8, "metrics": ["tip_deflection"], "confirm": {"n_elements": 400},
        "parameters": {"thickness_tip_m": {"nominal": 0.002, "tolerance": 2e-5}}}})
    out = sweep(study, tmp_path / "out", workers=1, progress=False)
    confirm = out["tolerances"]["confirm"]
    assert confirm["options"] == {"n_elements": 400} and confirm["designs"] == 2
    low = confirm["metrics"]["tip_deflection"]["low"]
    assert abs(low["rel_diff"]) > 0.01  # 4 elements against 400: the screen's error shows
    saved = json.loads((tmp_path / "out" / "tolerances.json").read_text())
    assert saved["confirm"]["metrics"] == json.loads(json.dumps(confirm["metrics"]))
