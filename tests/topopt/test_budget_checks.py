"""Requests that cannot fit are refused up front, in one line naming the file and the key: a
topology optimisation grid above the memory budget, a model file's modes, buckling factors,
harmonic points or modal basis above the caps of fem/budget.py."""
import time
from pathlib import Path

import pytest
from flexfem.fem.budget import MAX_FREQUENCY_POINTS, MAX_MODES, BudgetError, check_grid
from flexfem.geometry.user_model import load_spec
from flexfem.studies.cli import main

EXAMPLES = Path(__file__).parents[2] / "examples"


def _one_line(capsys, argv) -> str:
    start = time.perf_counter()
    code = main([str(a) for a in argv])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and "Traceback" not in err, err
    assert time.perf_counter() - start < 20
    return err


def test_a_topopt_grid_above_the_budget_is_refused_before_anything_is_allocated(tmp_path,
                                                                               capsys):
    """20000 x 20000 elements: 800 million DOFs, terabytes on any machine (it was a 36-line
    MemoryError traceback)."""
    text = (EXAMPLES / "topopt" / "mbb.toml").read_text()
    path = tmp_path / "huge.toml"
    path.write_text(text.replace("nelx = 60", "nelx = 20000").replace("nely = 20",
                                                                      "nely = 20000"))
    err = _one_line(capsys, ["topopt", path, "--out", tmp_path / "out"])
    assert "huge.toml" in err and "domain.nelx" in err and "800,080,002 DOFs" in err, err
    assert not (tmp_path / "out").exists()


def test_check_grid_passes_the_examples_grid_and_refuses_a_huge_one():
    check_grid(60, 20, "domain")
    with pytest.raises(BudgetError, match="domain: 100,000 x 100,000 elements"):
        check_grid(100_000, 100_000, "domain")


def _model(tmp_path, analysis: str) -> Path:
    folder = EXAMPLES / "parallel_guide"
    for name in ("guide.geo",):
        (tmp_path / name).write_text((folder / name).read_text())
    path = tmp_path / "guide.toml"
    path.write_text((folder / "guide.toml").read_text().replace("modes = 3", analysis))
    return path


@pytest.mark.parametrize("analysis, key, cap", [
    ("modes = 4000", "[analysis] modes = 4,000", MAX_MODES),
    ("buckling = 1000", "[analysis] buckling = 1,000", MAX_MODES),
    ('harmonic = { group = "stage", component = "x", f_max = 1e3, points = 100000000 }',
     "harmonic points = 100,000,000", MAX_FREQUENCY_POINTS),
    ('harmonic = { group = "stage", component = "x", f_max = 1e3, n_modes = 5000 }',
     "harmonic n_modes = 5,000", MAX_MODES),
])
def test_a_model_file_asking_too_much_is_refused_naming_the_key(tmp_path, capsys, analysis,
                                                                key, cap):
    path = _model(tmp_path, analysis)
    err = _one_line(capsys, ["analyze", path])
    assert "guide.toml line" in err and key in err and f"{cap:,}" in err, err


def test_requests_at_the_caps_are_accepted(tmp_path):
    path = _model(tmp_path, f"modes = {MAX_MODES}\nharmonic = {{ group = \"stage\", "
                            f"component = \"x\", f_max = 1e3, points = {MAX_FREQUENCY_POINTS} }}")
    spec = load_spec(path)
    assert spec.analysis.modes == MAX_MODES
    assert spec.analysis.harmonic.points == MAX_FREQUENCY_POINTS
