"""Design-rule check on hand-made rectangles (exact gaps) and on the scaled eight-bar."""
import pytest
from flexfem.geometry.design_rules import (
    FabricationRules,
    check_design_rules,
    fabrication_rules,
    violation_summary,
)
from flexfem.geometry.eightbar.flexure import EightBarFlexureParams, eightbar_layout
from flexfem.geometry.flexure_linkage import Part

UM = 1e-6


def test_thesis_rules_come_from_data():
    r = fabrication_rules()
    assert (r.min_beam_width, r.min_gap, r.max_gap) == pytest.approx((3 * UM, 0.7 * UM, 50 * UM))
    assert "p. 38" in r.source


def _bar(name, y, width):
    return Part(name, name, "bar", (0.0, y), (100 * UM, y), width)


def test_beam_width_and_gap_violations_are_found_with_their_values():
    rules = fabrication_rules()
    # two 5 um beams 0.5 um apart (edges at y = 2.5 and 3.0 um): gap 0.5 < 0.7 um
    parts = [_bar("a", 0.0, 5 * UM), _bar("b", 5.5 * UM, 5 * UM), _bar("thin", 80 * UM, 2 * UM)]
    v = check_design_rules(parts, rules)
    kinds = {x.kind: x for x in v}
    assert kinds["beam_width"].parts == ("thin",)
    assert kinds["beam_width"].value == pytest.approx(2 * UM)
    assert kinds["gap_too_small"].value == pytest.approx(0.5 * UM, rel=1e-9)
    assert kinds["gap_too_small"].location[1] == pytest.approx(2.75 * UM, abs=1e-9)
    # "thin" faces "b" across 80 - 1 - 5.5 - 2.5 = 71 um > 50 um
    assert kinds["gap_too_large"].value == pytest.approx(71 * UM, rel=1e-9)


def test_a_compliant_layout_passes():
    parts = [_bar("a", 0.0, 5 * UM), _bar("b", 15 * UM, 5 * UM)]  # gap 10 um
    assert check_design_rules(parts) == []


def test_bad_rules_raise():
    with pytest.raises(ValueError, match="max_gap"):
        FabricationRules(3 * UM, 1 * UM, 0.5 * UM)
    with pytest.raises(ValueError, match="unknown fabrication rules"):
        fabrication_rules("nope")


def test_eightbar_scaled_to_micrometres_breaks_the_minimum_beam_width():
    micro = EightBarFlexureParams().scaled(1e-3, "silicon_110")
    v = check_design_rules(eightbar_layout(micro).parts)
    summary = violation_summary(v)
    assert summary["beam_width"]["count"] == 10  # every flexure: 0.3 / 0.4 um < 3 um
    assert summary["beam_width"]["worst_m"] == pytest.approx(0.3 * UM)
