"""The stroke limits checked by a large-deflection solve ([analysis] stroke_check = true):
the bridge amplifier's leaves depart from linear by 14 % in force at the linear yield stroke,
so its limits come from the nonlinear path, and the force the path gives at its limit is that
of an independent solve, displacement-controlled on the continuum, at that stroke; a cross
pivot at its yield stroke stays linear, and its linear limits stand."""
from pathlib import Path

import numpy as np
import pytest
from flexfem.fem import Prescribed, solve_nonlinear
from flexfem.geometry.user_model import load_spec
from flexfem.studies.user_model.analysis import analyze_model, build, supports_and_loads
from flexfem.studies.user_model.fields import path_end_mesh
from flexfem.studies.user_model.stroke_check import DEPARTURE, LINEAR, UNCHECKED

BODIES = Path(__file__).parents[3] / "examples" / "bodies"
CHECKED = {"analysis.stroke_check": True}


def _prescribed_force(spec, group: str, stroke: float) -> float:
    """The force (N, along x) that holds ``group`` of the continuum at the stroke ``stroke``
    (m, along x): a large-deflection solve with the stroke prescribed on the group's face."""
    fe, _ = build(spec)
    supports, _ = supports_and_loads(spec)
    path = solve_nonlinear(fe, supports + [Prescribed(group, x=stroke)], [], steps=6)
    assert path.mean_displacement(group)[0] == pytest.approx(stroke, rel=1e-9)
    return float(path.reactions[-1][group][0])


@pytest.mark.parametrize("model", ["continuum", "beam"])
def test_the_bridges_limits_come_from_the_nonlinear_path(model):
    spec = load_spec(BODIES / "bridge.toml", CHECKED)
    kept = {}
    out = analyze_model(spec, model=model, fields=kept)
    check = out["stroke_check"]
    # --out's stroke_path.vtu: the path's end state, the input where the path ended
    end = path_end_mesh(*kept["stroke_path"])
    beam_model, _ = kept["stroke_path"]
    node = beam_model.groups["input.left"].nodes[0]
    assert end.point_data["displacement"][node, 0] == pytest.approx(check["strokes"][-1],
                                                                    rel=1e-9)
    assert out["stroke_limit_basis"] == "nonlinear path"
    assert abs(check["departure"]["force"]) > DEPARTURE  # -14 %: the leaves' axial stiffening
    assert "force" in check["departed"] and set(check["output_departure"]) >= {"R"}
    # R on the path at the stroke against the analysis' linear R (a ratio: the same at any
    # stroke; the check's model is the beam's, whose linear R is within 2 % of the continuum's)
    r_path = np.interp(check["at_stroke"], check["strokes"][1:], check["outputs"]["R"][1:])
    assert check["output_departure"]["R"] == pytest.approx(r_path / out["outputs"]["R"] - 1,
                                                           abs=0.02)
    linear = check["linear_limits"]["stroke_limit_yield"]
    assert out["stroke_limit_yield"] != pytest.approx(linear, rel=0.02)  # 63.7 vs 59.2 um
    assert check["yield_reached"] and out["stroke_limit_fatigue"] is not None
    # the path's peak stress reaches the allowable at the limit, linear between its steps
    at = np.interp(out["stroke_limit_yield"], check["strokes"], check["peak_stress"])
    assert at == pytest.approx(spec.material.yield_strength, rel=1e-9)
    held = _prescribed_force(spec, "input.left", out["stroke_limit_yield"])
    assert check["force_at_limit"] == pytest.approx(held, rel=0.05)
    assert check["force_at_limit"] < 0.95 * out["stroke_limit_yield"] / (
        out["mean_displacement"]["input.left"][0] / 10.0)  # well below the linear force


def test_a_cross_pivot_at_its_yield_stroke_is_linear():
    out = analyze_model(load_spec(BODIES / "cross_pivot.toml", CHECKED))
    assert out["stroke_limit_basis"] == LINEAR and out["stroke_check"]["departed"] == []
    assert max(abs(v) for v in out["stroke_check"]["departure"].values()) <= DEPARTURE
    assert out["stroke_limit_yield"] == out["stroke_check"]["linear_limits"]["stroke_limit_yield"]


def test_unchecked_by_default_and_a_bad_value_refused():
    out = analyze_model(load_spec(BODIES / "cross_pivot.toml"), model="beam")
    assert out["stroke_limit_basis"] == UNCHECKED and "stroke_check" not in out
    with pytest.raises(ValueError, match="stroke_check"):
        load_spec(BODIES / "cross_pivot.toml", {"analysis.stroke_check": 2})
