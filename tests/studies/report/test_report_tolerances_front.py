"""The report's tolerance and front helpers (studies/report/tolerances.py, front.py) on the
toy cantilever: the table, the sentence naming the tolerance that matters most, the figure,
the confirming model's table and a front with a reference placed on it, in seconds."""
import json

import pytest
from flexfem.studies.report.front import front_report
from flexfem.studies.report.tolerances import add_to_section, tolerance_report
from flexfem.studies.toy.model import evaluate

pytest.importorskip("SALib", reason="SALib is a dependency of tolerance studies")

TOY = {"mechanism": "toy", "options": {"n_elements": 4}, "tolerances": {
    "n": 16, "metrics": ["stiffness", "root_stress"], "confirm": {"n_elements": 400},
    "parameters": {
        "thickness_root_m": {"nominal": 0.002, "tolerance": 4e-5},
        "width_m": {"nominal": 0.01, "tolerance": 1e-5, "distribution": "uniform"}}}}
OUTPUTS = {"stiffness": ("tip stiffness", "N/m"), "root_stress": ("root stress", "Pa")}
LABELS = {"thickness_root_m": "root thickness", "width_m": "width"}


def test_tolerance_report_names_the_tolerance_that_matters(tmp_path):
    """The root thickness (2 % in 3σ) dominates a cantilever's stiffness and root stress over
    its width (0.1 %, uniform); the extremes re-checked on 400 elements."""
    result = tolerance_report(TOY, evaluate, tmp_path / "tol", OUTPUTS, LABELS, "the toy's tolerances",
                              n=8, confirm=True, figure="toy_tol.png", prefix="tol/")
    assert result["summary"]["n_designs"] == 8 * 4 and result["summary"]["failed"] == 0
    assert result["sentence"].startswith("Of the toy's tolerances, the root thickness "
                                         "tolerance (±40 um (3σ)) matters most")
    table = result["table"]
    assert [r[0] for r in table["rows"]] == ["tip stiffness", "root stress"]
    assert len(table["columns"]) == 3 + 2 and all(len(r) == 5 for r in table["rows"])
    assert result["figure"]["file"] == "tol/toy_tol.png" and (tmp_path / "tol" / "toy_tol.png").is_file()
    assert set(result["tables"]) == {"tol/results.csv", "tol/tolerances.json"}
    saved = json.loads((tmp_path / "tol" / "tolerances.json").read_text())
    assert saved["confirm"]["options"] == {"n_elements": 400}
    rows = result["confirm_table"]["rows"]
    assert len(rows) == 4 and all(r[3].endswith("%") for r in rows)
    assert "None" not in json.dumps(result["table"]) + json.dumps(result["confirm_table"])
    # the indices were drawn from the study's own store: a second run computes nothing
    again = tolerance_report(TOY, evaluate, tmp_path / "tol", OUTPUTS, LABELS, "the toy's tolerances",
                             n=8, confirm=True, figure="toy_tol.png")
    assert again["confirm"]["computed"] == 0 and again["table"] == table
    section = {"figures": [{"file": "a.png"}, {"file": "b.vtu"}], "notes": ["n"]}
    kept = add_to_section(section, result, before="b.vtu")
    assert [f["file"] for f in section["figures"]] == ["a.png", "tol/toy_tol.png", "b.vtu"]
    assert section["notes"][-1] == result["sentence"] and len(section["key_tables"]) == 2
    assert kept == {"summary": result["summary"], "confirm": result["confirm"]}


def test_front_report_places_the_reference(tmp_path):
    """Stiffness (max) against root stress (min) over the root thickness: a cantilever's
    trade-off, a reference on the base design placed beside it."""
    table = {"mechanism": "toy", "options": {"n_elements": 8},
             "variables": {"thickness_root_m": [0.001, 0.004], "thickness_tip_m": [0.001, 0.002]},
             "objectives": [{"metric": "stiffness", "goal": "max"},
                            {"metric": "root_stress", "goal": "min"}],
             "constraints": [{"metric": "tip_deflection", "at_most": 0.01}],
             "search": {"population": 8, "generations": 4, "seed": 0},
             "confirm": {"n_elements": 200},
             "reference": [{"name": "base", "params": {}}]}
    result = front_report(table, evaluate, tmp_path / "front", {"stiffness": ("stiffness", "N/m"),
                                                      "root_stress": ("root stress", "Pa"),
                                                      "tip_deflection": ("deflection", "m")},
                          "the toy", references=(("thick", {"thickness_root_m": 0.004,
                                                            "thickness_tip_m": 0.002}),),
                          prefix="front/", defaults={"thickness_root_m": 0.002,
                                                     "thickness_tip_m": 0.002})
    designs = result["result"]["designs"]
    assert designs and all(d["confirmed"] for d in designs)
    names = [r[0] for r in result["table"]["rows"]]
    assert names[-2:] == ["base", "thick"] and len(names) <= 5 + 2
    assert result["table"]["rows"][-2][1:3] == ["2.000", "2.000"]  # the defaults shown
    assert "base (" in result["sentence"] and "thick (" in result["sentence"]
    assert (tmp_path / "front" / "front.png").is_file() and result["figure"]["file"] == "front/front.png"


def test_the_stroke_limit_figure(tmp_path):
    """Stress against stroke with the yield and fatigue lines, and a material without
    fatigue data (silicon) drawn with its yield line only."""
    from flexfem.fem import material
    from flexfem.studies.report.stroke import fatigue_stress, plot_stroke_limits, stroke_limits

    steel = stroke_limits(4e12, material("structural_steel"), "actuator elongation", "m", "test")
    silicon = stroke_limits(1e9, material("silicon_110"), "pivot rotation", "rad", "test")
    assert fatigue_stress(steel) == pytest.approx(4e12 * steel["stroke_limit_fatigue_goodman"])
    assert fatigue_stress(silicon) is None
    fig = plot_stroke_limits([steel, silicon], tmp_path / "stroke.png")
    assert fig["file"] == "stroke.png" and (tmp_path / "stroke.png").stat().st_size > 10_000
    assert "yield strength" in fig["caption"] and "actuator elongation: test" in fig["caption"]


def test_strokes_drawn_together(tmp_path):
    """A linear stroke and one of computed states on one panel (one unit); two units refused."""
    from flexfem.fem import material
    from flexfem.studies.report.stroke import (curve_stroke_limits, plot_stroke_limits,
                                               stroke_limits)

    spring = material("spring_steel_aisi1095")
    linear = stroke_limits(3.7e9, spring, "cross-spring rotation", "rad", "test")
    leaf = curve_stroke_limits([0.1, 0.2, 0.6], [0.3e9, 0.6e9, 1.6e9], spring,
                               "compressed-leaf rotation", "rad", "test", preload_stress=-6e6)
    fig = plot_stroke_limits([linear, leaf], tmp_path / "both.png", together=True)
    assert (tmp_path / "both.png").stat().st_size > 10_000
    assert "compressed-leaf rotation: test" in fig["caption"]
    with pytest.raises(ValueError, match="one unit"):
        plot_stroke_limits([linear, stroke_limits(1e12, spring, "stroke", "m", "test")],
                           tmp_path / "mixed.png", together=True)
