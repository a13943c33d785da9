"""Every command's --out is a folder: a file there is refused in one line before anything
is computed (a sweep, a convergence study, a front, a topology optimisation, an analysis)."""
from pathlib import Path

import pytest

from flexfem.studies.cli import main

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.mark.parametrize("command", [
    ["sweep", str(EXAMPLES / "dbma_hinge_sweep.toml")],
    ["converge", str(EXAMPLES / "bodies" / "guide.toml"), "--metric", "stiffness_stage_x"],
    ["front", str(EXAMPLES / "bodies" / "guide_front.toml")],
    ["topopt", str(EXAMPLES / "topopt" / "mbb.toml")],
    ["analyze", str(EXAMPLES / "bodies" / "guide.toml"), "--model", "beam"],
], ids=lambda c: c[0])
def test_an_out_that_is_a_file_is_refused_first(tmp_path, capsys, command):
    taken = tmp_path / "taken"
    taken.write_text("a file of the user's")
    assert main(command + ["--out", str(taken)]) == 2
    err = capsys.readouterr().err
    assert f"--out {taken}: is a file, not a folder" in err and err.count("\n") == 1
    assert taken.read_text() == "a file of the user's"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["taken"]
