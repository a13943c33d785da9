"""``flexfem topopt``: the example problem files through the command, bad input as one
error line with exit 2, and a run resumed after an interruption ends where an uninterrupted
one does."""
import json
from pathlib import Path

import numpy as np
import pytest
from problems import interrupt_at, inverter

from flexfem.studies.cli import main
from flexfem.topopt import load_problem, optimize, problem_from_dict
from flexfem.topopt.state import load_state

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples" / "topopt"


def _run(capsys, *argv) -> tuple[int, str, str]:
    code = main(["topopt", *map(str, argv)])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def test_mbb_example_through_the_command(capsys, tmp_path):
    code, out, _ = _run(capsys, EXAMPLES / "mbb.toml", "--json", "--out", tmp_path)
    assert code == 0
    result = json.loads(out)
    assert result["converged"] and 200 < result["objective"] < 206
    assert result["volume_fraction"] == pytest.approx(0.5, abs=1e-3)
    assert {p.name for p in tmp_path.iterdir()} == {"state.npz", "result.json", "density.csv",
                                                     "density.png"}


@pytest.mark.slow
def test_inverter_example_through_the_command(capsys, tmp_path):
    code, out, _ = _run(capsys, EXAMPLES / "inverter.toml", "--json", "--out", tmp_path)
    result = json.loads(out)
    assert code == 0 and result["u_out"] < -0.5 < 0 < result["u_in"]
    code, out, _ = _run(capsys, EXAMPLES / "inverter.toml", "--out", tmp_path)
    assert code == 0 and "u_out" in out  # the rerun resumes the finished state: no iteration
    assert load_state(tmp_path)["iteration"] == result["iterations"]


@pytest.mark.slow
def test_a_shape_table_writes_the_outline_and_a_model_file(capsys, tmp_path):
    code, out, _ = _run(capsys, EXAMPLES / "inverter_mm.toml", "--json", "--out", tmp_path)
    result = json.loads(out)
    assert code == 0 and result["converged"] and result["u_out"] < 0
    assert {"outline.dxf", "outline.step", "design.geo", "design.toml"} <= {
        p.name for p in tmp_path.iterdir()}
    shape, tol = result["shape"], result["shape"]["tolerance"]
    assert shape["parts"] == 1 and shape["islands"] == []
    assert abs(shape["body_fitted"]["output"] - result["u_out"]) <= tol["tolerance"]
    assert abs(shape["body_fitted"]["output"] / result["u_out"] - 1) < 0.1


def test_a_resumed_run_ends_where_an_uninterrupted_one_does(tmp_path):
    problem = inverter(16, 8, iterations=30)
    whole = optimize(problem)
    interrupt_at(problem, tmp_path, 7)
    assert int(load_state(tmp_path)["iteration"]) == 7
    resumed = optimize(problem, out_dir=tmp_path)
    assert resumed.iterations == whole.iterations
    assert np.allclose(resumed.density, whole.density, atol=1e-10)
    assert [p.name for p in tmp_path.iterdir()] == ["state.npz"]  # no temporary file left


def test_state_of_another_problem_is_refused(tmp_path):
    optimize(inverter(8, 4, iterations=2), out_dir=tmp_path)
    with pytest.raises(ValueError, match="another problem"):
        optimize(inverter(8, 4, iterations=2, filter_kind="none"), out_dir=tmp_path)


BAD = [
    ("[domain]\nnelx = 0\nnely = 4\n[objective]\nkind = 'compliance'\n", "nelx"),
    ("[domain]\nnelx = 4\nnely = 4\ncolour = 1\n", "colour"),
    ("[domain]\nnelx = 4\nnely = 4\n[filter]\nkind = 'gauss'\n[objective]\nkind = 'compliance'\n"
     "[[support]]\nwhere = {edge = 'left'}\n[[load]]\nwhere = {point = [4, 4]}\n"
     "force = [0, 1]\n", "filter.kind"),
    ("[domain]\nnelx = 4\nnely = 4\n[objective]\nkind = 'compliance'\n"
     "[[support]]\nwhere = {edge = 'middle'}\n[[load]]\nwhere = {point = [0, 0]}\n"
     "force = [0, 1]\n", "where.edge"),
    ("[domain]\nnelx = 4\nnely = 4\n[objective]\nkind = 'displacement'\nspring = 'out'\n"
     "[[support]]\nwhere = {edge = 'left'}\n[[load]]\nwhere = {point = [4, 4]}\n"
     "force = [0, 1]\n[optimizer]\nkind = 'mma'\n", "spring"),
    ("[domain]\nnelx = 4\nnely = 4\n[objective]\nkind = 'compliance'\n"
     "[[support]]\nwhere = {edge = 'left'}\n[[load]]\nwhere = {point = [4, 4]}\n"
     "force = [0, 1]\n[[constraint]]\nkind = 'volume'\nmax = 1.5\n", "volume max"),
    ("[domain]\nnelx = 4\nnely = 4\n[objective]\nkind = 'compliance'\n"
     "[[support]]\nwhere = {edge = 'left'}\n[[load]]\nwhere = {point = [4, 4]}\n"
     "force = [0, 0]\n", "load case 1: every [[load]] force is zero"),
    ("[domain]\nnelx = 4\nnely = 4\n[objective]\nkind = 'compliance'\n"
     "[[support]]\nwhere = {edge = 'left'}\n[[load]]\nwhere = {point = [40, 4]}\n"
     "force = [0, 1]\n[[constraint]]\nkind = 'volume'\nmax = 0.5\n",
     "load[0].where.point = [40.0, 4.0] lies outside the design domain"),
    ("[domain\n", "not valid TOML"),
]


@pytest.mark.parametrize("text, key", BAD, ids=[k for _, k in BAD])
def test_bad_input_is_one_error_naming_the_key(capsys, tmp_path, text, key):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    code, out, err = _run(capsys, path, "--out", tmp_path / "out")
    assert code == 2 and out == ""
    assert err.startswith("flexfem topopt: error:") and key in err and err.count("\n") == 1
    assert not (tmp_path / "out").exists()


def test_the_examples_are_the_python_problems():
    mbb = load_problem(EXAMPLES / "mbb.toml")
    assert mbb.grid.nelx == 60 and mbb.volume_limit == 0.5 and mbb.optimizer.kind == "oc"
    with pytest.raises(ValueError, match="oc"):
        problem_from_dict({"domain": {"nelx": 4, "nely": 4},
                           "objective": {"kind": "displacement", "spring": "s"},
                           "spring": [{"name": "s", "where": {"point": [0, 0]}, "dof": "x",
                                       "stiffness": 1.0}],
                           "support": [{"where": {"edge": "left"}}],
                           "load": [{"where": {"point": [4, 4]}, "force": [0, 1]}]})
