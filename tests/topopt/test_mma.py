"""flexfem's MMA step (topopt/mma.py, mmapy's method written again for speed) against mmapy's
own ``mmasub``: the same asymptotes and the same next design, on random subproblems with
several constraints and with variables of no sensitivity, and along a whole run of the force
inverter beside the educational-style port that calls ``mmasub``."""
import numpy as np
import pytest
from inverter_port import inverter88
from mmapy import mmasub
from problems import inverter

from flexfem.topopt import optimize
from flexfem.topopt.mma import MMAState, mma_update


def _mmasub(state, it, z, f0, df0, fval, dfdx, move):
    n, m = z.size, len(fval)
    col = lambda v: np.asarray(v, dtype=float).reshape(-1, 1)  # noqa: E731
    out = mmasub(m, n, it, col(z), np.zeros((n, 1)), np.ones((n, 1)), col(state.xold1),
                 col(state.xold2), f0, col(df0), col(fval), np.reshape(dfdx, (m, n)),
                 col(state.low), col(state.upp), 1.0, np.zeros((m, 1)), np.full((m, 1), 1000.0),
                 np.ones((m, 1)), move=move)
    return out[0].ravel(), out[-2].ravel(), out[-1].ravel()


@pytest.mark.parametrize("n, m, seed", [(300, 1, 0), (300, 3, 1), (40, 2, 2), (3, 4, 3)])
def test_the_step_is_mmasubs(n, m, seed):
    """Five steps of a random sequence of designs: every next design and asymptote as
    mmasub's, to 1e-8 (the primal-dual iterations are the same; only rounding differs)."""
    rng = np.random.default_rng(seed)
    z = rng.uniform(0.1, 0.9, n)
    ours, theirs = MMAState.start(z), MMAState.start(z)
    for it in range(1, 6):
        df0 = rng.normal(size=n) * (rng.random(n) < 0.7)   # a third with no sensitivity
        fval = rng.normal(scale=0.3, size=m)
        dfdx = rng.normal(size=(m, n)) / n
        x_ref, low_ref, upp_ref = _mmasub(theirs, it, z, 1.0, df0, fval, dfdx, 0.2)
        x = mma_update(ours, it, z, 1.0, df0, list(fval), dfdx, 0.0, 1.0, 0.2)
        assert np.max(np.abs(x - x_ref)) < 1e-8
        assert np.max(np.abs(ours.low - low_ref)) < 1e-12
        assert np.max(np.abs(ours.upp - upp_ref)) < 1e-12
        theirs.xold2, theirs.xold1 = theirs.xold1, z.copy()
        theirs.low, theirs.upp = low_ref, upp_ref
        z = x_ref


def test_without_constraints_the_step_is_mmasubs_with_a_slack_one():
    """No constraint: mmasub is called with one that never binds (-1 <= 0), as before."""
    rng = np.random.default_rng(4)
    z, df0 = rng.uniform(0.1, 0.9, 50), rng.normal(size=50)
    x_ref, *_ = _mmasub(MMAState.start(z), 1, z, 1.0, df0, [-1.0], np.zeros((1, 50)), 0.3)
    x = mma_update(MMAState.start(z), 1, z, 1.0, df0, [], [], 0.0, 1.0, 0.3)
    assert np.max(np.abs(x - x_ref)) < 1e-8


def test_an_inverter_run_takes_the_ports_steps():
    """30 iterations of the 24 x 12 force inverter beside the port (top88's loop, spsolve,
    mmapy's mmasub): the same output displacement and densities."""
    u_ref, loops, x_ref = inverter88(24, 12, 0.3, 3.0, 1.5, 30, clamp=1)
    result = optimize(inverter(24, 12, iterations=30))
    assert result.iterations == loops == 30
    assert result.history[-1, 0] == pytest.approx(u_ref, rel=1e-8)
    ours = result.problem.grid.image(result.density)
    assert np.max(np.abs(ours - x_ref.reshape(24, 12).T)) < 1e-8
