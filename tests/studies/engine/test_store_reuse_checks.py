"""A stored row is reused only if it passes the checks of a fresh result and has every metric
the study asks for; any other is computed again, with a warning line that says why. The
rows are edited in the SQLite store as a user (or a damaged disk) would edit them."""
import json
import math
from pathlib import Path
import shutil
import sqlite3

import pytest

from flexfem.studies.engine import sweep as engine
from flexfem.studies.engine.front import Front, _cached
from flexfem.studies.engine.store import ResultStore
from flexfem.studies.engine.validate import declare, result_problems
from flexfem.studies.run import run_study, study_from_dict
from flexfem.studies.toy.model import evaluate as toy

ROOT = Path(__file__).resolve().parents[3]


def _edit(store: Path, edit) -> str:
    """Apply ``edit(metrics) -> metrics`` to the first stored row; its key."""
    with sqlite3.connect(store) as db:
        key, text = db.execute("SELECT key, metrics FROM cases ORDER BY key").fetchone()
        db.execute("UPDATE cases SET metrics = ? WHERE key = ?", (edit(json.loads(text)), key))
    return key


def _toy_study(**tables):
    return study_from_dict({"mechanism": "toy", "name": "s",
                            "grid": {"length_m": [0.05, 0.1, 0.15]}, **tables})


def _metrics(result) -> dict:
    return {c.key: c.metrics for c in result.cases}


@pytest.mark.parametrize("edit, why", [
    (lambda m: "{}", "it has no metrics"),
    (lambda m: json.dumps({**m, "stiffness": -m["stiffness"]}), "stiffness = -"),
    (lambda m: json.dumps({**m, "tip_deflection": None}), "tip_deflection = nan is not finite"),
])
def test_an_edited_row_is_computed_again_and_said(tmp_path, capsys, edit, why):
    store = tmp_path / "results.sqlite"
    first = run_study(_toy_study(), store, workers=1, progress=False)
    assert first.computed == 3
    key = _edit(store, edit)
    again = run_study(_toy_study(), store, workers=1, progress=False)
    assert (again.computed, again.reused) == (1, 2)
    assert _metrics(again) == _metrics(first)  # the fresh values, not the edited row
    warning = [line for line in capsys.readouterr().err.splitlines() if "warning" in line]
    assert len(warning) == 1 and key[:12] in warning[0] and why in warning[0], warning
    assert run_study(_toy_study(), store, workers=1, progress=False).computed == 0


def test_a_row_without_a_metric_the_study_plots_is_computed_again(tmp_path, capsys):
    store = tmp_path / "results.sqlite"
    run_study(_toy_study(), store, workers=1, progress=False)
    _edit(store, lambda m: json.dumps({k: v for k, v in m.items() if k != "root_stress"}))
    assert run_study(_toy_study(), store, workers=1, progress=False).computed == 0  # not asked
    plotted = _toy_study(plots=[{"metric": "root_stress", "parameter": "length_m"}])
    assert run_study(plotted, store, workers=1, progress=False).computed == 1
    assert "metric 'root_stress' is missing" in capsys.readouterr().err


@declare(positive=("stiffness",))
def negative_stiffness(params: dict, size_factor: float = 1.0) -> dict:
    """The toy with its stiffness negated: what the result checks must refuse."""
    out = toy(params, size_factor)
    return {**out, "stiffness": -out["stiffness"]}


def test_a_fresh_result_failing_the_checks_is_a_failed_case(tmp_path):
    study = engine.Study("negative", grid={"length_m": [0.1]})
    result = engine.run_study(study, tmp_path / "r.sqlite", negative_stiffness, workers=1,
                              progress=False)
    (case,) = result.cases
    assert case.status == "failed" and "result check: stiffness = -" in case.error
    assert result_problems({"stiffness": 2.0}, negative_stiffness) == []
    assert result_problems({"stiffness": math.inf}, negative_stiffness) == [
        "stiffness = inf is not finite"]


def test_an_undeclared_evaluate_keeps_its_signs(tmp_path):
    """A mechanism that declares nothing positive (a plugin's balanced, negative-stiffness
    design) keeps its negative values: only finiteness and presence are checked."""
    assert result_problems({"stiffness": -1.0}, lambda p: p) == []


def test_the_front_recomputes_an_edited_evaluation(tmp_path, capsys):
    front = Front("toy", {"length_m": (0.05, 0.15)}, (("stiffness", "min"),
                                                      ("root_stress", "max")))
    with ResultStore(tmp_path / "e.sqlite") as store:
        run = _cached(toy, front, store, {})
        fresh = run({"length_m": 0.1})
    key = _edit(tmp_path / "e.sqlite", lambda m: json.dumps({**m, "stiffness": -1.0}))
    with ResultStore(tmp_path / "e.sqlite") as store:
        assert _cached(toy, front, store, {})({"length_m": 0.1}) == fresh
    assert key[:12] in capsys.readouterr().err


def test_a_model_file_row_edited_in_the_store_is_recomputed(tmp_path, capsys):
    """The audit's case: a bodies-and-flexures sweep (beam model), one row's metrics set to
    '{}', another's stiffness negated; the rerun computes both again, the third is reused."""
    shutil.copy(ROOT / "examples" / "bodies" / "guide.toml", tmp_path / "guide.toml")
    data = {"mechanism": {"model": "guide.toml"}, "name": "g", "options": {"model": "beam"},
            "grid": {"t": [0.0009, 0.001, 0.0011]}}
    store = tmp_path / "results.sqlite"
    first = run_study(study_from_dict(data, base_dir=tmp_path), store, workers=1,
                      progress=False)
    assert first.computed == 3 and all(c.ok for c in first.cases)
    with sqlite3.connect(store) as db:
        (a, _), (b, text) = db.execute("SELECT key, metrics FROM cases ORDER BY key").fetchall()[:2]
        metrics = json.loads(text)
        metrics["stiffness_stage_x"] = -metrics["stiffness_stage_x"]
        db.execute("UPDATE cases SET metrics = '{}' WHERE key = ?", (a,))
        db.execute("UPDATE cases SET metrics = ? WHERE key = ?", (json.dumps(metrics), b))
    again = run_study(study_from_dict(data, base_dir=tmp_path), store, workers=1,
                      progress=False)
    assert (again.computed, again.reused) == (2, 1)
    assert _metrics(again) == _metrics(first)
    err = capsys.readouterr().err
    assert f"{a[:12]} is computed again: it has no metrics" in err
    assert f"{b[:12]} is computed again: stiffness_stage_x = -" in err
