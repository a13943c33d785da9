"""The robust formulation with large displacements: each of the three projected designs on
its own large-displacement equilibrium (as the plain formulation solves it), the worst by
the same KS aggregate, and the gradients of the aggregate and of the constraints against
central finite differences on a small grid at a large load."""
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from flexfem.topopt.model import Discrete
from flexfem.topopt.problem_file import problem_from_dict, read_problem_file
from flexfem.topopt.robust import DESIGNS, worst

LARGE = Path(__file__).parents[2] / "examples" / "topopt" / "inverter_large.toml"


def _robust_large(force: float = 0.5, stress: float | None = None, robust: bool = True):
    """inverter_large.toml on 20 x 10 elements, load ``force``, with [robust] (eta 0.3, no
    minimum size) and a projection at 0.5; ``stress``: a stress-norm limit too."""
    data = read_problem_file(LARGE)
    data["domain"].update(nelx=20, nely=10, size=[40.0, 20.0])
    data["load"][0]["force"] = [force, 0.0]
    data["nonlinear"] = {"steps": 5}
    data["projection"] = {"beta": 2.0, "beta_max": 16.0, "every": 20}
    if stress is not None:
        data["constraint"].append({"kind": "stress", "max": stress, "pnorm": 8.0})
    if robust:
        data["robust"] = {"eta": 0.3}
    return problem_from_dict(data)


def _start(d, seed):
    rng = np.random.default_rng(seed)
    return np.clip(0.3 + 0.5 * rng.random(d.n_variables), d.lower, d.upper), rng


def test_each_design_is_solved_by_the_large_displacement_solver():
    d = Discrete(_robust_large())
    z, _ = _start(d, 1)
    ev = d.evaluate(z)
    plain = Discrete(_robust_large(robust=False))
    filtered = d.filter.physical(d.P @ z)
    alone = []
    for name, eta in zip(DESIGNS, d.problem.robust.thresholds):
        rho = d.physical(z, filtered, eta)
        _, disp, f0, *_ = plain.responses(rho)
        assert ev.designs[name]["objective"] == pytest.approx(f0, rel=1e-7)
        alone.append(f0)
    assert abs(ev.displacements["input"]) > 0.05 * 40    # over 5 % of the length: large
    linear = Discrete(replace(d.problem, nonlinear=None)).evaluate(z)
    assert abs(linear.objective - ev.objective) > 0.01 * abs(ev.objective)
    f, _ = worst(alone, np.zeros((3, 1)), 1.0)
    assert ev.objective == pytest.approx(f, rel=1e-7)


@pytest.mark.parametrize("stress", [None, 0.05])
def test_robust_large_displacement_gradients_match_finite_differences(stress):
    problem = _robust_large(stress=stress)
    d = Discrete(problem)
    z, rng = _start(d, 3)
    ev = d.evaluate(z)
    h = 1e-6
    for j in rng.choice(np.flatnonzero(d.upper > d.lower), 5, replace=False):
        zp, zm = z.copy(), z.copy()
        zp[j] += h
        zm[j] -= h
        ep, em = d.evaluate(zp), d.evaluate(zm)
        fd = -(ep.objective - em.objective) / (2 * h) if problem.sense == "max" else \
            (ep.objective - em.objective) / (2 * h)
        assert ev.objective_grad[j] == pytest.approx(fd, rel=1e-4, abs=1e-6 * np.abs(
            ev.objective_grad).max())
        for k in range(len(ev.constraints)):
            fdc = (ep.constraints[k] - em.constraints[k]) / (2 * h)
            assert ev.constraint_grads[k, j] == pytest.approx(fdc, rel=1e-4, abs=1e-6 * np.abs(
                ev.constraint_grads[k]).max()), k


def test_a_short_robust_large_displacement_run_reports_both():
    """optimize() runs the small-displacement robust twin first, then the large one: the
    summary has the three designs and the large-displacement start."""
    from flexfem.topopt import optimize

    problem = replace(_robust_large(), optimizer=replace(_robust_large().optimizer,
                                                         max_iterations=4))
    summary = optimize(problem).summary()
    assert set(summary["robust"]["designs"]) == set(DESIGNS)
    assert summary["large_displacements"]["start_iterations"] == 4
    assert summary["iterations"] == 4
