"""Extreme but finite inputs to a model file give a clear refusal (exit 2, one line naming
the problem), never NaN, inf, a silently coarse mesh or a meshing run that cannot end: element
sizes gmsh cannot honour, meshes above the budget, overflowing loads, unphysical materials and
sections, lengths given in mm, and a stiffness where a support moves."""
import json
from pathlib import Path
import shutil

import pytest
from flexfem.studies.cli import main

EXAMPLES = Path(__file__).parents[3] / "examples"
GEO_GUIDE = EXAMPLES / "parallel_guide" / "guide.toml"
BODIES_GUIDE = EXAMPLES / "bodies" / "guide.toml"


def _refused(capsys, *argv) -> str:
    assert main(["analyze", *map(str, argv)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    return err


@pytest.mark.parametrize("size", ["1e-12", "1e-300", "0"])
def test_a_mesh_size_gmsh_cannot_honour_is_refused(capsys, size):
    err = _refused(capsys, GEO_GUIDE, "--set", f"mesh.size={size}")
    assert "must be a finite number > 0" in err or "cannot be meshed" in err


def test_a_vanishing_dimension_of_a_geo_is_refused_before_meshing(capsys):
    err = _refused(capsys, GEO_GUIDE, "--set", "t=1e-300")
    assert "element size of 5e-301 m" in err  # lc_leaf = t / 2


def test_a_mesh_above_the_budget_is_refused_in_seconds(capsys):
    err = _refused(capsys, GEO_GUIDE, "--set", "mesh.size=3e-5", "--max-dofs", "1000000")
    assert "above the budget of 1,000,000 DOFs" in err
    err = _refused(capsys, BODIES_GUIDE, "--set", "t=1e-5", "--max-dofs", "100000")
    assert "above the budget" in err


@pytest.mark.parametrize("path", [GEO_GUIDE, BODIES_GUIDE], ids=["geo", "bodies"])
@pytest.mark.parametrize("model", ["continuum", "beam"])
def test_an_overflowing_load_is_refused_not_printed_as_nan(tmp_path, capsys, path, model):
    text = path.read_text().replace("force = [1.0, 0.0]", "force = [1e300, 1e300]")
    folder = tmp_path / path.parent.name  # a copy: the examples folder stays as it is
    shutil.copytree(path.parent, folder)
    copy = folder / f"_overflow_{path.stem}.toml"
    copy.write_text(text)
    err = _refused(capsys, copy, "--model", model)
    assert "beyond what double precision can solve" in err


@pytest.mark.parametrize("setting, message", [
    ("material.E=1e300", "outside what solids have"),
    ("material.E=1e-300", "outside what solids have"),
    ("material.rho=1e300", "outside what solids have"),
    ("section.thickness=1e300", "lengths are in m"),
    ("section.thickness=1e-300", "lengths are in m"),
])
def test_unphysical_material_and_section_values_are_refused(capsys, setting, message):
    for path in (GEO_GUIDE, BODIES_GUIDE):
        assert message in _refused(capsys, path, "--set", setting)


def test_lengths_in_mm_are_caught(capsys):
    err = _refused(capsys, BODIES_GUIDE, "--set", "L=40", "--set", "d=20", "--set", "t=1")
    assert "lengths are in m" in err


def test_no_stiffness_where_a_support_moves(tmp_path, capsys):
    text = BODIES_GUIDE.read_text().replace('group = "ground"        # a body',
                                            'group = "ground"\nx = 0.001\ny = 0.0  # a body')
    path = tmp_path / "guide.toml"
    path.write_text(text)
    assert main(["analyze", str(path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["stiffness"] == {}
    assert out["mean_displacement"]["ground"][0] == pytest.approx(0.001, rel=1e-6)


def test_a_very_flexible_stage_gets_its_modes(capsys):
    """L = -1 hangs the stage a metre below the ground on 1 m leaves: modes of ~1 Hz, far
    below the element stiffness. The modal shift is near enough for Lanczos to separate them
    (it once took ~1e4 steps: a run that seemed to hang)."""
    assert main(["analyze", str(BODIES_GUIDE), "--set", "L=-1", "--json"]) == 0
    f = json.loads(capsys.readouterr().out)["frequencies_hz"]
    assert 0.5 < f[0] < 3.0 and f == sorted(f)


def test_a_drawing_in_mm_is_caught_before_meshing(capsys):
    err = _refused(capsys, GEO_GUIDE, "--set", "L=40")
    assert "40.01 m across; lengths are in m" in err


@pytest.mark.parametrize("setting, message", [("L=-1", "crosses itself"),
                                              ("d=1e-300", "coincide"),
                                              ("hb=1e-300", "coincide")])
def test_a_drawing_turned_inside_out_is_refused_before_meshing(capsys, setting, message):
    """A negative or vanishing dimension of a .geo makes its outline cross itself or two of
    its points coincide: gmsh would mesh it for minutes before failing."""
    assert message in _refused(capsys, GEO_GUIDE, "--set", setting)


@pytest.mark.parametrize("argv", [
    ["converge", "toy", "--metric", "tip_deflection", "--start", "1e-300"],
    ["converge", "toy", "--metric", "tip_deflection", "--ratio", "1e300"],
    ["converge", "toy", "--metric", "tip_deflection", "--params", '{"length_m": 1e300}'],
    ["optimize", "dbma", "--stroke", "1e300", "--quick"],
])
def test_extreme_command_line_values_are_one_line_refusals(capsys, argv):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
