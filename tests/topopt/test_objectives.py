"""The lowest eigenfrequency and the stress norm as objectives, and repeated eigenvalues: the
aggregate of the lowest eigenvalues is differentiable where a single eigenvalue is not."""
from dataclasses import replace

import numpy as np
import pytest
from problems import lbracket

from flexfem.topopt import Response, optimize
from flexfem.topopt.model import Discrete
from flexfem.topopt.problem_file import problem_from_dict


def _square(modes: int):
    """A 12 x 12 square pinned at its four edge mid-points: by its symmetry (a quarter turn
    maps it onto itself) the lowest in-plane eigenvalue is double at a uniform design."""
    return problem_from_dict({
        "domain": {"nelx": 12, "nely": 12}, "material": {"E": 1.0, "nu": 0.3, "rho": 1.0},
        "support": [{"where": {"point": p}} for p in ([6.0, 0.0], [6.0, 12.0], [0.0, 6.0],
                                                      [12.0, 6.0])],
        "load": [{"where": {"point": [3.0, 3.0]}, "force": [1.0, 0.0]}],
        "objective": {"kind": "frequency", "modes": modes},
        "constraint": [{"kind": "volume", "max": 0.5}], "optimizer": {"kind": "mma"},
        "filter": {"kind": "density", "radius": 1.5}})


def _one_sided(d, z, j, h=1e-5):
    """(left, right, central) difference quotients of the objective in variable j."""
    zp, zm = z.copy(), z.copy()
    zp[j] += h
    zm[j] -= h
    f0, fp, fm = (d.evaluate(v).objective for v in (z, zp, zm))
    return (f0 - fm) / h, (fp - f0) / h, (fp - fm) / (2 * h)


def test_a_double_eigenvalue_has_no_gradient_but_the_aggregate_has():
    single, pair = Discrete(_square(1)), Discrete(_square(2))
    z = np.full(single.n_variables, 0.5)
    assert pair.problem.sense == "max"            # frequency: maximised by default
    for j in (3, 40):
        left, right, _ = _one_sided(single, z, j)
        assert abs(left - right) > 0.5 * abs(left)          # a kink: no derivative
        ev = pair.evaluate(z)
        left, right, central = _one_sided(pair, z, j)
        assert -ev.objective_grad[j] == pytest.approx(central, rel=1e-5)
        assert left == pytest.approx(right, rel=1e-3)
    # the aggregate of a double eigenvalue lies 2^(-1/32) below it (in omega^2)
    f1, f2 = single.evaluate(z).objective, pair.evaluate(z).objective
    assert f2 / f1 == pytest.approx(2.0 ** (-1 / 64), rel=1e-6)


def test_maximising_the_frequency_of_a_clamped_beam():
    problem = problem_from_dict({
        "domain": {"nelx": 40, "nely": 10}, "material": {"E": 1.0, "nu": 0.3, "rho": 1.0},
        "support": [{"where": {"edge": "left"}}, {"where": {"edge": "right"}}],
        "load": [{"where": {"point": [20.0, 10.0]}, "force": [0.0, -1.0]}],
        "objective": {"kind": "frequency", "modes": 2},
        "constraint": [{"kind": "volume", "max": 0.5}],
        "optimizer": {"kind": "mma", "max_iterations": 200, "move": 0.1},
        "filter": {"kind": "density", "radius": 1.5}})
    result = optimize(problem)
    uniform = result.history[0, 0]                 # the first iteration: the uniform start
    assert result.converged and result.volume_fraction <= 0.5 + 1e-3
    assert result.objective > 2.0 * uniform


def test_minimising_the_stress_norm_of_the_l_bracket():
    problem = lbracket(iterations=40)
    problem = replace(problem, objective=Response("stress"), constraints=problem.constraints[:1])
    result = optimize(problem)
    assert result.volume_fraction <= 0.4 + 1e-3
    assert result.objective < 0.6 * result.history[0, 0]


@pytest.mark.parametrize("objective, message", [
    ({"kind": "frequency", "sense": "min"}, "its sense is 'max'"),
    ({"kind": "stress", "sense": "max"}, "its sense is 'min'"),
    ({"kind": "volume"}, "the volume is a constraint"),
    ({"kind": "frequency", "modes": 0}, "modes = 0"),
    ({"kind": "compliance", "modes": 2}, "modes: applies to kind 'frequency'")])
def test_bad_objectives_are_named(objective, message):
    data = {"domain": {"nelx": 4, "nely": 4}, "support": [{"where": {"edge": "left"}}],
            "load": [{"where": {"point": [4.0, 0.0]}, "force": [0.0, -1.0]}],
            "objective": objective, "constraint": [{"kind": "volume", "max": 0.5}],
            "optimizer": {"kind": "mma"}}
    with pytest.raises(ValueError, match=message):
        problem_from_dict(data)
