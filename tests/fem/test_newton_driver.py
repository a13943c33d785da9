"""The one Newton driver (fem/newton.py): quadratic convergence to a known root, the one
divergence rule, the line search, and every failure as StepFailed."""
import math

import numpy as np
import pytest

from flexfem.fem.factor import SingularStiffness
from flexfem.fem.newton import DIVERGENCE, diverged, newton
from flexfem.fem.stepping import StepFailed


def scalar(f, df):
    """(residual, correction) of f(x) = 0 on a 1-vector, reference 1."""
    return (lambda x: (np.array([f(x[0])]), 1.0, df(x[0])),
            lambda x, r, slope: -r / slope)


def test_converges_quadratically_to_the_root():
    # x^3 + x - 10 = 0 has the root x = 2 (8 + 2 - 10)
    residual, correction = scalar(lambda x: x**3 + x - 10.0, lambda x: 3 * x**2 + 1.0)
    found = newton(np.array([1.0]), residual, correction, tol=1e-13, max_iterations=20)
    assert found.x[0] == pytest.approx(2.0, rel=1e-14)
    h = found.history
    assert h[-1] <= 1e-13 and found.iterations == len(h) - 1
    # quadratic: each error about the square of the last (constant f''/2f' = 6/13 at x = 2)
    ratios = [b / a**2 for a, b in zip(h[-4:-2], h[-3:-1])]
    assert all(0.01 < q < 1.0 for q in ratios)


def test_a_vector_system_with_its_own_norm_and_update():
    # x0^2 + x1^2 = 5, x0 - x1 = 1: the root (2, 1) from (3, 0)
    def residual(x):
        r = np.array([x[0]**2 + x[1]**2 - 5.0, x[0] - x[1] - 1.0])
        return r, 5.0, np.array([[2 * x[0], 2 * x[1]], [1.0, -1.0]])
    found = newton(np.array([3.0, 0.0]), residual, lambda x, r, J: np.linalg.solve(J, -r),
                   tol=1e-12, max_iterations=20, norm=lambda r: np.abs(r).max(),
                   update=lambda x, dx: x + dx)
    assert np.allclose(found.x, [2.0, 1.0], rtol=1e-12, atol=0)


@pytest.mark.filterwarnings("ignore::RuntimeWarning")  # the diverging iterate's overflow
def test_newton_on_arctan_diverges_and_the_line_search_rescues_it():
    # f = arctan: Newton from |x| > 1.39 oscillates outward (x -> x - (1 + x^2) arctan x)
    residual, correction = scalar(math.atan, lambda x: 1.0 / (1.0 + x * x))
    with pytest.raises(StepFailed, match="the residual diverged") as caught:
        newton(np.array([3.0]), residual, correction, tol=1e-12, max_iterations=50)
    # arctan is bounded by pi/2 < 1e6 atan(3): what the rule catches is the iterate
    # overflowing (|x| grows ~ x^2 pi / 2 a step) to a non-finite residual
    assert not math.isfinite(caught.value.history[-1]) and len(caught.value.history) < 20
    found = newton(np.array([3.0]), residual, correction, tol=1e-12, max_iterations=50,
                   line_search=True)
    assert abs(found.x[0]) <= 1e-12


def test_the_divergence_rule_is_relative_to_the_first_residual():
    assert not diverged(0.9 * DIVERGENCE, 1.0, 1e-9)
    assert diverged(1.1 * DIVERGENCE, 1.0, 1e-9)
    assert diverged(1.1 * DIVERGENCE * 1e-3, 1e-3, 1e-9)  # the same ratio at another scale
    assert not diverged(0.9 * DIVERGENCE * 1e-6, 1e-12, 1e-6)  # floored at the target
    assert diverged(math.nan, 1.0, 1.0) and diverged(math.inf, 1.0, 1.0)
    # a residual that grows by more than DIVERGENCE from the first: StepFailed
    residual = lambda x: (np.array([10.0 ** (4 * x[0])]), 1.0, None)
    with pytest.raises(StepFailed, match="diverged") as caught:
        newton(np.array([0.0]), residual, lambda x, r, s: np.array([1.0]), tol=1e-9,
               max_iterations=10)
    assert caught.value.history == [1.0, 1e4, 1e8]


def test_a_singular_tangent_and_no_convergence_are_step_failures():
    residual = lambda x: (np.array([1.0 + x[0] ** 2]), 1.0, None)

    def singular(x, r, state):
        raise SingularStiffness("the tangent is singular", "group 'arm'")
    with pytest.raises(StepFailed, match="free: group 'arm'") as caught:
        newton(np.array([0.0]), residual, singular, tol=1e-9, max_iterations=5)
    assert caught.value.history == [1.0]
    # x^2 + 1 has no real root: Newton wanders until max_iterations
    with pytest.raises(StepFailed, match="no convergence in 7 iterations"):
        newton(np.array([0.5]), residual, lambda x, r, s: -r / (2 * x), tol=1e-9,
               max_iterations=7)
