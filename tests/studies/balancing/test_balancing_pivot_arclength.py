"""The moment-driven compressed-leaf pivot by arc-length (studies/balancing/pivot_arclength.py):
the path through the limit point against the elastica closed form, coinciding with rotation
control, and its report entries."""
import pytest
from flexfem.studies.balancing.negative_pivot_study import leaf_model, negative_pivot_designs
from flexfem.studies.balancing.pivot_arclength import parabola_vertex, pivot_arclength
from flexfem.studies.balancing.pivot_arclength_report import (arclength_comparisons,
                                                              plot_arclength)
from flexfem.studies.balancing.pivot_stability import leaf_state

pytestmark = pytest.mark.slow  # ~20-40 s on a shared machine


@pytest.fixture(scope="module")
def pivot():
    return negative_pivot_designs()[0][-1]


@pytest.fixture(scope="module")
def arc(pivot):
    return {"motor": 2, **pivot_arclength(pivot, steps=8)}


def test_the_path_follows_the_elastica_through_the_limit_point(arc, pivot):
    rows = arc["rows"]
    m_lim = abs(arc["limit_moment_elastica_Nm"])
    for row in rows[1:]:
        assert row["moment_fem_Nm"] == pytest.approx(row["moment_elastica_Nm"], abs=5e-4 * m_lim)
    assert rows[-1]["theta_rad"] >= 6 * pivot.theta_max
    # the limit point against the elastica's (bounded search of the largest |M|)
    assert arc["limit_rotation_rad"] == pytest.approx(arc["limit_rotation_elastica_rad"], rel=0.005)
    assert arc["limit_moment_Nm"] == pytest.approx(arc["limit_moment_elastica_Nm"], rel=5e-4)
    # the preload stage keeps the leaf straight; driven by a moment the leaf is unstable up
    # to the limit point (its negative stiffness) and stable past it
    assert arc["preload_hub_dy_max_m"] < 1e-6 * pivot.L
    k = arc["limit_step"]
    assert all(r["negative_eigenvalues"] == 1 for r in rows[:k])
    assert all(r["negative_eigenvalues"] == 0 for r in rows[k + 1:])
    assert arc["moment_driven_unstable_over_working_range"]
    # margins: the beam-column stiffness at small angle, the limit well beyond the range
    assert arc["tangent_stiffness_at_theta_max_Nm_per_rad"] < 0
    assert 1 < arc["rotation_margin"] < 6 and arc["moment_margin"] > 1


def test_arc_length_and_rotation_control_give_the_same_states(arc, pivot):
    # the same leaf, the hub turned to an arc-length state's rotation by rotation control
    model = leaf_model(pivot, "plane_stress", 2, None)
    k = arc["limit_step"]
    for row in (arc["rows"][2], arc["rows"][k + 2]):  # before and past the limit point
        held = leaf_state(model, pivot.P, row["theta_rad"], 3)
        assert held["moment_fem_Nm"] == pytest.approx(row["moment_fem_Nm"], rel=1e-6)
        assert held["hub_dy_m"] == pytest.approx(row["hub_dy_m"], rel=1e-6)


def test_report_entries(arc, tmp_path):
    # without rotation-controlled states (they come from pivot_stability_study in the report)
    figure = plot_arclength([arc], [], tmp_path / "arc.png")
    assert (tmp_path / "arc.png").exists() and "arc-length" in figure["caption"]
    rows = arclength_comparisons([arc], [])
    assert [r.verdict for r in rows] == ["agrees", "agrees", "within limit"]


def test_parabola_vertex():
    x0, y0 = parabola_vertex([0.0, 1.0, 3.0], [(x - 1.2) ** 2 * 2 + 0.5 for x in (0.0, 1.0, 3.0)])
    assert (x0, y0) == (pytest.approx(1.2), pytest.approx(0.5))
