"""The amplifier problem in the DBMA's envelope: its quarter, the actuator's room void, the
pad and the output solid, the input stiffness a limit; a few coarse iterations run."""
import numpy as np
import pytest

from flexfem.topopt import optimize
from flexfem.topopt.amplifier import amplifier_problem, dbma_envelope
from flexfem.topopt.model import Discrete


def test_the_envelope_is_the_dbmas_quarter():
    env = dbma_envelope()
    assert env["width"] == pytest.approx(0.04322) and env["height"] == pytest.approx(0.04547)
    assert env["pad"][0][0] == pytest.approx(0.03122) and env["thickness"] == 0.01


def test_a_coarse_amplifier_moves_its_output_up():
    problem = amplifier_problem(800.0, 4.36e6, 4e7, 1e5, element=2e-3, iterations=15,
                                radius=1.5)
    d = Discrete(problem)
    assert d.void.sum() > 0 and d.solid.sum() > 0
    result = optimize(problem)
    s = result.summary()
    assert s["u_out"] > 0 and s["u_in"] > 0
    assert s["u_in"] <= 400.0 / 4.36e6 * (1 + 1e-3)
    assert np.all(result.density[d.void] == 0.0)
