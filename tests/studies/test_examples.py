"""The example studies and front files in examples/ load, the designs they declare are valid
designs, and running one gives the numbers theory and the paper lead to."""
from pathlib import Path
import tomllib

import pytest
from flexfem.studies.dbma.analysis import params_from_dict
from flexfem.studies.eightbar.analysis import params_from_dict as eightbar_params
from flexfem.studies.engine.sweep import design_points, load_study

TOP = sorted((Path(__file__).resolve().parents[2] / "examples").glob("*.toml"))
FRONTS = [p for p in TOP if "objectives" in tomllib.loads(p.read_text())]
EXAMPLES = [p for p in TOP if p not in FRONTS]
DESIGN_CHECKS = {"dbma": params_from_dict, "eightbar": eightbar_params}
CHECKED = 40  # designs checked a study at most, spread over it (an eight-bar check: ~0.35 s)


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_example_study_declares_valid_designs(path):
    study = load_study(path)
    designs = design_points(study)
    assert len(designs) > 1
    check = DESIGN_CHECKS[study.mechanism]
    for design in designs[::max(1, len(designs) // CHECKED)]:
        check(design)  # raises ValueError on an unknown or out-of-bounds parameter


@pytest.mark.parametrize("path", FRONTS, ids=lambda p: p.name)
def test_example_front_declares_valid_bounds(path):
    """Both corners of the search box and every reference are valid designs."""
    from flexfem.studies.engine.front import front_from_dict
    from flexfem.studies.engine.sweep import read_study_file

    front = front_from_dict(read_study_file(path))
    check = DESIGN_CHECKS[front.mechanism]
    for corner in (0, 1):
        check({**front.base, **{k: v[corner] for k, v in front.variables.items()}})
    for _, params in front.references:
        check({**front.base, **params})


@pytest.mark.slow
def test_the_dbma_sweep_runs_and_follows_the_paper(tmp_path):
    from flexfem.geometry.dbma.params import paper_design
    from flexfem.studies.dbma.analysis import analyze_dbma
    from flexfem.studies.run import sweep
    path = next(p for p in EXAMPLES if p.name == "dbma_hinge_sweep.toml")
    result = sweep(path, tmp_path / "out", workers=1, progress=False)
    assert result["failed"] == 0 and result["cases"] == 16
    rows = result["results"]
    paper = next(r for r in rows if (r["b"], r["h"]) == (0.6e-3, 2.6e-3))
    # through the engine, the paper's design gives what analyze gives for the same model
    direct = analyze_dbma(paper_design(), dim=2, size_factor=2.0, force=100.0)
    assert paper["R_fem_per_side"] == pytest.approx(direct["R_fem_per_side"], rel=1e-6)  # solve rtol
    # Fig. 13a: thicker hinges amplify less, at either offset
    for h in (1.2e-3, 2.6e-3):
        line = sorted((r["b"], r["R_fem_per_side"]) for r in rows if r["h"] == h and r["b"] in
                      (0.4e-3, 0.6e-3, 0.8e-3, 1.0e-3))
        assert [R for _, R in line] == sorted((R for _, R in line), reverse=True)
    assert all(r["force_N"] == 100.0 for r in rows)


@pytest.mark.slow
def test_the_eightbar_tolerance_study_names_the_tolerance_that_matters(tmp_path):
    """The example with a smaller Monte Carlo (n = 16: 80 designs): every design runs, and the
    thin flexures' width drives the drive stiffness (k_x ~ sum of w^3 over the flexures).
    Its [tolerances.confirm] (5 designs by the continuum's large-deflection path, ~30 s) is
    left out here: nothing below reads it; the same table's confirm is checked against the
    beam model in tests/studies/report/test_report.py (the report's study is the example's:
    test_the_report_runs_the_example_tolerance_study), and flexfem sweep's confirm step in
    tests/studies/engine/test_tolerances.py."""
    from dataclasses import replace

    from flexfem.studies.run import sweep
    path = next(p for p in EXAMPLES if p.name == "eightbar_tolerances.toml")
    study = load_study(path)
    assert study.tolerances.confirm is not None  # what is left out below
    study = replace(study, tolerances=replace(study.tolerances, n=16, confirm=None))
    result = sweep(study, tmp_path / "out", workers=2, progress=False)
    assert result["failed"] == 0 and result["cases"] == 16 * 5
    metrics = result["tolerances"]["metrics"]
    assert {"k_x", "f1_hz", "fem_deviation_pct"} <= set(metrics)
    assert metrics["k_x"]["dominant"] in ("flexure_width", "base_flexure_width")
    assert metrics["k_x"]["total_order"]["root_fillet_radius"] < 0.2


def _example(name: str) -> dict:
    return tomllib.loads(next(p for p in TOP if p.name == name).read_text())


@pytest.mark.parametrize("module, name", [("eightbar.report", "eightbar_tolerances.toml"),
                                          ("dbma.report", "dbma_tolerances.toml")])
def test_the_report_runs_the_example_tolerance_study(module, name):
    """The report's tolerance study is the example file's (its sample size aside)."""
    import importlib

    table = importlib.import_module(f"flexfem.studies.{module}").TOLERANCES
    assert {k: v for k, v in table.items() if k != "name"} == \
        {k: v for k, v in _example(name).items() if k != "name"}


def test_the_report_searches_the_example_front():
    from flexfem.studies.dbma.optimize_output import FRONT
    assert FRONT == _example("dbma_front.toml")


@pytest.mark.slow
def test_the_dbma_tolerance_study_names_the_hinge_tolerances_that_matter(tmp_path):
    """The example with a smaller Monte Carlo (n = 16: 80 designs by the beam model): R
    scatters with the hinge offset h (R ~ l / h for a bow amplifier), the working mode with
    the hinge thickness b (its stiffness ~ b^3); the length l matters little for either; the
    continuum re-checks the extremes of both."""
    from dataclasses import replace

    from flexfem.studies.engine.sweep import run_study
    from flexfem.studies.engine.tolerance import confirm_extremes
    from flexfem.studies.mechanisms import get_evaluator
    from flexfem.studies.run import sweep
    study = load_study(next(p for p in EXAMPLES if p.name == "dbma_tolerances.toml"))
    study = replace(study, tolerances=replace(study.tolerances, n=16))
    result = sweep(study, tmp_path / "out", workers=1, progress=False)
    assert result["failed"] == 0 and result["cases"] == 16 * 5
    metrics = result["tolerances"]["metrics"]
    assert set(metrics) == {"R_fem_per_side", "fn_working"}
    assert metrics["R_fem_per_side"]["dominant"] == "h"
    assert metrics["fn_working"]["dominant"] == "b"
    assert all(m["total_order"]["l"] < 0.2 for m in metrics.values())
    assert 0 < 3 * metrics["R_fem_per_side"]["std"] / metrics["R_fem_per_side"]["mean"] < 0.01
    store = tmp_path / "out" / "results.sqlite"
    checked = confirm_extremes(study, lambda s: run_study(s, store, get_evaluator("dbma"),
                                                          workers=1, progress=False))
    assert checked["failed"] == 0 and 2 <= checked["designs"] <= 4
    for row in checked["metrics"].values():
        for end in ("low", "high"):  # the beam model within 3 % of the 2-D FEM
            assert abs(row[end]["rel_diff"]) < 0.03
        assert row["spread_confirm"] > 0  # the continuum orders the extremes alike
