"""Values with units in a model file ("40 mm", "210 GPa", "7850 kg/m^3"): the file reads as
its SI twin, to round-off, through analyze; a unit of the wrong dimension or one pint does not
know is refused with one line naming the file, the table and the key."""
import json
from pathlib import Path
import re

import pytest
from flexfem.geometry.user_model import load_spec
from flexfem.studies.cli import main

GUIDE = Path(__file__).parents[3] / "examples" / "bodies" / "guide.toml"
SI_TO_UNITS = [("L = 0.04 ", 'L = "40 mm" '), ("t = 0.001 ", 't = "1 mm" '),
               ('name = "structural_steel"', 'E = "200 GPa"\nnu = 0.3\nrho = "7.85 g/cm^3"'),
               ("thickness = 0.01 ", 'thickness = "10 mm" '),
               ('"L + 0.008"', '"L + 8 mm"'), ("force = [1.0, 0.0]", 'force = ["1 N", 0.0]')]


def _with_units(tmp_path, replacements=SI_TO_UNITS) -> Path:
    text = GUIDE.read_text()
    for old, new in replacements:
        assert old in text, old
        text = text.replace(old, new)
    path = tmp_path / "guide_units.toml"
    path.write_text(text)
    return path


def _si_twin(tmp_path) -> Path:
    text = GUIDE.read_text().replace('name = "structural_steel"', "E = 200e9\nnu = 0.3\nrho = 7850")
    path = tmp_path / "guide_si.toml"
    path.write_text(text)
    return path


def test_a_file_with_units_reads_as_its_si_twin(tmp_path, capsys):
    units = load_spec(_with_units(tmp_path))
    si = load_spec(_si_twin(tmp_path))
    assert units.parameters == pytest.approx(si.parameters, rel=1e-12)
    assert units.material.E == si.material.E and units.material.rho == pytest.approx(7850)
    results = []
    for path in (_with_units(tmp_path), _si_twin(tmp_path)):
        assert main(["analyze", str(path), "--model", "beam", "--json"]) == 0
        results.append(json.loads(capsys.readouterr().out))
    assert results[0]["stiffness"]["stage"]["x"] == pytest.approx(
        results[1]["stiffness"]["stage"]["x"], rel=1e-9)


@pytest.mark.parametrize("replacement, message", [
    (('thickness = "t"', 'thickness = "5 deg"'), r"\[\[flexure\]\] 1 thickness: '5 deg' is an "
                                                  r"angle, but this value is a length"),
    (("t = 0.001 ", 't = "1 mmm" '), r"\[parameters\] t: 1 'mmm' is not a unit pint knows"),
    (('name = "structural_steel"', 'E = "200 mm"\nnu = 0.3\nrho = 7850'),
     r"\[material\] E: '200 mm' is a length, but this value is a pressure"),
])
def test_a_wrong_unit_is_refused_naming_the_key(tmp_path, capsys, replacement, message):
    path = _with_units(tmp_path, [replacement])
    assert main(["analyze", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "guide_units.toml" in err
    assert re.search(message, err), err


def test_a_set_with_a_unit(tmp_path, capsys):
    assert main(["analyze", str(GUIDE), "--model", "beam", "--set", "t=1.2 mm", "--json"]) == 0
    with_unit = json.loads(capsys.readouterr().out)["stiffness"]["stage"]["x"]
    assert main(["analyze", str(GUIDE), "--model", "beam", "--set", "t=0.0012", "--json"]) == 0
    assert with_unit == pytest.approx(json.loads(capsys.readouterr().out)["stiffness"]["stage"]["x"],
                                      rel=1e-12)


@pytest.mark.parametrize("text, expected", [
    ("L + 5.39e-12", "L + 5.39e-12"),  # an exponent is not a unit 'e'
    ("1e-3 * L", "1e-3 * L"), ("2 * t", "2 * t"),  # a parameter is not a unit (t: tonne)
    ("L + 2 mm", "L + (0.002)"), ("3.5mm", 0.0035), (".5 mm", 0.0005), ("2e-3 m", 0.002)])
def test_quantities_are_found_where_they_are_and_nowhere_else(text, expected):
    from flexfem.geometry.user_model.quantities import with_si_units

    raw = {"parameters": {"L": 0.04, "t": 0.001}, "flexure": [{"thickness": text}]}
    assert with_si_units(raw, "f.toml")["flexure"][0]["thickness"] == expected


def test_the_summary_in_a_designers_units(capsys):
    assert main(["analyze", str(GUIDE), "--model", "beam", "--json", "--units", "mm"]) == 0
    si = json.loads(capsys.readouterr().out)
    assert "display_units" not in si  # --json stays SI
    assert main(["analyze", str(GUIDE), "--model", "beam", "--units", "mm"]) == 0
    text = capsys.readouterr().out
    k = si["stiffness"]["stage"]["x"]
    assert f"stiffness of 'stage' along x: {k / 1e3:.4g} N/mm" in text
    ux = si["mean_displacement"]["stage"][0]
    assert f"mean displacement of 'stage': ({ux * 1e3:.4g}, " in text and ") mm" in text
