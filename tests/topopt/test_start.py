"""optimize(start=...): a run begun from given design variables and beta instead of the
uniform start."""
from dataclasses import replace

import numpy as np
import pytest
from problems import inverter

from flexfem.topopt import Projection, optimize


def test_a_run_begins_where_it_is_started():
    problem = inverter(20, 10, "density", iterations=30,
                       projection=Projection(beta=1.0, eta=0.5, beta_max=8.0, every=5))
    first = optimize(problem)
    z = first.design
    again = optimize(replace(problem, optimizer=replace(problem.optimizer, max_iterations=0)),
                     start=(z, first.beta))
    assert np.array_equal(again.design, z) and again.beta == first.beta
    assert again.objective == pytest.approx(first.objective, rel=1e-12)
    onward = optimize(replace(problem, optimizer=replace(problem.optimizer, max_iterations=2)),
                      start=(z, first.beta))
    assert onward.history[0, 0] == pytest.approx(first.objective, rel=1e-12)   # from z


def test_a_start_of_another_size_is_refused():
    problem = inverter(20, 10, "density", iterations=3)
    with pytest.raises(ValueError, match="start: .* design variables"):
        optimize(problem, start=(np.full(10, 0.3), None))
