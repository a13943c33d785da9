"""fem/fatigue.py by hand: a compressive mean stress (Shigley, 9th ed., Section 6-12: sigma_a
<= Se / n, first-cycle yield sigma_a + |sigma_m| <= Sy / n), a tensile mean on the existing
Goodman and Soderberg lines, and the limits of a flexure known only at computed states
(interpolated, never extrapolated). Structural steel: Se 200, Sy 250, Sut 400 MPa."""
import pytest
from flexfem.fem import material
from flexfem.fem.fatigue import (allowed_amplitude, fatigue_stroke, fatigue_stroke_curve,
                                 yield_stroke, yield_stroke_curve)

STEEL = material("structural_steel")
MPa = 1e6


@pytest.mark.parametrize("mean, n, expected", [
    (-20 * MPa, 1.0, 200 * MPa),    # Se governs: a compressive mean does not help
    (-100 * MPa, 1.0, 150 * MPa),   # the first cycle yields first: 250 - 100
    (-20 * MPa, 2.0, 100 * MPa),    # Se / n = 100 < Sy / n - 20 = 105
    (-120 * MPa, 2.0, 5 * MPa),     # Sy / n - 120
    (-300 * MPa, 1.0, 0.0),         # the mean alone is past yield
])
def test_compressive_mean_by_hand(mean, n, expected):
    for criterion in ("goodman", "soderberg"):  # the two lines agree for a compressive mean
        assert allowed_amplitude(mean, STEEL, criterion, n) == pytest.approx(expected)


def test_tensile_mean_is_the_goodman_and_soderberg_line():
    assert allowed_amplitude(100 * MPa, STEEL) == pytest.approx(200 * MPa * (1 - 100 / 400))
    assert allowed_amplitude(100 * MPa, STEEL, "soderberg", 1.5) == pytest.approx(
        200 * MPa * (1 / 1.5 - 100 / 250))
    s = 1e9  # Pa per m: a linear flexure, mean stroke 0.05 m (50 MPa, the first cycle elastic)
    for criterion in ("goodman", "soderberg"):
        linear = fatigue_stroke(s, STEEL, 0.05, criterion)
        strokes = [0.1, 0.2, 0.3, 0.4]
        curve, reached = fatigue_stroke_curve(strokes, [s * x for x in strokes], STEEL,
                                              mean_stroke=0.05, criterion=criterion)
        assert reached and curve == pytest.approx(linear, rel=1e-9)
    assert fatigue_stroke(s, STEEL, 0.05) == pytest.approx(0.175)


def test_a_preloaded_curve_by_hand():
    """S(x) = |sigma_p| + s x sampled at three states: the yield limit where S = Sy, the
    fatigue amplitude where s x reaches the compressive-mean allowance."""
    s = 1e9
    strokes = [0.05, 0.15, 0.30]
    for preload, amplitude in ((-20 * MPa, 0.200), (-100 * MPa, 0.150)):
        stresses = [abs(preload) + s * x for x in strokes]
        at, reached = yield_stroke_curve(strokes, stresses, STEEL.yield_strength, 1.0, preload)
        assert reached and at == pytest.approx((250 * MPa - abs(preload)) / s)
        a, reached = fatigue_stroke_curve(strokes, stresses, STEEL, preload)
        assert reached and a == pytest.approx(amplitude, rel=1e-9)


def test_a_curve_is_interpolated_between_its_states_and_never_extrapolated():
    strokes, stresses = [1.0, 2.0, 3.0], [100 * MPa, 200 * MPa, 400 * MPa]
    at, reached = yield_stroke_curve(strokes, stresses, STEEL.yield_strength)
    assert reached and at == pytest.approx(2.25)  # 200 -> 400 MPa between 2 and 3
    assert yield_stroke_curve(strokes, stresses, 500 * MPa) == (3.0, False)  # a lower bound
    assert yield_stroke_curve(strokes, [s / 4 for s in stresses], STEEL.yield_strength,
                              ) == (3.0, False)
    a, reached = fatigue_stroke_curve(strokes, [s / 4 for s in stresses], STEEL)
    assert (a, reached) == (3.0, False)
    assert fatigue_stroke_curve(strokes, stresses, material("silicon_110"))[0] is None
    assert yield_stroke(1e8, STEEL.yield_strength) == pytest.approx(2.5)  # the linear one
    with pytest.raises(ValueError, match="increasing"):
        yield_stroke_curve([2.0, 1.0], [1.0, 2.0], STEEL.yield_strength)
