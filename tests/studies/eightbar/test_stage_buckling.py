"""The eight-bar stage's buckling along the stroke (studies/eightbar/stage.py, quick mode):
the continuum's and the beam model's critical added loads about their own large-deflection
states, the beam within 5 % of the continuum at every position (issue 33), the state's
effect, the drawn pose's linear buckling, the report's rows and figure, the CLI's table."""
import json

import pytest

from flexfem.fem import Fixed, Force, solve_buckling
from flexfem.geometry.eightbar.flexure import EightBarFlexureParams
from flexfem.studies.cli import main
from flexfem.studies.eightbar import cli as eightbar_cli
from flexfem.studies.eightbar.stage import BUCKLING_CASES, FACE, ratio_key
from flexfem.studies.eightbar.stage_report import comparisons, plot_buckling

pytestmark = pytest.mark.slow  # the quick study (conftest.py's stage), ~2 min


def test_beam_model_within_five_percent_at_every_position(stage):
    """Measured on the coarse mesh (size factor 2): the beam model 1.3-3.1 % above the
    continuum, its worst the drive force at the ends of the stroke."""
    rows = stage["stroke_buckling"]
    assert [r["x_m"] for r in rows] == pytest.approx(
        [-stage["travel_m"] / 2, -stage["travel_m"] / 4, 0.0, stage["travel_m"] / 4,
         stage["travel_m"] / 2])
    for row in rows:
        for key in BUCKLING_CASES:
            assert row[key] > 0 and row[f"beam_{key}"] > 0
            assert row[ratio_key(key)] == pytest.approx(row[f"beam_{key}"] / row[key])
            assert abs(row[ratio_key(key)] - 1.0) <= 0.05
    b = stage["buckling"]
    assert b["beam_buckling_within"]
    assert abs(b["beam_buckling_worst_ratio"] - 1.0) == max(
        abs(r[ratio_key(k)] - 1.0) for r in rows for k in BUCKLING_CASES)
    # mirror symmetry: the -x rows are the +x rows' twins
    for a, z in zip(rows[:2], rows[:-3:-1]):
        assert a.get("mirrored") and a["drive_critical_n"] == z["drive_critical_n"]


def test_the_state_matters_and_the_beam_follows_it(stage):
    """The critical drive force falls by ~11 % from the drawn pose to the end of the stroke
    (the flexures turned): the incremental buckling about each state sees it, and the beam
    model's fall is the continuum's within 2 % of the drawn pose's load."""
    rows = {r["x_m"]: r for r in stage["stroke_buckling"]}
    middle, end = rows[0.0], rows[max(rows)]
    fall = end["drive_critical_n"] / middle["drive_critical_n"]
    beam_fall = end["beam_drive_critical_n"] / middle["beam_drive_critical_n"]
    assert fall < 0.95
    assert beam_fall == pytest.approx(fall, abs=0.02)
    assert stage["buckling"]["drive_critical_min_n"] == end["drive_critical_n"]


def test_drawn_pose_row_is_the_linear_buckling(stage):
    """At x = 0 (the path's unloaded step) the incremental buckling is the linear buckling of
    the force on the free face, to the solves' accuracy on this compliant mechanism (runs
    scatter by ~3e-6: the factor's solves of a near-mechanism)."""
    from flexfem.studies.eightbar.analysis import build_model
    model, _ = build_model(EightBarFlexureParams(), 2.0)
    linear = solve_buckling(model, [Fixed("fixed")], [Force(FACE, (1.0, 0.0))], n=1)
    assert stage["buckling"]["drive_critical_n"] == pytest.approx(linear.load_factors[0],
                                                                  rel=2e-5)


def test_report_rows_and_figure(stage, tmp_path):
    rows = comparisons(stage, stage["linear_analysis"]["k_x"])
    beam = [r for r in rows if r.quantity.endswith("(beam model)")]
    assert len(beam) == 3 and all(r.tolerance == 0.05 and r.kind == "derived" for r in beam)
    worst = max(beam, key=lambda r: abs(r.value / r.reference - 1))
    assert worst.value / worst.reference == pytest.approx(
        stage["buckling"]["beam_buckling_worst_ratio"])
    figure = plot_buckling(stage, tmp_path / "buckling.png")
    assert (tmp_path / "buckling.png").stat().st_size > 0 and "beam" in figure["caption"]


def test_cli_prints_the_table(stage, capsys, monkeypatch):
    monkeypatch.setattr(eightbar_cli, "stage_study", lambda quick: stage)
    assert main(["eightbar", "stage", "--quick"]) == 0
    text = capsys.readouterr().out
    assert "buckling along the stroke" in text and "within 5 %" in text
    assert len([line for line in text.splitlines() if line.strip().startswith("-16.550")]) == 1
    assert main(["eightbar", "stage", "--quick", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert {"drive_critical_n", "beam_drive_critical_n", "drive_ratio"} <= set(
        out["stroke_buckling"][0])
