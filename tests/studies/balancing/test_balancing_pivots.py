"""Cross-spring flexure pivots sized by beam theory to replace the torsion springs."""
import pytest
from flexfem.fem import Material, material
from flexfem.studies.balancing.pivots import (
    FlexurePivot,
    cross_spring_stiffness,
    leaf_bending_stress,
    negative_stiffness_preload,
    pivot_stiffness_beam_theory,
    size_flexure_pivot,
)

STEEL = material("spring_steel_aisi1095")


def test_the_pivot_materials_come_from_the_one_material_library_in_si():
    assert STEEL.E == pytest.approx(205e9) and STEEL.yield_strength == pytest.approx(1.3e9)
    assert "AISI 1095" in STEEL.source
    with pytest.raises(ValueError, match="unobtainium"):
        material("unobtainium")


def test_beam_formulas_by_hand():
    """E t theta / (2 L) and n E w t^3 / (12 L), evaluated by hand."""
    assert leaf_bending_stress(200e9, 1e-3, 0.1, 0.05) == pytest.approx(200e6, rel=1e-14)
    assert cross_spring_stiffness(200e9, 0.02, 1e-3, 0.05, 2) == pytest.approx(
        2 * 200e9 * 0.02 * 1e-9 / 12 / 0.05, rel=1e-14)


@pytest.mark.parametrize("K, N", [(4.23, 1.0), (4.23, 3.0), (0.68, 4.0), (40.0, 2.0)])
def test_sized_pivot_meets_stiffness_and_stress(K, N):
    """Width solves the stiffness equation exactly (only round-off: 1e-12); the thickness is
    rounded down to 10 um, so the stress can only fall below yield / safety factor."""
    theta = (-0.25 * N, 0.2 * N)
    pivot = size_flexure_pivot(K, theta, STEEL, safety_factor=2.0, transmission_ratio=N)
    assert pivot_stiffness_beam_theory(pivot) == pytest.approx(K * N**2, rel=1e-12)
    assert pivot.stiffness_at_motor == pytest.approx(K, rel=1e-12)
    assert pivot.theta_max == pytest.approx(0.25)
    assert pivot.max_stress == pytest.approx(leaf_bending_stress(STEEL.E, pivot.t, 0.25, pivot.L))
    assert pivot.max_stress <= STEEL.yield_strength / 2.0
    assert pivot.safety_factor >= 2.0
    assert pivot.t <= pivot.w <= 0.1


def test_negative_or_impossible_stiffness_raises():
    with pytest.raises(ValueError, match="K = -4.55"):
        size_flexure_pivot(-4.55, (-0.2, 0.2), STEEL)
    with pytest.raises(ValueError, match="no cross-spring pivot"):
        size_flexure_pivot(4.23, (-3.0, 3.0), STEEL)          # +-170 deg, no transmission
    with pytest.raises(ValueError, match="safety_factor"):
        size_flexure_pivot(4.23, (-0.2, 0.2), STEEL, safety_factor=0.5)


def test_validation_and_negative_stiffness_preload():
    with pytest.raises(ValueError, match="E = 0"):
        Material("x", 0.0, 0.3, 7850.0, 1e6)
    good = size_flexure_pivot(4.23, (-0.2, 0.2), STEEL)
    with pytest.raises(ValueError, match="n_leaves"):
        FlexurePivot(**{**good.__dict__, "n_leaves": 0})
    assert negative_stiffness_preload(-4.55, 0.1) == pytest.approx(45.5)
    with pytest.raises(ValueError, match="must be < 0"):
        negative_stiffness_preload(4.55, 0.1)
