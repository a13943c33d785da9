"""A study file cannot widen its own rights: what the command line owns (allow_code, the model
file's path, a mechanism named by path and digest, any path as a value) is refused in a study,
front or tolerance file with one line naming the file and the key (exit 2), before any case or
worker runs; a model a study names is resolved inside the study's folder and its digest is
verified. ``--allow-code`` on the command line still lifts the rights checks."""
import os
import shutil
from pathlib import Path

import pytest
from flexfem.studies import mechanisms
from flexfem.studies.cli import main
from flexfem.studies.engine.sweep import Study
from flexfem.studies.run import load_study, run_front, run_study, sweep

EXAMPLE = Path(__file__).parents[3] / "examples" / "parallel_guide"


@pytest.fixture(autouse=True)
def _no_cluster(monkeypatch):
    monkeypatch.delenv("FLEXFEM_SCHEDULER", raising=False)


@pytest.fixture
def folders(tmp_path):
    """study/: the guide and an "evil" copy whose .geo would create MARKER; elsewhere/: a
    guide outside the study's folder, one parameter changed."""
    study, elsewhere = tmp_path / "study", tmp_path / "elsewhere"
    for folder in (study, elsewhere):
        folder.mkdir()
        for name in ("guide.toml", "guide.geo"):
            shutil.copy(EXAMPLE / name, folder / name)
    marker = tmp_path / "MARKER"
    geo = (study / "guide.geo").read_text()
    (study / "evil.geo").write_text(geo + f'\nSystemCall "touch {marker}";\n')
    (study / "evil.toml").write_text((study / "guide.toml").read_text()
                                     .replace('geometry = "guide.geo"', 'geometry = "evil.geo"'))
    other = elsewhere / "guide.toml"
    other.write_text(other.read_text().replace("L = 0.04", "L = 0.05"))
    return study, elsewhere, marker


def _cli(capsys, *args) -> tuple[int, str]:
    code = main([str(a) for a in args])
    captured = capsys.readouterr()
    return code, captured.err


def _refused(capsys, study: Path, out: Path, *extra, key: str) -> str:
    code, err = _cli(capsys, "sweep", study, "--out", out, *extra)
    lines = err.strip().splitlines()
    assert code == 2, err
    assert len(lines) == 1 and "Traceback" not in err, err
    assert str(study) in lines[0] and key in lines[0], err
    assert not out.exists()  # refused before anything is stored
    return lines[0]


@pytest.mark.parametrize("workers", [["--workers", "1"], ["--workers", "2"],
                                     ["--scheduler", "tcp://127.0.0.1:9"]])
def test_allow_code_in_options_is_refused_and_runs_nothing(folders, capsys, workers):
    """The audit's probe: [options] allow_code = true beside a .geo that runs a command. The
    refusal comes before the executor (an unreachable scheduler is never contacted)."""
    study, _, marker = folders
    path = study / "s.toml"
    path.write_text('mechanism = { model = "evil.toml" }\n[options]\nallow_code = true\n')
    line = _refused(capsys, path, study.parent / "out", *workers, key="options.allow_code")
    assert "--allow-code" in line
    assert not marker.exists()


def test_the_model_file_is_not_an_option(folders, capsys):
    study, elsewhere, _ = folders
    path = study / "s.toml"
    path.write_text('mechanism = { model = "guide.toml" }\n[options]\n'
                    f'file = "{elsewhere / "guide.toml"}"\n')
    _refused(capsys, path, study.parent / "out", "--workers", "1", key="options.file")


def test_a_path_as_any_value_is_refused(folders, capsys):
    study, elsewhere, _ = folders
    path = study / "s.toml"
    path.write_text('mechanism = { model = "guide.toml" }\n[options]\n'
                    f'"material.name" = "{elsewhere / "steel.toml"}"\n')
    _refused(capsys, path, study.parent / "out", "--workers", "1", key="options.material.name")


def test_a_mechanism_by_path_and_digest_is_refused(folders, capsys):
    study, elsewhere, _ = folders
    path = study / "s.toml"
    path.write_text(f'mechanism = "model:{elsewhere / "guide.toml"}@000000000000"\n')
    _refused(capsys, path, study.parent / "out", "--workers", "1", key="mechanism")
    # --allow-code lifts the folder rule, never the digest: a wrong one names the right one
    line = _refused(capsys, path, study.parent / "out", "--workers", "1", "--allow-code",
                    key="mechanism")
    right = mechanisms.model_mechanism(elsewhere / "guide.toml")
    assert "digest" in line and right.rpartition("@")[2] in line
    path.write_text(f'mechanism = "{right}"\n')
    summary = sweep(path, study.parent / "out", workers=1, progress=False, allow_code=True)
    assert summary["cases"] == 1 and summary["failed"] == 0 and summary["mechanism"] == right


@pytest.mark.parametrize("how", ["absolute", "dotdot", "symlink"])
def test_a_model_outside_the_study_folder_is_refused(folders, capsys, how):
    study, elsewhere, _ = folders
    target = elsewhere / "guide.toml"
    if how == "symlink":
        os.symlink(target, study / "link.toml")
        name = "link.toml"
    else:
        name = str(target) if how == "absolute" else "../elsewhere/guide.toml"
    path = study / "s.toml"
    path.write_text(f'mechanism = {{ model = "{name}" }}\n')
    line = _refused(capsys, path, study.parent / "out", "--workers", "1", key="mechanism.model")
    assert ("absolute" if how == "absolute" else "outside the study's folder") in line
    # what the user's --allow-code lifts: the outside file is analysed, under its own name
    study_ = load_study(path, allow_code=True)
    assert study_.mechanism.startswith(f"model:{target.resolve()}@")


def test_a_wrong_digest_is_refused_in_python_too(folders):
    study, _, _ = folders
    name = mechanisms.model_mechanism(study / "guide.toml")
    evaluate = mechanisms.get_evaluator(name)
    (study / "guide.geo").write_text((study / "guide.geo").read_text() + "\n// edited\n")
    with pytest.raises(ValueError, match="the file changed"):
        mechanisms.get_evaluator(name)
    assert evaluate.keywords["file"] == str((study / "guide.toml").resolve())


def test_tolerances_confirm_cannot_allow_code(folders, capsys):
    study, _, marker = folders
    path = study / "t.toml"
    path.write_text('mechanism = { model = "evil.toml" }\n[tolerances]\nn = 4\n'
                    'metrics = ["stiffness_stage_x"]\n[tolerances.parameters]\n'
                    't = { nominal = 0.001, tolerance = 1e-5 }\n'
                    '[tolerances.confirm]\nallow_code = true\n')
    _refused(capsys, path, study.parent / "out", "--workers", "1",
             key="tolerances.confirm.allow_code")
    assert not marker.exists()


FRONT = '''mechanism = {mechanism}
[options]
{option}
[variables]
t = [0.0008, 0.0012]
[[objectives]]
metric = "stiffness_stage_x"
goal = "min"
[[objectives]]
metric = "max_von_mises"
goal = "min"
[search]
population = 4
generations = 1
'''


@pytest.mark.parametrize("mechanism, option, key", [
    ('{ model = "evil.toml" }', "allow_code = true", "options.allow_code"),
    ('{ model = "guide.toml" }', 'file = "ELSEWHERE"', "options.file"),
    ('"model:ELSEWHERE@000000000000"', "", "mechanism"),
    ('{ model = "../elsewhere/guide.toml" }', "", "mechanism.model"),
])
def test_a_front_file_cannot_widen_its_rights(folders, capsys, mechanism, option, key):
    pytest.importorskip("pymoo")
    study, elsewhere, marker = folders
    path = study / "f.toml"
    other = str(elsewhere / "guide.toml")
    path.write_text(FRONT.format(mechanism=mechanism.replace("ELSEWHERE", other),
                                 option=option.replace("ELSEWHERE", other)))
    code, err = _cli(capsys, "front", path, "--out", study.parent / "out")
    assert code == 2 and len(err.strip().splitlines()) == 1, err
    assert str(path) in err and key in err, err
    assert not (study.parent / "out").exists() and not marker.exists()
    with pytest.raises(ValueError, match=key.replace(".", r"\.")):
        run_front(path, study.parent / "out")


def test_python_studies_cannot_set_the_bound_options(folders):
    """A Study built in Python is refused by run_study; and the model's evaluate itself, the
    last guard on every worker, refuses a call that sets what its caller bound."""
    study, _, marker = folders
    name = mechanisms.model_mechanism(study / "evil.toml")
    with pytest.raises(ValueError, match="options.allow_code"):
        run_study(Study(name, options={"allow_code": True}), study / "r.sqlite", workers=1)
    evaluate = mechanisms.get_evaluator(name)
    for option in ("allow_code", "file"):
        with pytest.raises(ValueError, match="set by the command line"):
            evaluate({}, **{option: True if option == "allow_code" else str(study / "x.toml")})
    assert not marker.exists()


def test_allow_code_on_the_command_line_still_lifts_the_option_check(folders):
    study, elsewhere, _ = folders
    path = study / "s.toml"
    path.write_text('mechanism = { model = "guide.toml" }\n[options]\n'
                    f'file = "{elsewhere / "guide.toml"}"\n')
    with pytest.raises(ValueError, match="options.file"):
        load_study(path)
    assert load_study(path, allow_code=True).options["file"] == str(elsewhere / "guide.toml")
