"""A spring between two groups adds in series and in parallel as springs do."""
import numpy as np
import pytest

from flexfem.fem import Fixed, Force, Model, PlaneStress, group_spring, solve_static
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
