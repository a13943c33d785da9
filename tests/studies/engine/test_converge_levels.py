"""A convergence study checks every level's mesh estimate against the budget before it meshes
the first (a refusal in seconds naming the first level that does not fit), keeps each level in
a store as it completes, and a rerun reuses what was computed ("level N reused")."""
import importlib
import io
import json
import math
import time
from pathlib import Path

import pytest
from flexfem.fem.budget import BudgetError, Estimated, check_budget, estimate_only
from flexfem.geometry.user_model import load_spec
from flexfem.studies.cli import main
from flexfem.studies.engine.convergence import converge, default_levels

draw = importlib.import_module("flexfem.geometry.mechanism.draw")  # the module, not draw()

EXAMPLES = Path(__file__).parents[3] / "examples"
BODIES = EXAMPLES / "bodies" / "guide.toml"
GEO = EXAMPLES / "parallel_guide" / "guide.toml"


def test_check_budget_estimates_only_inside_the_context():
    estimate = {"elements": 10, "nodes": 20, "dofs": 40}
    check_budget(estimate, 2, max_dofs=100)  # fits: nothing happens
    with pytest.raises(BudgetError):
        check_budget(estimate, 2, max_dofs=30)
    with estimate_only(), pytest.raises(Estimated) as caught:
        check_budget(estimate, 2, max_dofs=30)
    assert caught.value.estimate == estimate and caught.value.limit == 30
    assert not caught.value.fits
    with estimate_only():  # a check of max_dofs alone (an empty estimate) is not an estimate
        check_budget({"elements": 0, "nodes": 0, "dofs": 0}, 2, max_dofs=30)
    check_budget(estimate, 2, max_dofs=100)  # the context is left


def _first_misfit(path: Path, factors, budget: int) -> int:
    spec = load_spec(path)
    for i, s in enumerate(factors):
        dofs = draw.estimate_mesh(spec.mechanism, spec.dim, s, spec.mesh.size,
                                  spec.mesh.order)["dofs"]
        if dofs > budget:
            return i
    raise AssertionError("every level fits")


def test_a_level_that_does_not_fit_is_refused_before_any_is_meshed(tmp_path, capsys,
                                                                   monkeypatch):
    """Bodies and flexures: their estimate is computed without gmsh, so meshing anything is
    an error here; the refusal names the first level above the (fixed) budget."""
    budget, levels = 40_000, 8
    first = _first_misfit(BODIES, [1 / 2**i for i in range(levels)], budget)
    assert 1 <= first < levels - 1  # a real probe: levels before it fit, those after do not

    def no_meshing(*args, **kwargs):
        raise AssertionError("a level was meshed before every level was checked")

    monkeypatch.setattr(draw, "gmsh_session", no_meshing)
    start = time.perf_counter()
    code = main(["converge", str(BODIES), "--metric", "stiffness_stage_x", "--levels",
                 str(levels), "--start", "1", "--max-dofs", str(budget), "--out",
                 str(tmp_path / "out")])
    assert time.perf_counter() - start < 20
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and "Traceback" not in err, err
    assert f"level {first + 1}/{levels} " in err and f"{budget:,} DOFs" in err, err
    assert "before any level was meshed" in err
    assert not (tmp_path / "out" / "levels.sqlite").exists()


def test_a_geo_model_is_refused_in_seconds_too(tmp_path, capsys):
    """The parallel guide's .geo: --levels 12 ran for minutes before its level 6 was refused;
    now the estimates (gmsh loads the .geo, meshes nothing) refuse it at once."""
    start = time.perf_counter()
    code = main(["converge", str(GEO), "--metric", "stiffness_stage_x", "--levels", "12",
                 "--max-dofs", "200000", "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert code == 2 and "does not fit" in err and "200,000 DOFs" in err, err
    assert time.perf_counter() - start < 30
    assert not (tmp_path / "out" / "levels.sqlite").exists()


def _counting(fail_at=None):
    """An evaluate of values 1 + h^2 (h = size_factor) that records its calls and raises at
    level ``fail_at`` (as a run killed there would stop)."""
    calls = []

    def evaluate(params, size_factor=1.0):
        calls.append(size_factor)
        if fail_at is not None and math.isclose(size_factor, 1 / 2**fail_at):
            raise RuntimeError("the machine went away")
        return {"value": 1 + size_factor**2, "h": size_factor, "dofs": int(4 / size_factor)}
    return evaluate, calls


def test_levels_computed_before_a_failure_are_kept_and_reused(tmp_path):
    store = tmp_path / "levels.sqlite"
    evaluate, calls = _counting(fail_at=3)
    with pytest.raises(RuntimeError):
        converge(evaluate, "value", default_levels(5), store=store, mechanism="probe")
    assert calls == [1, 0.5, 0.25, 0.125]
    evaluate, calls = _counting()
    stream = io.StringIO()
    result = converge(evaluate, "value", default_levels(5), store=store, mechanism="probe",
                      progress=stream)
    assert calls == [0.125, 0.0625]  # only what was not stored
    assert result.reused == [0, 1, 2]
    assert result.values == [1 + (1 / 2**i) ** 2 for i in range(5)]
    assert "level 1/5 reused" in stream.getvalue() and "level 3/5 reused" in stream.getvalue()
    assert result.extrapolated == pytest.approx(1.0, rel=1e-12)
    # another design is another level: nothing reused
    evaluate, calls = _counting()
    other = converge(evaluate, "value", default_levels(3), params={"L": 2.0}, store=store,
                     mechanism="probe")
    assert other.reused == [] and len(calls) == 3


def test_the_cli_keeps_its_levels_in_the_output_folder(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    args = ["converge", "toy", "--metric", "tip_deflection", "--json"]
    assert main([*args, "--levels", "3"]) == 0
    first = json.loads(capsys.readouterr().out)
    assert first["reused"] == [] and Path(first["store"]).is_file()
    assert Path(first["store"]).parent == Path("convergence_toy")  # the default folder
    assert main([*args, "--levels", "4"]) == 0
    again = json.loads(capsys.readouterr().out)
    assert again["reused"] == [0, 1, 2] and again["values"][:3] == first["values"]
    assert main(["converge", "toy", "--metric", "tip_deflection", "--levels", "4"]) == 0
    assert "level(s) 0, 1, 2, 3 reused" in capsys.readouterr().out


def test_max_dofs_is_refused_for_a_mechanism_without_a_mesh(tmp_path, capsys):
    assert main(["converge", "toy", "--metric", "tip_deflection", "--max-dofs", "1000",
                 "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "max_dofs" in err and "toy" in err and err.count("\n") == 1


def test_a_misspelled_params_name_is_refused_before_any_level(tmp_path, capsys):
    from flexfem.studies.cli import main

    assert main(["converge", "toy", "--metric", "tip_deflection_m", "--params",
                 '{"lenght_m": 0.1}', "--out", str(tmp_path / "c")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "params.lenght_m names no parameter" in err \
        and "did you mean 'length_m'?" in err
    assert not (tmp_path / "c" / "levels.sqlite").exists()
