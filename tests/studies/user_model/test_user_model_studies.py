"""A model-file mechanism in the study engine: a sweep named by `mechanism = { model = ... }`,
a convergence study, and stored cases that follow the model and geometry files."""
import json
from pathlib import Path
import shutil

import pytest

from flexfem.studies.cli import main
from flexfem.studies.mechanisms import check_mechanism, model_mechanism

GUIDE = Path(__file__).resolve().parents[3] / "examples" / "parallel_guide"


@pytest.fixture
def guide(tmp_path) -> Path:
    """A copy of the parallel-guide example, and a study file beside it sweeping L."""
    for name in ("guide.toml", "guide.geo"):
        shutil.copy(GUIDE / name, tmp_path / name)
    (tmp_path / "study.toml").write_text(
        'mechanism = { model = "guide.toml" }\nname = "lengths"\n'
        "[grid]\nL = [0.04, 0.05]\n")
    return tmp_path


def _sweep(folder: Path, capsys) -> dict:
    assert main(["sweep", str(folder / "study.toml"), "--out", str(folder / "out"),
                 "--workers", "1", "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_a_study_sweeps_a_model_file_and_follows_beam_theory(guide, capsys):
    result = _sweep(guide, capsys)
    assert result["cases"] == 2 and result["failed"] == 0
    k = {row["L"]: row["stiffness_stage_x"] for row in result["results"]}
    # fixed-guided leaves: k ~ 1 / L^3, up to root and shear terms of order t/L (~2 %)
    assert k[0.04] / k[0.05] == pytest.approx((0.05 / 0.04) ** 3, rel=0.03)


def test_stored_cases_follow_the_model_and_geometry_files(guide, capsys):
    assert _sweep(guide, capsys)["computed"] == 2
    assert _sweep(guide, capsys)["reused"] == 2
    geo = guide / "guide.geo"
    geo.write_text(geo.read_text() + "\n// edited\n")
    again = _sweep(guide, capsys)
    assert again["computed"] == 2 and again["reused"] == 0


def test_converge_takes_a_model_file(guide, capsys):
    assert main(["converge", str(guide / "guide.toml"), "--metric", "stiffness_stage_x",
                 "--levels", "3", "--start", "2", "--out", str(guide / "out"), "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["values"][0] > result["values"][-1] > 0  # P2 stiffens on coarse meshes
    assert result["extrapolated"] == pytest.approx(result["values"][-1], rel=0.01)


def test_a_bare_or_missing_model_is_refused_by_name(tmp_path):
    with pytest.raises(ValueError, match="needs its model file"):
        check_mechanism("model")
    with pytest.raises(ValueError, match="no such model file"):
        model_mechanism("nowhere.toml", tmp_path)


def test_a_study_sweeps_the_declared_beam_model(guide, capsys):
    """options = { model = "beam" }: the same metric names from the model file's [[beam]]
    declarations, which follow L; a case of the beam model is another case than the
    continuum's."""
    study = guide / "study.toml"
    study.write_text(study.read_text().replace('name = "lengths"\n',
                                               'name = "lengths"\n[options]\nmodel = "beam"\n'))
    result = _sweep(guide, capsys)
    assert result["cases"] == 2 and result["failed"] == 0
    rows = {row["L"]: row for row in result["results"]}
    assert all(row["dofs"] < 500 for row in rows.values())  # beams, not the mesh
    k = {L: row["stiffness_stage_x"] for L, row in rows.items()}
    assert k[0.04] / k[0.05] == pytest.approx((0.05 / 0.04) ** 3, rel=0.03)
    study.write_text(study.read_text().replace('model = "beam"', 'model = "shell"'))
    assert main(["sweep", str(study), "--out", str(guide / "out2"), "--workers", "1"]) != 0
    assert "options.model = 'shell' must be one of ['continuum', 'beam']" in capsys.readouterr().err
    assert not (guide / "out2" / "results.sqlite").exists()  # refused before anything ran
