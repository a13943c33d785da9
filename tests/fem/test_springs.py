"""A spring between two groups adds in series and in parallel as springs do."""
import numpy as np
import pytest

from flexfem.fem import (Fixed, Force, Material, Model, PlaneStress, ground_spring, group_spring,
                         solve_nonlinear, solve_static)
from meshes import beam_2d


@pytest.fixture
def bar(steel):
    """A 1 m x 0.1 m bar, fixed at x = 0, pulled at its tip."""
    return Model(beam_2d(1.0, 0.1, 0.05), steel, PlaneStress(0.01), order=2)


def test_a_spring_to_the_ground_adds_in_parallel(bar):
    P = 1e3
    free = solve_static(bar, [Fixed("fixed")], [Force("tip", (P, 0.0))])
    k_bar = P / free.mean_displacement("tip")[0]
    k_spring = 2 * k_bar
    # the spring from the (held) root to the tip stands beside the bar: k_bar + k_spring
    sprung = bar.with_stiffness(group_spring(bar, "fixed", "tip", k_spring, "x"))
    both = solve_static(sprung, [Fixed("fixed")], [Force("tip", (P, 0.0))])
    assert P / both.mean_displacement("tip")[0] == pytest.approx(k_bar + k_spring, rel=1e-9)
    assert bar.stiffness is not sprung.stiffness  # the original model is unchanged
    assert np.isclose(P / free.mean_displacement("tip")[0], k_bar)


def test_bad_springs_are_refused(bar):
    with pytest.raises(ValueError, match="stiffness"):
        group_spring(bar, "fixed", "tip", -1.0)
    with pytest.raises(ValueError, match="component = 'z'"):
        group_spring(bar, "fixed", "tip", 1.0, "z")
    with pytest.raises(ValueError, match="shape"):
        bar.with_stiffness(np.eye(3))


def test_a_ground_spring_is_the_spring_from_a_held_group(bar):
    P = 1e3
    a = bar.with_stiffness(ground_spring(bar, "tip", 5e7, "x"))
    b = bar.with_stiffness(group_spring(bar, "fixed", "tip", 5e7, "x"))
    ua = solve_static(a, [Fixed("fixed")], [Force("tip", (P, 0.0))]).mean_displacement("tip")
    ub = solve_static(b, [Fixed("fixed")], [Force("tip", (P, 0.0))]).mean_displacement("tip")
    assert np.allclose(ua, ub, rtol=1e-12)
    with pytest.raises(ValueError, match="stiffness"):
        ground_spring(bar, "tip", 0.0)


def test_the_nonlinear_solver_carries_an_added_spring():
    """A bar of nu = 0 stretched to 1.2 times its length against a spring at its tip: the
    dead load F = E A (s^3 - s) / 2 + k (s - 1) L (St. Venant-Kirchhoff, uniaxial)."""
    E, L, h, t, k, s = 2e9, 1.0, 0.1, 0.01, 4e7, 1.2
    bar = Model(beam_2d(L, h, 0.05), Material("nu0", E, 0.0, 1000.0), PlaneStress(t), order=2)
    F = E * h * t * (s**3 - s) / 2 + k * (s - 1) * L
    sprung = bar.with_stiffness(ground_spring(bar, "tip", k, "x"))
    result = solve_nonlinear(sprung, [Fixed("fixed")], [Force("tip", (F, 0.0))], steps=8)
    assert result.mean_displacement("tip")[0] == pytest.approx((s - 1) * L, rel=1e-8)
    plain = solve_nonlinear(bar, [Fixed("fixed")], [Force("tip", (F, 0.0))], steps=8)
    assert plain.mean_displacement("tip")[0] > 1.05 * (s - 1) * L   # without it: further
