"""A [material] of E, nu and rho only (no strengths) solves with every model: the stiffness,
stresses and modes are those of the library's steel of the same E, nu and rho, and what needs
a strength (the stroke to yield, the fatigue stroke, the share of yield) is reported as not
available with the strength it needs: null with its reason in --json, never inf or nan."""
import json
import math
from pathlib import Path

import pytest

from flexfem.geometry.user_model import load_spec
from flexfem.studies.cli import main
from flexfem.studies.user_model.analysis import analyze_model, evaluate

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
STEEL = 'name = "structural_steel"'
BARE = "E = 200e9\nnu = 0.3\nrho = 7850"  # the library steel's E, nu and rho, no strengths


def _bare_copy(tmp_path, example: str, extra: str = "") -> Path:
    """A copy of ``example`` (and its geometry file) with the bare [material]."""
    source = EXAMPLES / example
    text = source.read_text()
    assert STEEL in text
    for sibling in source.parent.glob("*.geo"):
        (tmp_path / sibling.name).write_text(sibling.read_text())
    path = tmp_path / source.name
    path.write_text(text.replace(STEEL, BARE + extra))
    return path


def _no_non_finite(value):
    if isinstance(value, float):
        assert math.isfinite(value)
    elif isinstance(value, dict):
        for v in value.values():
            _no_non_finite(v)
    elif isinstance(value, list):
        for v in value:
            _no_non_finite(v)


def _check_against_steel(bare: dict, steel: dict):
    assert bare["yield_strength"] is None and steel["yield_strength"] == 250e6
    (group, by_axis), = steel["stiffness"].items()  # the same E, nu, rho: the same solve
    assert bare["stiffness"][group] == pytest.approx(by_axis, rel=1e-9)
    assert bare["max_von_mises"] == pytest.approx(steel["max_von_mises"], rel=1e-9)
    assert bare["frequencies_hz"] == pytest.approx(steel["frequencies_hz"], rel=1e-9)
    assert bare["stroke_limit_yield"] is None and steel["stroke_limit_yield"] > 0
    assert bare["stroke_limit_fatigue"] is None and steel["stroke_limit_fatigue"] > 0
    assert bare["not_available"] == {
        "yield_strength": "not given in [material]",
        "stroke_limit_yield": "needs yield_strength",
        "stroke_limit_fatigue": "needs fatigue_strength and fatigue_cycles"}
    assert "not_available" not in steel
    _no_non_finite(bare)


@pytest.mark.parametrize("example, model", [("bodies/guide.toml", "continuum"),
                                            ("bodies/guide.toml", "beam"),
                                            ("parallel_guide/guide.toml", "continuum"),
                                            ("parallel_guide/guide.toml", "beam")])
def test_every_model_solves_a_material_without_strengths(tmp_path, example, model):
    bare = analyze_model(load_spec(_bare_copy(tmp_path, example)), model=model)
    steel = analyze_model(load_spec(EXAMPLES / example), model=model)
    _check_against_steel(bare, steel)


def test_the_spatial_beam_model_too(tmp_path):
    """--dim 3 of bodies and flexures, by the beam model (the lifted model's modes)."""
    path = _bare_copy(tmp_path, "bodies/guide.toml")
    bare = analyze_model(load_spec(path, dim=3), model="beam")
    steel = analyze_model(load_spec(EXAMPLES / "bodies/guide.toml", dim=3), model="beam")
    assert bare["dim"] == 3
    _check_against_steel(bare, steel)


def test_the_cli_says_what_is_not_available(tmp_path, capsys):
    path = _bare_copy(tmp_path, "bodies/guide.toml")
    assert main(["analyze", str(path), "--model", "beam"]) == 0
    text = capsys.readouterr().out
    assert "(% of yield not available: needs yield_strength)" in text
    assert "stroke of 'stage' to yield: not available: needs yield_strength" in text
    assert ("fatigue-limited stroke amplitude of 'stage': not available: needs "
            "fatigue_strength and fatigue_cycles") in text
    assert "inf" not in text and "nan" not in text
    assert main(["analyze", str(path), "--model", "beam", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)  # strict JSON: null, no Infinity
    assert out["yield_strength"] is None and out["stroke_limit_yield"] is None
    assert out["not_available"]["stroke_limit_yield"] == "needs yield_strength"


def test_a_study_metric_that_needs_a_strength_is_absent_with_its_reason(tmp_path):
    path = _bare_copy(tmp_path, "bodies/guide.toml")
    metrics = evaluate({"L": 0.05}, file=str(path), model="beam")
    assert "stroke_limit_yield" not in metrics and "stroke_limit_fatigue" not in metrics
    assert metrics["not_available"] == ("stroke_limit_yield: needs yield_strength; "
                                        "stroke_limit_fatigue: needs fatigue_strength and "
                                        "fatigue_cycles")
    steel = evaluate({"L": 0.05}, file=str(EXAMPLES / "bodies/guide.toml"), model="beam")
    assert metrics["stiffness_stage_x"] == pytest.approx(steel["stiffness_stage_x"], rel=1e-9)
    assert "not_available" not in steel and steel["stroke_limit_yield"] > 0


def test_a_sweep_of_a_material_without_strengths_stores_the_reason(tmp_path, capsys):
    path = _bare_copy(tmp_path, "bodies/guide.toml")
    study = tmp_path / "study.toml"
    study.write_text(f'mechanism = {{ model = "{path.name}" }}\nname = "lengths"\n'
                     '[options]\nmodel = "beam"\n[grid]\nL = [0.04, 0.05]\n')
    assert main(["sweep", str(study), "--out", str(tmp_path / "out"), "--workers", "1",
                 "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["failed"] == 0
    for row in result["results"]:
        assert row["stiffness_stage_x"] > 0 and "stroke_limit_yield" not in row
        assert "stroke_limit_yield: needs yield_strength" in row["not_available"]


def test_fatigue_with_a_mean_stroke_needs_the_static_strength(tmp_path):
    """Fatigue data alone give the fully reversed amplitude; a mean stroke's Goodman line needs
    the ultimate strength (and a compressive face the yield strength): not available without
    them, where the line would otherwise be drawn to an infinite strength."""
    path = _bare_copy(tmp_path, "bodies/guide.toml",
                      "\nfatigue_strength = 200e6\nfatigue_cycles = 1e6")
    reversed_ = analyze_model(load_spec(path), model="beam")
    steel = analyze_model(load_spec(EXAMPLES / "bodies/guide.toml"), model="beam")
    assert reversed_["stroke_limit_fatigue"] == pytest.approx(steel["stroke_limit_fatigue"],
                                                              rel=1e-12)
    assert "stroke_limit_fatigue" not in reversed_["not_available"]
    mean = analyze_model(load_spec(path, {"analysis.mean_stroke": 1e-4}), model="beam")
    assert mean["stroke_limit_fatigue"] is None
    assert mean["not_available"]["stroke_limit_fatigue"] == (
        "needs ultimate_strength and yield_strength (the goodman line of a mean stroke)")
    soderberg = analyze_model(load_spec(path, {"analysis.mean_stroke": 1e-4,
                                               "analysis.fatigue": "soderberg"}), model="beam")
    assert soderberg["not_available"]["stroke_limit_fatigue"] == (
        "needs yield_strength (the soderberg line of a mean stroke)")


def test_a_front_constrained_by_a_stroke_says_why_its_designs_fail(tmp_path, capsys):
    _bare_copy(tmp_path, "bodies/guide.toml")
    front = (EXAMPLES / "bodies" / "guide_front.toml").read_text()
    front = front.replace("population = 24", "population = 4").replace("generations = 12",
                                                                      "generations = 1")
    (tmp_path / "front.toml").write_text(front)
    assert main(["front", str(tmp_path / "front.toml"), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err  # every design fails alike: the search stops after the first
    assert "every design of the first generation (4) failed, so the search stops" in err
    assert "'stroke_limit_yield' is missing (not available: stroke_limit_yield: needs " \
           "yield_strength" in err and err.count("\n") == 1


def test_converge_of_a_stroke_says_what_it_needs(tmp_path, capsys):
    path = _bare_copy(tmp_path, "bodies/guide.toml")
    assert main(["converge", str(path), "--metric", "stroke_limit_yield", "--levels", "3",
                 "--out", str(tmp_path / "conv")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "not available: stroke_limit_yield: needs " \
                                    "yield_strength" in err
