"""The elastic-beam (compliance) model of the DBMA against limits derived by hand."""
import dataclasses

import numpy as np
import pytest
from flexfem.geometry.dbma.params import paper_design
from flexfem.studies.dbma import enhanced as en

# Rigid arms are exact constraints; axially rigid hinges are RIGID = 1e6 times stiffer, so the
# kinematic limit is met to ~1e-6 relative; 1e-5 leaves room for round-off in the solve.
LIMIT_TOL = 1e-5


@pytest.fixture(scope="module")
def design():
    return paper_design()


def test_frame_element_is_symmetric_with_three_rigid_body_modes():
    k = en.frame_element_stiffness(0.0, 0.0, 3e-3, 4e-3, 200e9, 1e-5, 1e-11, G=80e9)
    assert np.allclose(k, k.T, rtol=0, atol=1e-9 * np.abs(k).max())
    eigenvalues = np.linalg.eigvalsh(k)
    assert np.sum(np.abs(eigenvalues) < 1e-9 * eigenvalues.max()) == 3


def test_cantilever_tip_deflection_euler_bernoulli():
    # one element is exact for a tip load: PL^3 / (3 E I)
    E, A, I, L, P = 200e9, 1e-5, 1e-11, 0.05, 1.0
    k = en.frame_element_stiffness(0.0, 0.0, L, 0.0, E, A, I)
    free = [3, 4, 5]
    u = np.linalg.solve(k[np.ix_(free, free)], [0.0, P, 0.0])
    assert u[1] == pytest.approx(P * L**3 / (3 * E * I), rel=1e-12)


def test_rigid_arm_and_axially_rigid_hinges_recover_the_kinematic_ratio(design):
    # pivots at the hinge centres: r = (e + l) / h (derivation in docs/dbma-analytical.md)
    for h in (0.8e-3, 2.6e-3, 5e-3):
        p = dataclasses.replace(design, h=h)
        r = en.row_amplification_ratio(p, rigid_arm=True, axially_rigid_hinges=True)
        assert 2 * r == pytest.approx(en.amplification_ratio_kinematic(p), rel=LIMIT_TOL)


@pytest.mark.parametrize("h, b", [(0.3e-3, 0.6e-3), (2.6e-3, 0.6e-3), (2.6e-3, 1.2e-3), (6e-3, 0.4e-3)])
def test_rigid_arm_frame_matches_closed_form(design, h, b):
    p = dataclasses.replace(design, h=h, b=b)
    assert en.amplification_ratio_enhanced(p, rigid_arm=True) == pytest.approx(
        en.amplification_ratio_rigid_arm(p), rel=LIMIT_TOL)


def test_ratio_vanishes_linearly_as_h_goes_to_zero(design):
    # closed form (e + l) h / (h^2 + b^2/3) per row -> 6 (e + l) h / b^2 for R when h << b,
    # relative error h^2 / (b^2/3) <= 1e-5 at h = 1e-6 m
    slope = 6 * (design.e + design.l) / design.b**2
    slopes = []
    for h in (1e-7, 1e-6):
        p = dataclasses.replace(design, h=h)
        assert en.amplification_ratio_rigid_arm(p) / h == pytest.approx(slope, rel=1e-5)
        slopes.append(en.amplification_ratio_enhanced(p) / h)
    # the elastic model is linear in h there too (next term ~ h^2/b^2 ~ 1e-5); the stroke is
    # then almost all axial, and the arm's axial compliance e/(E d c) is in series with the
    # hinges' 2 l/(E d b): the slope drops by that share (13.5 % here). Arm bending and shear
    # enter at (b/c)^3 ~ 2e-4 relative, hence the 1e-3 tolerance.
    assert slopes[0] == pytest.approx(slopes[1], rel=1e-4)
    hinges, arm = 2 * design.l / design.b, design.e / design.c
    assert slopes[0] == pytest.approx(slope * hinges / (hinges + arm), rel=1e-3)
    assert en.amplification_ratio_enhanced(dataclasses.replace(design, h=0.0)) == pytest.approx(0.0, abs=1e-9)


def test_thin_hinges_tend_to_the_kinematic_ratio(design):
    # (e + l) h / (h^2 + b^2/3): relative gap b^2 / (3 h^2) -> 0 as b -> 0
    p = dataclasses.replace(design, b=0.01e-3)
    gap = p.b**2 / (3 * p.h**2)
    assert en.amplification_ratio_enhanced(p, rigid_arm=True) == pytest.approx(
        en.amplification_ratio_kinematic(p) / (1 + gap), rel=LIMIT_TOL)


def test_elastic_arm_lowers_the_ratio_but_only_a_little(design):
    # a 10 mm x 19.9 mm arm is ~ (c/b)^3 = 4600 times stiffer in bending than a hinge
    rigid = en.amplification_ratio_enhanced(design, rigid_arm=True)
    elastic = en.amplification_ratio_enhanced(design)
    assert elastic < rigid
    assert elastic == pytest.approx(rigid, rel=0.01)


def test_ratio_is_scale_free(design):
    lengths = ("c", "a", "d", "l", "e", "ls", "ll", "b", "h")
    scaled = dataclasses.replace(design, **{n: 0.1 * getattr(design, n) for n in lengths})
    assert en.amplification_ratio_enhanced(scaled) == pytest.approx(
        en.amplification_ratio_enhanced(design), rel=1e-9)


def test_free_input_output_stiffness_is_hinge_bending_only(design):
    # no axial force: M(x) = V x from the arm's centre (antisymmetry), so per quarter
    # uy = 2 V [(e/2 + l)^3 - (e/2)^3] / (3 E I); two rows in series halve k_q
    EI = design.E * design.d * design.b**3 / 12
    half = design.e / 2
    k_q = 3 * EI / (2 * ((half + design.l) ** 3 - half**3))
    for h in (0.5e-3, 2.6e-3):
        p = dataclasses.replace(design, h=h)
        assert en.output_stiffness_enhanced(p, rigid_arm=True, input_blocked=False) == pytest.approx(
            k_q / 2, rel=LIMIT_TOL)


def test_blocking_the_input_stiffens_the_output(design):
    blocked = en.output_stiffness_enhanced(design)
    free = en.output_stiffness_enhanced(design, input_blocked=False)
    assert blocked > 10 * free


def test_input_stiffness_matches_the_rigid_arm_derivation(design):
    # rigid arm, output free: delta = N l (2/(E A) + h^2/(2 E I)) per quarter (docs), a row
    # has N/delta and the two rows share the stroke
    EA = design.E * design.d * design.b
    EI = design.E * design.d * design.b**3 / 12
    k_rigid = 2 / (design.l * (2 / EA + design.h**2 / (2 * EI)))
    assert en.input_stiffness_enhanced(design, rigid_arm=True) == pytest.approx(k_rigid, rel=1e-9)
    # the elastic arm adds compliance in series, but a little: (b/c)^3-small
    assert 0.99 * k_rigid < en.input_stiffness_enhanced(design) < k_rigid


def test_enhanced_metrics(design):
    metrics = en.enhanced_metrics(design)
    assert metrics["R_kinematic"] > metrics["R_rigid_arm"] > metrics["R_enhanced"] > 0
    assert en.enhanced_metrics(dataclasses.replace(design, h=0.0))["R_kinematic"] == float("inf")
    with pytest.raises(ValueError, match="h = 0.0"):
        en.amplification_ratio_kinematic(dataclasses.replace(design, h=0.0))


def test_post_chain_with_a_guided_post_shares_the_stroke(design):
    # post without rotation: both arms carry the same axial force, each takes half the stroke
    # and lifts by r delta/2, so the chain gives exactly the row ratio r = R_enhanced / 2
    guided = en.amplification_ratio_post_chain(design, post_rotation_blocked=True)
    assert guided == pytest.approx(en.row_amplification_ratio(design), rel=1e-9)


def test_post_chain_with_a_free_post_is_a_lever_that_loses_the_stroke(design):
    # a free post tilts instead: arm 1 slides out with the input block and the post turns
    # about its top hinge, which only bends hinges (no axial stretch, no arm rotation), so
    # almost no lift is left
    free = en.amplification_ratio_post_chain(design)
    assert abs(free) < 0.01 * en.amplification_ratio_enhanced(design)
