"""A user's own model from Python (flexfem.studies.user_model: load_model, analyze, Report):
the same analysis as analyze_model's dict (and so as ``flexfem analyze --json``) on three
example files by both models, the same one-line error for a misspelled override, and Report's
attributes, summary and files agreeing with its dict and, for the leaf-spring guide, with
the fixed-guided beam's stiffness."""
import json
import math
from pathlib import Path

import numpy as np
import pytest

from flexfem.fem.materials import material
from flexfem.geometry.user_model import load_spec
from flexfem.studies.cli import main
from flexfem.studies.user_model import Report, analyze, analyze_model, load_model
from flexfem.studies.user_model.summary import summarize

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
GUIDE = EXAMPLES / "bodies" / "guide.toml"
#: (file, fidelity, size factor): bodies and flexures by the beam model, a drawing by the
#: continuum (coarse: the comparison needs equal inputs, not a converged mesh)
CASES = [(GUIDE, "beam", None), (EXAMPLES / "bodies" / "bridge.toml", "beam", None),
         (EXAMPLES / "parallel_guide" / "guide.toml", "continuum", 3.0)]


def assert_same(a, b, path="") -> None:
    """Equal structure, keys in the same order, equal strings; numbers to 1e-9 relative (a
    sparse eigensolver's last digits vary from run to run)."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and list(a) == list(b), path
        for key in a:
            assert_same(a[key], b[key], f"{path}.{key}")
    elif isinstance(a, (list, tuple)):
        assert isinstance(b, (list, tuple)) and len(a) == len(b), path
        for k, (x, y) in enumerate(zip(a, b)):
            assert_same(x, y, f"{path}[{k}]")
    elif isinstance(a, float) and not isinstance(b, bool):
        assert b == pytest.approx(a, rel=1e-9, abs=1e-300), path
    else:
        assert a == b, path


@pytest.fixture(scope="module")
def guide():
    return analyze(load_model(GUIDE), fidelity="beam")


@pytest.mark.parametrize("path, fidelity, factor", CASES,
                         ids=[f"{c[0].parent.name}/{c[0].name}-{c[1]}" for c in CASES])
def test_load_model_and_analyze_give_analyze_models_dict(path, fidelity, factor):
    report = analyze(load_model(path), fidelity=fidelity, size_factor=factor)
    expected = analyze_model(load_spec(path), factor or 1.0, model=fidelity)
    if fidelity == "continuum":  # what flexfem analyze adds: how the mesh was chosen
        expected.update(size_factor=factor, mesh_choice="given")
    assert_same(expected, report.to_dict())
    assert report.fidelity == fidelity and report.model.path == Path(path)


def test_a_misspelled_override_is_the_clis_one_line_error(capsys):
    with pytest.raises(ValueError) as raised:
        load_model(GUIDE, set={"tt": 0.001})
    message = str(raised.value)
    assert "'tt'" in message and "did you mean 't'" in message and "\n" not in message
    assert main(["analyze", str(GUIDE), "--set", "tt=0.001", "--model", "beam"]) == 2
    assert capsys.readouterr().err.strip() == f"flexfem analyze: error: {message}"


def test_bad_choices_are_refused_in_one_line():
    spec = load_model(GUIDE)
    with pytest.raises(ValueError, match="fidelity = 'shell' must be one of"):
        analyze(spec, fidelity="shell")
    with pytest.raises(ValueError, match="the beam model has none"):
        analyze(spec, fidelity="beam", size_factor=2.0)


def test_the_reports_attributes_are_its_dicts_numbers(guide):
    data = guide.to_dict()
    assert isinstance(guide, Report) and guide.dim == 2 and guide.dofs == data["dofs"]
    assert guide.max_von_mises == data["max_von_mises"] > 0
    np.testing.assert_array_equal(guide.max_von_mises_location, data["max_von_mises_location"])
    for group, u in data["mean_displacement"].items():
        np.testing.assert_array_equal(guide.mean_displacement[group], u)
    np.testing.assert_array_equal(guide.reactions["ground"], data["reactions"]["ground"])
    assert guide.stiffness == data["stiffness"] and guide.yield_strength > 0
    assert guide.stroke_limits["stroke_limit_yield"] == data["stroke_limit_yield"] > 0
    assert guide.buckling is None and guide.solved_model is not None
    data["dofs"] = -1  # to_dict is a copy
    assert guide.to_dict()["dofs"] == guide.dofs


def test_the_guides_stiffness_is_the_fixed_guided_leaves(guide):
    """Two fixed-guided leaves: k = 2 * 12 E I / L^3 (I = b t^3 / 12); the beam model adds the
    roots' compliance and shear: a root lengthens a leaf by the order of half its thickness,
    (1 + t / L)^-3 ~ -7 % at L/t = 40, so within 10 % and below."""
    spec = guide.model
    E, L, t, b = material("structural_steel").E, 0.04, 0.001, spec.thickness
    k = 24 * E * b * t**3 / 12 / L**3
    assert guide.stiffness["stage"]["x"] == pytest.approx(k, rel=0.10)
    assert guide.stiffness["stage"]["x"] < k  # compliance added, never removed


def test_summary_and_files_are_the_clis(guide, tmp_path):
    assert guide.summary() == summarize(guide.to_dict())
    mm = guide.summary(units="mm")
    assert mm == summarize({**guide.to_dict(), "display_units": "mm"}) != guide.summary()
    x = guide.stiffness["stage"]["x"]
    assert f"stiffness of 'stage' along x: {x / 1e3:.4g} N/mm" in mm
    with pytest.raises(ValueError, match="units = 'inch'"):
        guide.summary(units="inch")
    files = guide.write(tmp_path / "out")
    assert Path(files[-1]).name == "index.html" and all(Path(f).is_file() for f in files)
    written = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert written == {**guide.to_dict(), "files": files}
    assert math.isfinite(written["max_von_mises"])
