"""Pivot stability (studies/balancing/pivot_stability.py), quick: the compressed leaf's moment
against the elastica through its limit point, and the cross-spring centre shift against
L theta^2 / (12 cos(alpha/2))."""
import math

import pytest
from flexfem.studies.balancing.pivot_stability import pivot_stability_study

pytestmark = pytest.mark.slow  # ~20-30 s on a shared machine


@pytest.fixture(scope="module")
def study():
    return pivot_stability_study(quick=True)


def test_moment_rotation_through_the_limit_point(study):
    n = study["negative"][0]
    for row in n["rows"]:
        assert row["moment_fem_Nm"] == pytest.approx(row["moment_elastica_Nm"], rel=2e-3)
        assert row["stable_rotation_held"]
    k = [r["tangent_stiffness_Nm_per_rad"] for r in n["rows"]]
    assert k[0] < 0 < k[-1]  # negative stiffness in the working range, positive past the limit
    assert 1 < n["limit_margin"] < 6
    # at the limit the moment is the curve's extreme
    assert abs(n["limit_moment_Nm"]) >= max(abs(r["moment_fem_Nm"]) for r in n["rows"]) * 0.999
    assert n["preload_margin"] == pytest.approx((math.pi / n["kL"]) ** 2)
    # the limit point against the elastica's (largest |M| at the design preload)
    assert n["limit_rotation_rad"] == pytest.approx(n["limit_rotation_elastica_rad"], rel=0.03)
    assert n["limit_moment_Nm"] == pytest.approx(n["limit_moment_elastica_Nm"], rel=0.01)


def test_cross_spring_centre_shift_matches_the_closed_form(study):
    c = study["cross"]
    for row in c["rows"]:
        assert row["shift_x_m"] == pytest.approx(row["shift_closed_m"], rel=0.02)
        assert abs(row["shift_y_m"]) < 0.1 * row["shift_m"]
