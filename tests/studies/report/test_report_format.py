"""How the report writes what a designer decides by: a limit's margin (never a percentage
difference), angles wrapped to (-180, 180] with their whole turns, the stroke limits by hand
(yield and Goodman), and the modes' explanation from their effective masses."""
import math

import pytest

from flexfem.fem import material
from flexfem.studies.report.format import difference_text, margin_text, number, wrap_degrees
from flexfem.studies.report.modes import describe_mode, mode_table
from flexfem.studies.report.stroke import (curve_stroke_limits, fatigue_note, fatigue_stress,
                                           stroke_limits, stroke_sentence, stroke_table)


def _limit_row(value, reference, unit, limit):
    return {"flexfem": value, "reference": reference, "unit": unit, "limit": limit,
            "difference": (value - reference) / reference, "difference_kind": "relative"}


@pytest.mark.parametrize("value, reference, unit, limit, text", [
    (47.09, 1.0, "-", "lower", "47.1x the minimum"),
    (0.0046, 0.1, "-", "upper", "21.7x below the maximum"),
    (1.465e-5, 3.3e-5, "m", "lower", "2.25x short of the minimum"),  # beyond: short of it
    (5.02, 7.34, "Hz", "lower", "-2.32 Hz short of the minimum"),
    (1.6, 1.0, "-", "lower", "+0.6 above the minimum"),
    (3.0, 1.0, "-", "upper", "3x the maximum, over it"),
    (1.2, 1.0, "-", "upper", "+0.2 over the maximum"),
])
def test_a_limit_row_shows_its_margin_not_a_percentage(value, reference, unit, limit, text):
    row = _limit_row(value, reference, unit, limit)
    assert margin_text(row) == text == difference_text(row)
    assert "%" not in difference_text(row)


@pytest.mark.parametrize("value, text", [
    (10.0, "10 deg"), (180.0, "180 deg"), (-180.0, "180 deg - 1 turn"),
    (-227.2, "132.8 deg - 1 turn"), (1050.36, "-29.64 deg + 3 turns")])
def test_angles_are_wrapped_with_their_turns(value, text):
    assert number(value, "deg") == text
    angle, turns = wrap_degrees(value)
    assert -180 < angle <= 180 and math.isclose(angle + 360 * turns, value)


def test_an_angle_difference_beyond_half_a_turn_is_wrapped():
    row = {"difference": 870.36, "difference_kind": "absolute", "unit": "deg"}
    assert difference_text(row) == "+150 deg + 2 turns"


def test_stroke_limits_by_hand():
    """A fixed-guided leaf: sigma = 3 E t d / L^2 per stroke d; yield at Sy / s, Goodman
    fully reversed at Se / s, with a mean stroke Se (1/n - s d_m / Sut) / s."""
    steel = material("structural_steel")
    E, t, L = steel.E, 0.5e-3, 40e-3
    s = 3 * E * t / L ** 2
    limits = stroke_limits(s, steel, "leaf end's stroke", "m", "nominal bending stress")
    assert math.isclose(limits["stroke_limit_yield"], steel.yield_strength / s)
    assert math.isclose(limits["stroke_limit_fatigue_goodman"], steel.fatigue_strength / s)
    mean = stroke_limits(s, steel, "stroke", "m", "nominal", safety_factor=1.5,
                         mean_stroke=0.2e-3)
    expected = steel.fatigue_strength * (1 / 1.5 - s * 0.2e-3 / steel.ultimate_strength) / s
    assert math.isclose(mean["stroke_limit_fatigue_goodman"], expected)
    table = stroke_table([limits])
    assert "None" not in str(table) and "±" in table["rows"][0][3]
    assert "before yield" in stroke_sentence([limits]) and "1e6 cycles" in stroke_sentence([limits])


def test_a_preloaded_flexure_from_its_states():
    """Peak stress |sigma_p| + s x at three states, a compressive preload sigma_p = -100 MPa:
    yield where the peak reaches Sy, fatigue where s x reaches min(Se, Sy - 100 MPa) (250 -
    100 = 150 MPa for structural steel); a stronger material's yield is not reached by the
    states, and the text says so instead of extrapolating."""
    steel = material("structural_steel")
    s, strokes = 1e9, [0.05, 0.15, 0.30]
    peaks = [100e6 + s * x for x in strokes]
    limits = curve_stroke_limits(strokes, peaks, steel, "leaf rotation", "m", "states",
                                 preload_stress=-100e6)
    assert limits["stroke_limit_yield"] == pytest.approx(0.150)
    assert limits["stroke_limit_fatigue_goodman"] == pytest.approx(0.150)
    assert fatigue_stress(limits) == pytest.approx(250e6)
    row = stroke_table([limits])["rows"][0]
    assert "preload's mean -100 MPa" in row[1] and ">" not in row[2]
    assert "9th ed., Section 6-12" in fatigue_note([limits])
    assert "compressive" not in fatigue_note([stroke_limits(s, steel, "x", "m", "linear")])
    strong = curve_stroke_limits(strokes, [p / 4 for p in peaks], steel, "rotation", "m",
                                 "states", preload_stress=-25e6)
    assert not strong["stroke_limit_yield_reached"] and strong["stroke_limit_yield"] == 0.30
    assert "rotation > 0.3 m (last computed state); > ±0.3 m (last" in stroke_sentence([strong])
    assert "None" not in str(stroke_table([strong]))


def test_silicon_has_no_fatigue_limit_and_the_text_says_so():
    limits = stroke_limits(1e12, material("silicon_110"), "rotation", "rad", "peak")
    assert limits["stroke_limit_fatigue_goodman"] is None
    row = stroke_table([limits])["rows"][0]
    assert row[3] == "no fatigue data for this material" and "deg" in row[2]
    assert "None" not in str(row)


def test_every_mode_is_explained():
    assert describe_mode([0.0005, 0.0], "xy").startswith("internal")
    assert describe_mode([0.0, 0.86], "xy", working=True).endswith("along y")
    assert describe_mode([0.29, 0.0], "xy") == "along x (29 % of the mass)"
    table = mode_table([221.3, 310.4], [[1e-4, 0.0], [0.0, 0.28]], 0.325, "xy", "modes",
                       working=2)
    assert [r[-1].split(":")[0] for r in table["rows"]] == ["internal", "working mode"]
    assert table["rows"][0][2:4] == ["0.031 %", "< 0.01 %"]


def test_the_glance_table_counts_verdicts_and_names_the_worst_row():
    from flexfem.studies.report.comparison import Comparison
    from flexfem.studies.report.render import headline_groups, render_html, render_markdown
    from flexfem.studies.report.summary import glance_rows

    rows = [Comparison("a", 1.01, 1.0, "-", "Eq. 1", tolerance=0.05, headline=True).to_row(),
            Comparison("b", 1.3, 1.0, "-", "Eq. 2", tolerance=0.1, headline=True,
                       note="why b differs").to_row(),
            Comparison("c", 1.15, 1.0, "-", "Eq. 3", tolerance=0.1, headline=True).to_row(),
            Comparison("d", 2.0, 1.0, "-", "Eq. 4", limit="lower", headline=True).to_row()]
    report = {"sections": [{"section": "s", "title": "S", "document": "dbma", "lead": "rebuilt",
                            "comparisons": rows}],
              "environment": {"flexfem": "0", "python": "3", "cpus": 2},
              "settings": {"quick": True}, "wall_time_s": 1.0}
    [row] = glance_rows(headline_groups(report), report)
    assert row[1] == "rebuilt" and row[2] == "2 of 4 agree or meet their limit"
    assert row[3] == "b: +30.0 %" and row[4] == "why b differs"  # 3x its tolerance, differs
    assert "At a glance" in render_markdown(report)
    html = render_html(report)
    assert html.index("At a glance") < html.index("Design summary")
