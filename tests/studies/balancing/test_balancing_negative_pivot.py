"""Negative-stiffness compressed-leaf pivots (studies.balancing.negative_pivot[_study]).

Leaf for the FEM checks: L = 100 mm, t = 1.25 mm (L / t = 80), w = 50 mm, spring steel, P2
triangles, 2 elements through the leaf, rigid clamp and rigid hub (RigidFace), plane stress
(the beam of the beam formula)."""
import math

import numpy as np
import pytest
from flexfem.studies.balancing.negative_pivot import (
    KL_DEFAULT,
    CompressedLeafPivot,
    beam_column_rotational_stiffness,
    bending_stress_factor,
    compressed_leaf_elastica,
    compressed_leaf_stress,
    kL_for_stiffness_factor,
    preload_for_stiffness,
    size_negative_pivot,
    stiffness_factor,
)
from flexfem.studies.balancing.negative_pivot_study import negative_pivot_fem_check, negative_pivot_study
from flexfem.fem import material

STEEL = material("spring_steel_aisi1095")
E, L, T, W = STEEL.E, 0.1, 1.25e-3, 0.05
I = W * T**3 / 12
EI_L = E * I / L


def leaf(kL=KL_DEFAULT, theta_max=0.2):
    P = kL**2 * E * I / L**2
    K = EI_L * kL / math.tan(kL)
    stress = compressed_leaf_stress(E, T, W, L, P, theta_max)
    return CompressedLeafPivot(L=L, t=T, w=W, P=P, material=STEEL, transmission_ratio=1.0,
                               theta_max=theta_max, stiffness=K, max_stress=stress,
                               safety_factor=STEEL.yield_strength / stress)


def test_beam_column_stiffness_limits():
    # P = 0: E I / L; small P: E I / L - P L / 3 + O(P^2) (series of x cot x = 1 - x^2/3 - x^4/45
    # - 2 x^6 / 945: at x^2 = 1e-3 the x^6 term is 2e-12, round-off in tan ~1e-15)
    assert beam_column_rotational_stiffness(E, I, L, 0.0) == pytest.approx(EI_L, rel=1e-12)
    P = 1e-3 * E * I / L**2
    assert beam_column_rotational_stiffness(E, I, L, P) == pytest.approx(
        EI_L - P * L / 3 - EI_L * 1e-6 / 45, rel=1e-11)
    # zero at the cantilever buckling load (kL = pi/2), negative beyond it
    assert beam_column_rotational_stiffness(E, I, L, (math.pi / 2)**2 * E * I / L**2) \
        == pytest.approx(0.0, abs=1e-12 * EI_L)
    assert beam_column_rotational_stiffness(E, I, L, 4.0 * E * I / L**2) == pytest.approx(
        EI_L * 2.0 / math.tan(2.0), rel=1e-12)
    # tension stiffens: x coth x
    assert beam_column_rotational_stiffness(E, I, L, -4.0 * E * I / L**2) == pytest.approx(
        EI_L * 2.0 / math.tanh(2.0), rel=1e-12)
    # inverse and round trip
    for kL in (0.3, 1.0, math.pi / 2, 2.0, KL_DEFAULT, 3.0):
        assert kL_for_stiffness_factor(float(stiffness_factor(kL))) == pytest.approx(kL, rel=1e-10)
    K = -2.5 * EI_L
    P = preload_for_stiffness(K, E, I, L)
    assert beam_column_rotational_stiffness(E, I, L, P) == pytest.approx(K, rel=1e-10)
    assert bending_stress_factor(2.0) == pytest.approx(2.0 / math.sin(2.0))


def test_elastica_against_linear_theory_and_pure_bending():
    # small theta: the beam-column (1e-4 rad: cubic terms ~ theta^2 = 1e-8 relative)
    P = 4.0 * E * I / L**2
    e = compressed_leaf_elastica(E, I, L, P, 1e-4)
    assert e.moment / 1e-4 == pytest.approx(EI_L * 2.0 / math.tan(2.0), rel=1e-6)
    assert e.dy / 1e-4 == pytest.approx(math.tan(1.0) / 2.0 * L, rel=1e-6)  # tan(kL/2)/k
    assert e.clamp_curvature * L / 1e-4 == pytest.approx(2.0 / math.sin(2.0), rel=1e-6)
    assert e.stable
    # P = 0, large theta: a circular arc, M = E I theta / L, dy = L (1 - cos theta) / theta
    arc = compressed_leaf_elastica(E, I, L, 0.0, 1.0)
    assert arc.moment == pytest.approx(EI_L, rel=1e-8)
    assert arc.dy == pytest.approx(L * (1 - math.cos(1.0)), rel=1e-6)
    # Sturm comparison: P cos(phi) <= P < pi^2 E I / L^2, so every state with theta held is
    # stable, even next to the guided buckling load and at large rotation
    assert compressed_leaf_elastica(E, I, L, 0.99 * math.pi**2 * E * I / L**2, 0.5).stable


def test_fem_compressed_leaf_against_beam_column_and_elastica():
    # kL = 3 pi / 4: K = -2.36 E I / L.
    # Small angle: the continuum leaf differs from the Euler beam-column by shear (Engesser:
    # k^2 grows by P / (kappa G A) = (kL)^2 (t/L)^2 E / (12 kappa G) = 2e-4, moving K by
    # |f'(kL)| dkL = 0.15 % of E I / L) and by the clamps' Poisson boundary layers (0.3 %,
    # tests/studies/test_balancing_pivot_fem.py): asserted to 1 % of E I / L.
    # Large angle (0.2 rad): the same, plus SVK strain nonlinearity O(strain) = 3e-3: 1 % of
    # E I theta / L against the elastica.
    p = leaf(theta_max=0.2)
    check = negative_pivot_fem_check(p, fractions=(0.5, 1.0, -1.0), steps=4)
    assert check["stiffness_closed_Nm_per_rad"] == pytest.approx(
        EI_L * KL_DEFAULT / math.tan(KL_DEFAULT), rel=1e-12)
    assert abs(check["stiffness_error_over_EI_L"]) < 0.01
    theta = np.array(check["curve_theta_rad"])
    m_fem, m_ela = np.array(check["curve_moment_fem_Nm"]), np.array(check["curve_moment_elastica_Nm"])
    assert np.all(m_fem / theta < 0)  # negative stiffness achieved over the range
    assert np.all(np.abs(m_fem - m_ela) < 0.01 * EI_L * np.abs(theta))
    # same (stable, symmetric) branch: odd moment, sideways hub motion as the elastica's
    assert m_fem[1] == pytest.approx(-m_fem[2], rel=1e-4)
    dy_fem, dy_ela = np.array(check["curve_dy_fem_m"]), np.array(check["curve_dy_elastica_m"])
    assert np.all(np.abs(dy_fem - dy_ela) < 0.01 * np.abs(dy_ela))
    assert check["elastica_stable_all"] and check["step_cuts"] == 0
    # clamp stress: beam E t kappa / 2 + P / (w t) within 3 % (nodal projection at the clamp
    # corner, as for the uncompressed leaf), below yield
    assert check["stress_fem_peak_nodal_Pa"] / check["stress_elastica_Pa"] == pytest.approx(
        1.0, abs=0.03)
    assert check["safety_factor_fem"] > 1.0


def test_sizing_meets_stiffness_stress_and_buckling_margin():
    for K, N in ((-4.76, 4.0), (-4.06, 6.0), (-1.0, 1.0)):
        half = 0.9
        p = size_negative_pivot(K, (-half, 0.5 * half), STEEL, safety_factor=2.0,
                                transmission_ratio=N)
        assert p.stiffness_at_motor == pytest.approx(K, rel=1e-12)
        # the width solves the beam-column stiffness equation (round-off only)
        assert beam_column_rotational_stiffness(STEEL.E, p.I, p.L, p.P) == pytest.approx(
            K * N**2, rel=1e-9)
        assert p.kL == pytest.approx(KL_DEFAULT, rel=1e-9) and p.kL < math.pi
        assert p.theta_max == pytest.approx(half / N)
        # thickness rounded down: the stress can only fall below yield / 2
        assert p.max_stress <= STEEL.yield_strength / 2.0
        assert p.safety_factor >= 2.0
        assert p.t <= p.w <= 0.1


def test_quick_study_motors_2_and_4(tmp_path):
    from flexfem.studies.balancing.report import default_workspace

    summary = negative_pivot_study(tmp_path, quick=True, workspace=default_workspace(quick=True))
    assert (tmp_path / "balancing_negative_pivot.csv").exists()
    assert (tmp_path / "balancing_negative_pivot.png").stat().st_size > 10_000
    assert {r["motor"] for r in summary["rows"]} == {2, 4}  # the K < 0 motors of Table IV
    for r in summary["rows"]:
        assert r["K_motor_Nm_per_rad"] < 0 and r["fem_curve_moment_fem_Nm"][-1] < 0
        assert abs(r["fem_stiffness_error_over_EI_L"]) < 0.01
        assert r["fem_safety_factor_fem"] > 1.0
        # the leaf's softening over +-theta_max costs little of the ideal spring's reduction
        assert r["rms_reduction_leaf_fem_pct"] > 0.9 * r["rms_reduction_ideal_torsion_pct"]


def test_bad_input():
    with pytest.raises(ValueError, match="K = "):
        size_negative_pivot(4.0, (-0.5, 0.5), STEEL)
    with pytest.raises(ValueError, match="kL"):
        size_negative_pivot(-4.0, (-0.5, 0.5), STEEL, kL=1.0)
    with pytest.raises(ValueError, match="safety_factor"):
        size_negative_pivot(-4.0, (-0.5, 0.5), STEEL, safety_factor=0.5)
    with pytest.raises(ValueError, match="theta_range_rad"):
        size_negative_pivot(-4.0, (0.0, 0.0), STEEL)
    with pytest.raises(ValueError, match="no compressed leaf"):
        size_negative_pivot(-4000.0, (-1.0, 1.0), STEEL)
    with pytest.raises(ValueError, match="P = "):
        beam_column_rotational_stiffness(E, I, L, 1.01 * math.pi**2 * E * I / L**2)
    with pytest.raises(ValueError, match="L = "):
        beam_column_rotational_stiffness(E, I, -L, 0.0)
    with pytest.raises(ValueError, match="stiffness factor"):
        kL_for_stiffness_factor(1.5)
    with pytest.raises(ValueError, match="theta"):
        compressed_leaf_elastica(E, I, L, 0.0, 2.0)
    with pytest.raises(ValueError, match="P = "):
        compressed_leaf_elastica(E, I, L, -1.0, 0.1)
    with pytest.raises(ValueError, match="P = "):
        CompressedLeafPivot(**{**leaf().__dict__, "P": 1.1 * math.pi**2 * E * I / L**2})
    with pytest.raises(ValueError, match="t = "):
        CompressedLeafPivot(**{**leaf().__dict__, "t": 0.5 * L})
    with pytest.raises(ValueError, match="fractions"):
        negative_pivot_fem_check(leaf(), fractions=(1.5,))
    with pytest.raises(ValueError, match="steps"):
        negative_pivot_fem_check(leaf(), steps=0)
