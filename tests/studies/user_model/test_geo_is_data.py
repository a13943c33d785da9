"""A model file is data: a .geo that runs programs, writes files, reads outside its folder or
ends the process is refused, with the file, line and command named, through ``analyze``, a
local sweep and a Dask sweep (tests/studies/engine/test_dask_cluster.py); nothing runs and no file appears. ``--allow-code`` lifts it."""
import shutil
from pathlib import Path

import pytest
from flexfem.geometry.user_model import load_spec
from flexfem.geometry.user_model.geo_guard import CodeInGeometry, check_geo
from flexfem.studies.cli import main
from flexfem.studies.run import sweep

EXAMPLE = Path(__file__).parents[3] / "examples" / "parallel_guide"

# each payload would create MARKER (or read a file outside, or end the process)
PAYLOADS = {
    "System": 'System "touch {marker}";',
    "SystemCall": 'SystemCall "touch {marker}";',
    "NonBlockingSystemCall": 'NonBlockingSystemCall "touch {marker}";',
    "OnelabRun": 'OnelabRun("x", "touch {marker}");',
    "Printf >": 'Printf("owned") > "{marker}";',
    "Printf >>": 'Printf("owned") >> "{marker}";',
    "Printf > StrCat": 'Printf("owned") > StrCat("{marker}", "");',
    "Printf > StrPrefix": 'Printf("owned") > StrPrefix("{marker}.txt");',
    "Printf > Sprintf": 'Printf("owned") > Sprintf("{marker}");',
    "Printf > a variable": 'fn = "{marker}"; Printf("owned") > fn;',
    "Printf with arguments > Str": 'Printf("%g", 2) >> Str("{marker}");',
    "Print": 'Print "{marker}.png";',
    "Save": 'Save "{marker}.msh";',
    "CreateDir": 'CreateDir "{marker}.d";',
    "Exit": "Exit;",
    "Include outside": 'Include "/etc/hostname";',
    "Include computed": 'Include StrCat("/etc/", "hostname");',
    "Merge outside": 'Merge "../outside.msh";',
    "GetEnv": 'home = GetEnv("HOME");',
    "General option": "General.SaveOptions = 1;",
    "Solver option": 'Solver.Executable0 = "/bin/sh";',
}


def _model(tmp_path, payload: str) -> tuple[Path, Path]:
    """A copy of the parallel-guide example whose .geo ends with ``payload``; returns the
    model file and the marker path the payload would create."""
    folder = tmp_path / "model"
    shutil.copytree(EXAMPLE, folder)
    marker = tmp_path / "MARKER"
    geo = folder / "guide.geo"
    geo.write_text(geo.read_text() + "\n" + payload.format(marker=marker) + "\n")
    return folder / "guide.toml", marker


def _no_trace(marker: Path) -> bool:
    return not any(marker.parent.glob(marker.name + "*"))


@pytest.mark.parametrize("name", sorted(PAYLOADS))
def test_analyze_refuses_each_command(tmp_path, name, capsys):
    model, marker = _model(tmp_path, PAYLOADS[name])
    assert main(["analyze", str(model), "--json"]) == 2
    err = capsys.readouterr().err
    line = len((model.parent / "guide.geo").read_text().splitlines())
    assert f"guide.geo:{line}:" in err and "--allow-code" in err
    assert _no_trace(marker)


def test_refusal_names_the_command(tmp_path):
    model, _ = _model(tmp_path, PAYLOADS["SystemCall"])
    with pytest.raises(CodeInGeometry, match="'SystemCall' runs a shell command"):
        load_spec(model)


def test_commands_in_comments_and_strings_are_text(tmp_path):
    model, _ = _model(tmp_path, '// System "touch x";\n/* Exit; */\nPrintf("System Exit");')
    assert load_spec(model).groups  # parsed, nothing refused


def test_include_inside_the_folder_is_checked_in_turn(tmp_path):
    model, marker = _model(tmp_path, 'Include "extra.geo";')
    extra = model.parent / "extra.geo"
    extra.write_text("x_extra = 1;\n")
    assert load_spec(model).groups
    extra.write_text(f'x_extra = 1;\nSystem "touch {marker}";\n')
    with pytest.raises(CodeInGeometry, match=r"extra.geo:2: 'System'"):
        load_spec(model)
    assert _no_trace(marker)


def test_geometry_outside_the_folder_and_symlinks_out_are_refused(tmp_path):
    model, _ = _model(tmp_path, "")
    outside = tmp_path / "elsewhere.geo"
    shutil.copy(model.parent / "guide.geo", outside)
    text = model.read_text()
    model.write_text(text.replace('geometry = "guide.geo"', 'geometry = "../elsewhere.geo"'))
    with pytest.raises(ValueError, match="outside the model file's folder"):
        load_spec(model)
    assert load_spec(model, allow_code=True).geometry == outside.resolve()
    (model.parent / "link.geo").symlink_to(outside)
    model.write_text(text.replace('geometry = "guide.geo"', 'geometry = "link.geo"'))
    with pytest.raises(ValueError, match="outside the model file's folder"):
        load_spec(model)


def test_allow_code_lifts_the_check(tmp_path):
    model, marker = _model(tmp_path, f'SystemCall "touch {tmp_path / "MARKER"}";')
    load_spec(model, allow_code=True)
    assert marker.exists()  # the user said they trust it: gmsh ran it


def test_check_geo_passes_every_example():
    for geo in sorted((EXAMPLE.parent).glob("*/*.geo")):
        check_geo(geo)


def _study(tmp_path, model: Path) -> Path:
    study = model.parent / "study.toml"
    study.write_text('name = "probe"\nmechanism = { model = "guide.toml" }\n'
                     "[grid]\nL = [0.04, 0.05]\n")
    return study


@pytest.mark.parametrize("name", ["SystemCall", "Printf >"])
def test_local_sweep_runs_nothing(tmp_path, name):
    model, marker = _model(tmp_path, PAYLOADS[name])
    with pytest.raises(CodeInGeometry, match="--allow-code"):  # before any case runs
        sweep(_study(tmp_path, model), tmp_path / "out", workers=2, progress=False)
    assert _no_trace(marker) and not (tmp_path / "out" / "results.sqlite").exists()


def test_study_names_no_model_outside_its_folder(tmp_path):
    model, _ = _model(tmp_path, "")
    study = tmp_path / "study.toml"
    study.write_text('mechanism = { model = "model/guide.toml" }\n[grid]\nL = [0.04]\n')
    sweep(study, tmp_path / "ok", workers=1, progress=False)  # inside: fine
    inner = tmp_path / "sub" / "study.toml"
    inner.parent.mkdir()
    inner.write_text('mechanism = { model = "../model/guide.toml" }\n[grid]\nL = [0.04]\n')
    with pytest.raises(ValueError, match="outside the study's folder"):
        sweep(inner, tmp_path / "out", workers=1, progress=False)
