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
