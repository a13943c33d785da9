"""A [material] of E and nu only (no rho) serves every static analysis, on every model, with
the numbers of the library's steel of the same E and nu; an [analysis] that needs masses
(modes, harmonic) is refused when the file is read, naming rho and the [material] line."""
import math
from pathlib import Path

import pytest

from flexfem.fem import Material
from flexfem.geometry.user_model import load_spec
from flexfem.studies.cli import main
from flexfem.studies.user_model.analysis import analyze_model

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
STEEL = 'name = "structural_steel"'
NO_RHO = "E = 200e9\nnu = 0.3"  # the library steel's E and nu


def _copy(tmp_path, example: str, modes: bool = False) -> Path:
    """A copy of ``example`` (with its geometry files) whose [material] has no rho, and no
    [analysis] modes unless ``modes``."""
    source = EXAMPLES / example
    for sibling in source.parent.glob("*.geo"):
        (tmp_path / sibling.name).write_text(sibling.read_text())
    text = source.read_text().replace(STEEL, NO_RHO)
    if not modes:
        text = text.replace("modes = 3", "")
    path = tmp_path / source.name
    path.write_text(text)
    return path


@pytest.mark.parametrize("example, model, dim", [("bodies/guide.toml", "continuum", None),
                                                 ("bodies/guide.toml", "beam", None),
                                                 ("bodies/guide.toml", "beam", 3),
                                                 ("parallel_guide/guide.toml", "beam", None),
                                                 ("spatial/guide.toml", "beam", None)])
def test_a_static_analysis_needs_no_density(tmp_path, example, model, dim):
    path = _copy(tmp_path, example)
    bare = analyze_model(load_spec(path, dim=dim), model=model)
    steel = analyze_model(load_spec(EXAMPLES / example, {"analysis.modes": 1}, dim=dim)
                          if "modes = 3" not in (EXAMPLES / example).read_text() else
                          load_spec(EXAMPLES / example, dim=dim), model=model)
    (group, by_axis), = steel["stiffness"].items()
    assert bare["stiffness"][group] == pytest.approx(by_axis, rel=1e-9)
    assert bare["max_von_mises"] == pytest.approx(steel["max_von_mises"], rel=1e-9)
    assert "frequencies_hz" not in bare


@pytest.mark.parametrize("example", ["bodies/guide.toml", "parallel_guide/guide.toml",
                                     "spatial/guide.toml"])
def test_modes_without_density_are_refused_when_read(tmp_path, example, capsys):
    path = _copy(tmp_path, example, modes=True)
    line = path.read_text().splitlines().index("[material]") + 1
    with pytest.raises(ValueError, match=rf"line {line}: \[analysis\] modes needs the "
                                         r"material's density: add rho \(kg/m\^3\)"):
        load_spec(path)
    assert main(["analyze", str(_copy(tmp_path, example)), "--set", "analysis.modes=2"]) == 2
    assert "add rho (kg/m^3) to [material]" in capsys.readouterr().err


def test_a_material_without_density_says_so_where_a_mass_is_asked():
    bare = Material("bare", 200e9, 0.3, None)
    assert math.isnan(bare.density_or_nan)
    with pytest.raises(ValueError, match="material 'bare' has no density: masses and "
                                         r"frequencies need rho \(kg/m\^3\)"):
        bare.density
    with pytest.raises(ValueError, match="rho"):
        Material("bad", 200e9, 0.3, -1.0)
