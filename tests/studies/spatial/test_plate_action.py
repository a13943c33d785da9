"""The anticlastic plate factor (studies/spatial/plate_action.py) against the bent strip's
energy minimised numerically: a strip of width w and thickness t bent to curvature kappa,
its transverse deflection free (finite differences across the width), the plate energy plus
the membrane energy of the curl; E I_eff = 2 U / kappa^2."""
import numpy as np
import pytest

from flexfem.studies.spatial.plate_action import plate_factor, searle_parameter


def strip_factor(width, thickness, nu, curvature, n=601):
    """E I_eff / (E I) of the strip by minimising its energy per unit length (E = 1)."""
    y = np.linspace(-width / 2, width / 2, n)
    h = y[1] - y[0]
    D = thickness ** 3 / (12 * (1 - nu ** 2))
    second = np.zeros((n, n))
    for i in range(n):
        j = min(max(i, 1), n - 2)
        second[i, j - 1:j + 2] = np.array([1.0, -2.0, 1.0]) / (h * h)
    weights = np.full(n, h)
    weights[[0, -1]] = h / 2
    centred = np.eye(n) - np.outer(np.ones(n), weights) / weights.sum()
    W = np.diag(weights)
    A = D * second.T @ W @ second + thickness * curvature ** 2 * centred.T @ W @ centred
    g = -nu * D * curvature * (second.T @ weights)
    w = np.linalg.solve(A, -g)
    energy = 0.5 * w @ A @ w + g @ w + 0.5 * curvature ** 2 * D * width
    return 2 * energy / curvature ** 2 / (thickness ** 3 * width / 12)


@pytest.mark.parametrize("beta", [0.1, 1.0, 3.0, 10.0, 30.0, 100.0])
def test_the_factor_is_the_strips_minimum_energy(beta):
    w, t, nu = 10.0, 1.0, 0.3
    kappa = beta * t / w ** 2
    assert searle_parameter(w, t, kappa) == pytest.approx(beta)
    assert plate_factor(w, t, nu, kappa) == pytest.approx(strip_factor(w, t, nu, kappa),
                                                          rel=1e-4)


def test_the_beam_at_rest_the_plate_when_wide():
    assert plate_factor(0.01, 0.001, 0.3, 0.0) == 1.0
    assert plate_factor(0.01, 0.001, 0.3, 1e-9) == pytest.approx(1.0, abs=1e-12)
    assert plate_factor(0.1, 1e-4, 0.3, 1e3) == pytest.approx(1 / (1 - 0.09), rel=1e-3)
    factors = [plate_factor(0.01, 0.001, 0.3, k) for k in np.geomspace(1e-3, 1e3, 30)]
    assert np.all(np.diff(factors) >= 0)


def test_bad_input_is_named():
    with pytest.raises(ValueError, match="Poisson's ratio"):
        plate_factor(0.01, 0.001, 0.5, 1.0)
    with pytest.raises(ValueError, match="thickness"):
        plate_factor(0.01, 0.0, 0.3, 1.0)
