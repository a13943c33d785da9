"""Heaviside projection with continuation: the map, beta's schedule, a mechanism designed
with it (near-binary), a resumed run mid-continuation, and the problem file's table."""
import numpy as np
import pytest
from problems import interrupt_at, inverter

from flexfem.topopt import Projection, optimize, problem_from_dict
from flexfem.topopt.projection import project, project_derivative
from flexfem.topopt.state import load_state


def test_the_projection_fixes_void_solid_and_threshold():
    x = np.array([0.0, 0.3, 0.5, 1.0])
    for beta in (1.0, 8.0, 64.0):
        rho = project(x, beta, 0.5)
        assert rho[0] == pytest.approx(0.0, abs=1e-12) and rho[-1] == pytest.approx(1.0)
        assert rho[2] == pytest.approx(0.5)
    assert project(np.array([0.4]), 64.0, 0.5)[0] < 1e-4
    h = 1e-6
    assert project_derivative(x[1:3], 8.0, 0.4) == pytest.approx(
        (project(x[1:3] + h, 8.0, 0.4) - project(x[1:3] - h, 8.0, 0.4)) / (2 * h), rel=1e-6)


def test_beta_doubles_after_every_iterations_or_on_a_small_change():
    p = Projection(beta=1.0, beta_max=8.0, every=10)
    assert p.next_beta(1.0, 3, 0.5, 0.01) == 1.0
    assert p.next_beta(1.0, 10, 0.5, 0.01) == 2.0
    assert p.next_beta(2.0, 1, 0.005, 0.01) == 4.0
    assert p.next_beta(8.0, 50, 0.0, 0.01) == 8.0
    with pytest.raises(ValueError, match="beta_max"):
        Projection(beta=4.0, beta_max=2.0)


@pytest.mark.slow
def test_a_projected_inverter_is_nearly_black_and_white():
    plain = optimize(inverter(24, 12, iterations=200))
    projected = optimize(inverter(24, 12, iterations=200,
                                  projection=Projection(beta=1.0, beta_max=16.0, every=20)))
    grey = [np.mean((r.density > 0.05) & (r.density < 0.95)) for r in (plain, projected)]
    assert projected.converged and projected.summary()["u_out"] < -0.5
    assert grey[1] < 0.02 < grey[0]
    assert projected.volume_fraction == pytest.approx(0.3, abs=0.005)


def test_a_run_resumed_mid_continuation_ends_where_an_uninterrupted_one_does(tmp_path):
    problem = inverter(16, 8, iterations=40,
                       projection=Projection(beta=1.0, beta_max=4.0, every=5))
    whole = optimize(problem)
    interrupt_at(problem, tmp_path, 7)
    assert float(load_state(tmp_path)["beta"]) == 2.0
    resumed = optimize(problem, out_dir=tmp_path)
    assert resumed.iterations == whole.iterations
    assert np.allclose(resumed.density, whole.density, atol=1e-10)


def test_the_problem_files_projection_table():
    data = {"domain": {"nelx": 4, "nely": 2}, "objective": {"kind": "compliance"},
            "support": [{"where": {"edge": "left"}}],
            "load": [{"where": {"point": [4, 0]}, "force": [0, -1]}],
            "constraint": [{"kind": "volume", "max": 0.5}],
            "filter": {"kind": "density", "radius": 1.5},
            "projection": {"beta_max": 16, "every": 30}}
    assert problem_from_dict(data).projection == Projection(1.0, 0.5, 16.0, 30)
    data["filter"]["kind"] = "sensitivity"
    with pytest.raises(ValueError, match="projection"):
        problem_from_dict(data)
    data["filter"]["kind"], data["projection"]["every"] = "density", 2.5
    with pytest.raises(ValueError, match="projection.every"):
        problem_from_dict(data)
