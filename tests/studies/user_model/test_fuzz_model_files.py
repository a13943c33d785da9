"""Every numeric field of a model file at the extreme but finite values 1e-300 and 1e300
(--set, and the force vector by editing the file), through `flexfem analyze`: the run either
succeeds with every number of its output finite, or is refused with one line (exit 2) -- never
a traceback, a NaN or inf printed, or a run that does not end (the mesh budget and the sanity
checks refuse before meshing). Sized to run in seconds."""
import json
import math
import shutil
from pathlib import Path

import pytest
from flexfem.studies.cli import main

EXAMPLES = Path(__file__).parents[3] / "examples"
COMMON = ["material.E", "material.nu", "material.rho", "material.yield_strength",
          "material.ultimate_strength", "material.fatigue_strength", "material.fatigue_cycles",
          "section.thickness", "mesh.size", "mesh.order", "analysis.modes", "analysis.steps",
          "analysis.buckling", "analysis.safety_factor", "analysis.mean_stroke"]
FILES = {
    "bodies": (EXAMPLES / "bodies" / "guide.toml",
               ["L", "t", "d", "beam_model.root_extension", "beam_model.elements"] + COMMON),
    "geo": (EXAMPLES / "parallel_guide" / "guide.toml",
            ["L", "t", "d", "hb", "hs", "m", "lc_leaf", "lc_block"] + COMMON),
}
EXTREMES = ("1e-300", "1e300")


def _all_finite(value) -> bool:
    if isinstance(value, dict):
        return all(_all_finite(v) for v in value.values())
    if isinstance(value, list):
        return all(_all_finite(v) for v in value)
    return not isinstance(value, float) or math.isfinite(value)


def _check(capsys, argv) -> None:
    code = main(["analyze", *argv, "--json", "--max-dofs", "200000"])
    out, err = capsys.readouterr()
    assert "Traceback" not in err, argv
    if code == 0:
        assert _all_finite(json.loads(out)), argv
    else:
        assert code == 2 and err.count("\n") == 1 and "error:" in err, (argv, err)


@pytest.mark.parametrize("kind", sorted(FILES))
def test_every_field_at_the_extremes(capsys, kind):
    path, fields = FILES[kind]
    models = ("continuum", "beam") if kind == "bodies" else ("continuum",)
    for field in fields:
        for value in EXTREMES:
            for model in models:
                _check(capsys, [str(path), "--set", f"{field}={value}", "--model", model])


@pytest.mark.parametrize("force", ["[1e300, 0.0]", "[1e-300, 0.0]", "[0.0, -1e300]"])
def test_the_force_at_the_extremes(tmp_path, capsys, force):
    for path in (FILES["bodies"][0], FILES["geo"][0]):
        folder = tmp_path / path.parent.name  # a copy: the examples folder stays as it is
        shutil.copytree(path.parent, folder)
        copy = folder / f"_fuzz_{path.stem}.toml"
        copy.write_text(path.read_text().replace("force = [1.0, 0.0]", f"force = {force}"))
        for model in ("continuum", "beam"):
            _check(capsys, [str(copy), "--model", model])
