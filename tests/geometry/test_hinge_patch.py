"""The notch hinge's 2-D correction of its beam (flexfem.geometry.hinge_patch)."""
import math

import numpy as np
import pytest

from flexfem.fem import Fixed as FEFixed, Material, Model, PlaneStress
from flexfem.fem.beam import BeamModel, Fixed, Section, beam_chain
from flexfem.fem.beam.compliance import compliance
from flexfem.fem.compliance import compliance_matrix
from flexfem.geometry.beam_layout import profile_beam
from flexfem.geometry.hinge_patch import (NotchFactors, _patch_mesh, notch_factors,
                                          patch_factors, tabulated)
from flexfem.geometry.hinge_profiles import add_hinge_surface, profile_thickness

STEEL = Material("steel", E=200e9, nu=0.3, rho=7800.0)


@pytest.mark.parametrize("args, match", [
    (("leaf", 2e-3, 1e-3, 0.5e-3, 0.3), "no notch"),
    (("elliptic", 2e-3, 1e-3, 0.5e-3, 0.3), "hinge_profile"),
    (("circular", -2e-3, 1e-3, 0.5e-3, 0.3), "l = "),
    (("circular", 2e-3, 0.0, 0.5e-3, 0.3), "b = "),
    (("circular", 2e-3, 1e-3, 0.5e-3, 0.5), "nu = "),
    (("filleted", 2e-3, 1e-3, 1e-3, 0.3), "fillet_radius"),
])
def test_bad_input_names_the_problem(args, match):
    with pytest.raises(ValueError, match=match):
        notch_factors(*args)


def test_the_corrected_beam_reproduces_the_notch_with_its_stubs():
    """A notch at t/R = 1 with a stub of its end height at each end (the patch): its beam,
    the stubs as beams, with the factors has the 2-D patch's end compliance (computed here
    again) in rotation, extension and their coupling to 2e-4, sideways within 0.5 % (shear is
    under 2 % of it: its factor stays 1), where the bare beam is 19 % stiff in rotation and
    12 % in extension (with the stubs' own compliance)."""
    b, l = 1e-3, 2e-3
    h = b + l  # the notch's end height, b + 2 R
    f = patch_factors("circular", l, b, b, 0.3)
    thickness = lambda s: profile_thickness("circular", l, b, b, s)

    def drawn(occ):
        stubs = [(2, occ.addRectangle(-h, -h / 2, 0.0, h, h)),
                 (2, occ.addRectangle(l, -h / 2, 0.0, h, h))]
        fused, _ = occ.fuse([(2, add_hinge_surface(occ, 0.0, l, 0.0, b, "circular", b))],
                            stubs)
        return [tag for _, tag in fused]

    patch = Model(_patch_mesh(drawn, l, (-h, l + h), thickness, l / 2, b, 12), STEEL,
                  PlaneStress(2e-3), order=2)
    C2 = compliance_matrix(patch, [FEFixed("root")], "tip", point=(l + h, 0.0)).matrix
    out = {}
    for name, factors in (("bare", None), ("corrected", f)):
        notch = profile_beam((0, 0), (l, 0), thickness, 2e-3, (), 40, 0.0, vectorized=True,
                             factors=factors)
        mesh = beam_chain([(-h, 0), (0, 0)], Section.rect(2e-3, h), 4).join(notch, 1e-12)
        mesh = mesh.join(beam_chain([(l, 0), (l + h, 0)], Section.rect(2e-3, h), 4), 1e-12)
        model = BeamModel(mesh.nodes, mesh.elements, mesh.sections, STEEL, shear=True)
        out[name] = compliance(model, [Fixed(mesh.node_at((-h, 0)))], mesh.node_at((l + h, 0)))
    for i, j in ((0, 0), (2, 2), (1, 2)):
        assert out["corrected"][i, j] == pytest.approx(C2[i, j], rel=2e-4), (i, j)
    assert out["corrected"][1, 1] == pytest.approx(C2[1, 1], rel=5e-3)
    assert out["bare"][2, 2] / C2[2, 2] - 1 == pytest.approx(-0.19, abs=0.02)
    assert out["bare"][0, 0] / C2[0, 0] - 1 == pytest.approx(-0.12, abs=0.02)
    assert f.shear == 1.0 and f.kt_bending > 1.0 and f.kt_tension > f.kt_bending


def test_thin_notches_tend_to_beam_theory():
    """As t/R -> 0 the notch's neck is a slender strip and Paros-Weisbord's plane sections
    hold: every factor tends to 1 (the table's monotone approach) and the deficit grows
    with t/R up to about t/R = 1."""
    t = [0.02, 0.05, 0.1, 0.2, 0.4, 0.8]
    f = [tabulated(x, 0.3) for x in t]
    bending = np.array([x.bending for x in f])
    kt = np.array([x.kt_bending for x in f])
    assert 0.985 < bending[0] < 1.0 and abs(kt[0] - 1) < 0.01
    assert np.all(np.diff(bending) < 0) and np.all(np.diff(kt) > 0)
    assert bending[-1] < 0.9


def test_the_table_is_used_in_its_range_and_computed_outside():
    inside = notch_factors("circular", 2e-3 / 0.3, 1e-3, 0.5e-3, 0.3)
    assert inside == tabulated(0.3, 0.3)
    assert tabulated(3.0, 0.3) is None and tabulated(0.3, 0.45) is None
    outside = notch_factors("circular", 2e-3 / 3.0, 1e-3, 0.5e-3, 0.3)  # t/R = 3: computed
    assert isinstance(outside, NotchFactors) and 0.6 < outside.bending < 0.8
    filleted = notch_factors("filleted", 4.41e-3, 0.6e-3, 0.3e-3, 0.3)
    assert 0.95 < filleted.bending < 1.0 and math.isnan(filleted.kt_bending)


@pytest.mark.slow
@pytest.mark.parametrize("t_over_r, nu", [(0.2, 0.3), (1.1, 0.25)])
def test_the_table_is_the_computation(t_over_r, nu):
    """A grid point of data/notch_factors.toml recomputed (24 triangles across, as
    scripts/notch_factor_table.py)."""
    b = 1e-3
    computed = patch_factors("circular", 2 * b / t_over_r, b, b, nu, neck_elements=24)
    table = tabulated(t_over_r, nu)
    for name in NotchFactors.__dataclass_fields__:
        assert getattr(table, name) == pytest.approx(getattr(computed, name), rel=1e-6), name


@pytest.mark.slow
@pytest.mark.parametrize("t_over_r, nu", [(0.035, 0.3), (0.33, 0.27), (0.95, 0.33)])
def test_the_table_interpolates_between_its_points(t_over_r, nu):
    """Off the grid (in t/R and nu) the interpolation is within 0.2 % of the computation
    (the shear factor 0.5 %: where it is blended in, at 2-8 % of the deflection, its kink
    costs 0.2 %, or 0.01 % of the compliance); the mesh: 12 triangles across against 24
    within 0.5 %."""
    b = 1e-3
    fine = patch_factors("circular", 2 * b / t_over_r, b, b, nu, neck_elements=24)
    coarse = patch_factors("circular", 2 * b / t_over_r, b, b, nu, neck_elements=12)
    table = tabulated(t_over_r, nu)
    for name in NotchFactors.__dataclass_fields__:
        rel = 5e-3 if name == "shear" else 2e-3
        assert getattr(table, name) == pytest.approx(getattr(fine, name), rel=rel), name
        rel = 1e-2 if name.startswith("kt") else 5e-3
        assert getattr(coarse, name) == pytest.approx(getattr(fine, name), rel=rel), name


def test_a_sampled_profile_gives_the_exact_arcs_factors():
    """profile_factors draws any profile through 257 samples (a model file's notch); for a
    circular notch at t/R = 0.4 it gives the exact arcs' factors (patch_factors) within 3e-4
    (measured 5e-5) and their K_t within 0.5 % (measured 0.24 %); for a filleted leaf its
    stiffness factors."""
    from flexfem.geometry.hinge_patch import has_notch, profile_factors

    b, l = 1e-3, 5e-3
    thickness = lambda s: float(profile_thickness("circular", l, b, b, s))
    assert has_notch(thickness, l)
    sampled = profile_factors(thickness, l, 0.3)
    exact = patch_factors("circular", l, b, b, 0.3)
    for name in ("bending", "shear", "axial"):
        assert getattr(sampled, name) == pytest.approx(getattr(exact, name), rel=3e-4), name
    for name in ("kt_bending", "kt_tension"):
        assert getattr(sampled, name) == pytest.approx(getattr(exact, name), rel=5e-3), name
    with pytest.raises(ValueError, match="finite and > 0"):
        profile_factors(lambda s: b - s, l, 0.3)
    filleted = lambda s: float(profile_thickness("filleted", 4.41e-3, 0.6e-3, 0.5e-3, s))
    sampled = profile_factors(filleted, 4.41e-3, 0.3)  # measured within 1.1e-4
    exact = patch_factors("filleted", 4.41e-3, 0.6e-3, 0.5e-3, 0.3)
    for name in ("bending", "shear", "axial"):
        assert getattr(sampled, name) == pytest.approx(getattr(exact, name), rel=3e-4), name
    assert math.isnan(sampled.kt_bending)  # a flat neck: the peak is at the fillets


@pytest.mark.parametrize("profile, expected", [
    (lambda s: 1e-3, False),                                         # a leaf
    (lambda s: 1e-3 * (1 + s / 5e-3), False),                        # a taper
    (lambda s: float(profile_thickness("filleted", 5e-3, 1e-3, 1e-3, s)), True),   # fillets
    (lambda s: float(profile_thickness("filleted", 5e-3, 1e-3, 0.2e-3, s)), False),  # shallow
    (lambda s: float(profile_thickness("circular", 5e-3, 1e-3, 1e-3, s)), True),
    (lambda s: 1e-3 * (1 + 4 * (s / 5e-3 - 0.5) ** 2), True),       # a parabolic notch
])
def test_what_is_a_notch(profile, expected):
    from flexfem.geometry.hinge_patch import has_notch

    assert has_notch(profile, 5e-3) is expected
