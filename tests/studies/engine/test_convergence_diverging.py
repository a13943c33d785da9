"""A series that grows under refinement is diverging (singular): no extrapolation, no level
"within tolerance", whatever the signs of its changes; the cross pivot's peak stress at its
fused crossing (a sharp re-entrant corner) is one."""
import math

import pytest
from flexfem.studies.engine.convergence import converge, diverging
from flexfem.studies.run_cli import summarize_convergence

#: The cross pivot's peak von Mises stress (MPa) over four halvings as issue 34 measured it.
ISSUE_SERIES = [23.0, 27.7, 39.0, 54.1]


def _series(values):
    def evaluate(params, level):
        return {"f": values[level], "h": 2.0 ** -level}
    return evaluate, [{"level": i} for i in range(len(values))]


def test_the_issue_series_is_diverging_and_no_level_is_within_tolerance():
    evaluate, levels = _series(ISSUE_SERIES)
    result = converge(evaluate, "f", levels, tol=0.005)
    assert result.behaviour == "divergent"
    assert result.coarsest_within_tol is None  # was 3: the finest "within 0.5 %" of itself
    assert math.isnan(result.error_estimate) and math.isnan(result.gci)
    text = summarize_convergence({"mechanism": "cross", **result.to_dict()})
    assert "diverging (singular)" in text and "within 0.5 %" not in text


@pytest.mark.parametrize("values", [
    [1.0, 1.3, 1.1, 1.4],      # oscillating, the swing growing: ratio of differences 1.5
    [1.0, 1.2, 1.4, 1.6],      # constant differences: ratio 1, order 0
    [1.0, 1.5, 1.9, 2.2],      # shrinking by 0.75 a halving: order 0.42 < 0.5
])
def test_changes_that_do_not_shrink_are_diverging(values):
    evaluate, levels = _series(values)
    result = converge(evaluate, "f", levels, tol=0.005)
    assert result.behaviour == "divergent" and result.coarsest_within_tol is None


def test_a_converging_series_is_not_called_diverging():
    evaluate, levels = _series([1 + 4.0 ** -k for k in range(4)])  # order 2
    result = converge(evaluate, "f", levels, tol=0.02)  # 1.56 % off at the finest level
    assert result.behaviour == "monotone" and result.coarsest_within_tol == 3
    assert not diverging(1.25, 1.0625, 1.015625, 2.0)
    assert diverging(1.0, 1.0, 1.1, math.nan)  # no change, then one: not converged


def test_the_cross_pivots_peak_stress_diverges():
    """flexfem converge examples/bodies/cross_pivot.toml --metric max_von_mises: the peak at
    the fused crossing grows with each halving of the element size."""
    from flexfem.studies.user_model.analysis import evaluate as model_evaluate

    def evaluate(params, size_factor):
        return model_evaluate(params, file="examples/bodies/cross_pivot.toml",
                              size_factor=size_factor)

    levels = [{"size_factor": 2.0 ** -k} for k in range(3)]
    result = converge(evaluate, "max_von_mises", levels, tol=0.005)
    assert all(b > a for a, b in zip(result.values, result.values[1:]))
    assert result.behaviour == "divergent" and result.coarsest_within_tol is None
