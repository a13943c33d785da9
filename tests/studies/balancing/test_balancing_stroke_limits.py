"""The compressed-leaf (negative-stiffness) pivot's rotation limits from its large-deflection
states (studies/balancing/report.py): the yield limit lies between the computed states whose
peak stresses bracket S_y, the fatigue amplitude where the stroke's own stress (the peak less
the preload's P / (w t)) reaches S_e, and both shrink when the preload grows (the clamp's
moment, kL / sin kL times the hub's, grows with kL)."""
import numpy as np
import pytest
from flexfem.studies.balancing.negative_pivot_study import negative_pivot_designs
from flexfem.studies.balancing.report import leaf_stress_curve, leaf_stroke_limits


@pytest.fixture(scope="module")
def pivot():
    motor, _, _, _, _, pivot = negative_pivot_designs()[0]
    return motor, pivot


@pytest.fixture(scope="module")
def design(pivot):
    motor, leaf = pivot
    curve = leaf_stress_curve(leaf, quick=True)
    return curve, leaf_stroke_limits(leaf, motor, curve)


def test_the_yield_limit_lies_between_the_states_that_bracket_yield(pivot, design):
    _, leaf = pivot
    curve, limits = design
    theta, stress = np.array(curve["theta_rad"]), np.array(curve["stress_Pa"])
    Sy = leaf.material.yield_strength
    assert stress[-1] >= Sy and np.all(stress[:-1] < Sy)  # they stop at the first past yield
    k = len(stress) - 1
    assert limits["stroke_limit_yield_reached"]
    assert theta[k - 1] < limits["stroke_limit_yield"] <= theta[k]
    assert limits["stroke_limit_yield"] > leaf.theta_max  # sized for S_y / 2 at theta_max


def test_the_fatigue_amplitude_with_the_compressive_preload(pivot, design):
    _, leaf = pivot
    curve, limits = design
    mean = -curve["P_N"] / (leaf.w * leaf.t)
    assert limits["preload_stress_Pa"] == pytest.approx(mean) and mean < 0
    level = leaf.material.fatigue_strength + abs(mean)  # sigma_a = S_e, the peak S_e + |mean|
    theta, stress = curve["theta_rad"], curve["stress_Pa"]
    k = next(i for i, s in enumerate(stress) if s >= level)
    assert theta[k - 1] < limits["stroke_limit_fatigue_goodman"] <= theta[k]
    assert limits["stroke_limit_fatigue_goodman"] == pytest.approx(
        np.interp(level, stress[k - 1:k + 1], theta[k - 1:k + 1]), rel=1e-9)
    # a compressive mean: Goodman and Soderberg are one rule
    assert limits["stroke_limit_fatigue_soderberg"] == limits["stroke_limit_fatigue_goodman"]
    assert limits["stroke_limit_fatigue_goodman"] < limits["stroke_limit_yield"]


def test_a_larger_preload_lowers_the_limits(pivot, design):
    motor, leaf = pivot
    _, limits = design
    stiffer = leaf_stroke_limits(leaf, motor, leaf_stress_curve(leaf, True, 1.15 * leaf.P))
    assert stiffer["stroke_limit_yield"] < limits["stroke_limit_yield"]
    assert stiffer["stroke_limit_fatigue_goodman"] < limits["stroke_limit_fatigue_goodman"]
