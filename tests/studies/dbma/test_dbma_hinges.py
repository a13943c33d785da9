"""DBMA hinge profiles: geometry options, validation, closed forms, single-hinge FEM against
Paros-Weisbord, and the quick sensitivity study (coarse 2-D meshes)."""
import dataclasses
import math

import numpy as np
import pytest
from flexfem.fem import Fixed, Force, Model, PlaneStress, solve_static
from flexfem.geometry.dbma import drawing as dbma
from flexfem.geometry.dbma.drawing import DBMALayout, mesh_dbma, part_area
from flexfem.geometry.dbma.params import paper_design
from flexfem.geometry.hinge_profiles import (
    ARC_SEGMENT_ANGLE,
    mesh_hinge_specimen,
    profile_area,
)
from flexfem.studies.dbma import hinges as hs
from flexfem.studies.dbma.analysis import dbma_material
from flexfem.studies.dbma.enhanced import amplification_ratio_rigid_arm

P = paper_design()


def _area(mesh):
    m = mesh.mesh
    a, b, c = (m.p[:, m.t[i]] for i in range(3))
    return float(np.sum(0.5 * np.abs((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]))))


def _fail_gmsh(*args, **kwargs):
    raise AssertionError("gmsh must not be touched for invalid parameters")


def test_default_leaf_area_is_the_rectangle_formula():
    # the part as drawn before the profiles existed: input members a x 2 ll, pads, output
    # members ls x (ll - arm_gap), 8 arms e x c and 16 leaves l x b (all rectangles)
    lay = DBMALayout()
    assert lay.hinge_profile == "leaf"
    expected = (2 * P.a * 2 * P.ll + 2 * lay.pad_depth * lay.pad_height
                + 2 * P.ls * (P.ll - lay.arm_gap) + 8 * P.e * P.c + 16 * P.l * P.b)
    assert part_area(P) == pytest.approx(expected, rel=1e-12)
    # the fillet radius means nothing to a leaf
    assert part_area(P, DBMALayout(hinge_fillet_radius=1e-3)) == part_area(P)


@pytest.mark.parametrize("profile", ["filleted", "circular"])
def test_profiles_mesh_with_groups_and_area(profile):
    lay = DBMALayout(hinge_profile=profile)
    mesh = mesh_dbma(P, lay, dim=2, size_factor=2.83)
    for name in ("input", "input_a", "input_b", "output", "fixed"):
        assert len(mesh.facets(name)) > 0, name
    assert len(mesh.elements("hinges")) > 0
    # every hinge surface is in 'hinges': its area is 16 profiles (up to the chord error)
    hinge_area = float(np.sum(_element_areas(mesh)[mesh.elements("hinges")]))
    one = profile_area(profile, P.l, P.b, lay.hinge_fillet_radius)
    # arcs become chords of at most ARC_SEGMENT_ANGLE; each chord adds the segment
    # r^2 (a - sin a) / 2 of material (the void is the circle): over a hinge's arcs (one full
    # circle of radius r for the notch, of r_f for the fillets) at most pi r^2 (1 - sin a / a)
    r = P.l / 2 if profile == "circular" else lay.hinge_fillet_radius
    a = ARC_SEGMENT_ANGLE
    # (reached, to round-off, where every chord is the full angle: hence the 1e-6)
    excess = 16 * math.pi * r ** 2 * (1 - math.sin(a) / a) * (1 + 1e-6)
    assert 0 <= hinge_area - 16 * one <= excess
    assert 0 <= _area(mesh) - part_area(P, lay) <= excess


def _element_areas(mesh):
    m = mesh.mesh
    a, b, c = (m.p[:, m.t[i]] for i in range(3))
    return 0.5 * np.abs((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]))


@pytest.mark.parametrize("kwargs, word", [
    ({"hinge_profile": "elliptic"}, "hinge_profile"),
    ({"hinge_profile": None}, "hinge_profile"),
    ({"hinge_fillet_radius": 0.0}, "hinge_fillet_radius"),
    ({"hinge_fillet_radius": -1e-3}, "hinge_fillet_radius"),
    ({"hinge_fillet_radius": float("nan")}, "hinge_fillet_radius"),
])
def test_invalid_profile_options_raise(kwargs, word):
    with pytest.raises(ValueError, match=word):
        DBMALayout(**kwargs)


@pytest.mark.parametrize("params, layout, word", [
    # fillets longer than half the hinge (l / 2 = 2.205 mm)
    (P, DBMALayout(hinge_profile="filleted", hinge_fillet_radius=2.3e-3), "hinge_fillet_radius"),
    # the notch's ends (b + l = 5.01 mm tall) offset by h / 2 leave the arm: h + b + l > c
    (dataclasses.replace(P, h=5.5e-3), DBMALayout(hinge_profile="circular"), "circular"),
])
def test_profiles_that_do_not_fit_raise_before_gmsh(monkeypatch, params, layout, word):
    monkeypatch.setattr(dbma, "gmsh_session", _fail_gmsh)
    with pytest.raises(ValueError, match=word):
        mesh_dbma(params, layout)


def test_paros_weisbord_closed_form():
    # the full equation is the closed form of the Euler-Bernoulli integral (midpoint rule on
    # 2000 cells: error ~1e-6 here); the thin-notch form is its limit, first correction O(b/r)
    c = hs.beam_compliances(P, "circular")["rotation"]
    assert hs.circular_notch_rotational_compliance(P.E, P.d, P.l, P.b) == pytest.approx(c, rel=1e-4)
    thin = dict(E=1.0, d=1.0, l=2.0, b=0.01)   # b / r = 0.01
    assert (hs.circular_notch_rotational_compliance_simplified(**thin)
            == pytest.approx(hs.circular_notch_rotational_compliance(**thin), rel=0.01))
    # the leaf: l / (E I) both ways, and the rigid-arm ratio is the existing closed form
    leaf = hs.beam_compliances(P, "leaf")
    assert leaf["rotation"] == pytest.approx(hs.leaf_rotational_compliance(P.E, P.d, P.l, P.b),
                                             rel=1e-12)
    assert (hs.amplification_ratio_rigid_arm(P, leaf["axial"], leaf["rotation"])
            == pytest.approx(amplification_ratio_rigid_arm(P), rel=1e-12))


def _specimen_compliance(profile):
    """Rotation per moment (rad/(N m)) of one hinge between two 10 mm blocks, 2-D plane
    stress of thickness d: a pure couple F H from opposite shear forces on the right block's
    top and bottom faces; C = 2 U / M^2 (U the strain energy)."""
    mesh = mesh_hinge_specimen(P.l, P.b, profile, size_factor=1.0)
    model = Model(mesh, dbma_material(P), PlaneStress(P.d), order=2)
    force, height = 10.0, 10e-3
    result = solve_static(model, [Fixed("fixed")],
                          [Force("top", (-force, 0.0)), Force("bottom", (force, 0.0))])
    return 2 * result.strain_energy / (force * height) ** 2


def test_circular_notch_is_stiffer_in_rotation_than_the_leaf():
    leaf, notch = _specimen_compliance("leaf"), _specimen_compliance("circular")
    leaf_beam = hs.leaf_rotational_compliance(P.E, P.d, P.l, P.b)
    notch_pw = hs.circular_notch_rotational_compliance(P.E, P.d, P.l, P.b)
    # beam theory holds sections plane, a kinematic restriction: it is stiffer than the 2-D
    # solution, so FEM / beam >= 1 (less a little discretisation stiffness, < 1 % here).
    # Leaf: the root compliance where the leaf enters each block adds ~0.44 b of length per
    # root (O'Donnell, J. Appl. Mech. 27 (1960) 461; plane stress): 1 + 0.88 b / l = 1.12.
    # Notch: the plane-section error grows with b / r (0.27 here); Paros-Weisbord's full
    # equation is reported stiffer than 2-D FEM by some percent at this b / r. Both are
    # bounded here by 1 + twice the leaf's root correction.
    upper = 1 + 2 * 0.88 * P.b / P.l
    assert 0.99 < leaf / leaf_beam < upper
    assert 0.99 < notch / notch_pw < upper
    # the claim of the study: at the same l and b the notch is ~3.4x stiffer in rotation;
    # FEM ratio = PW ratio (0.297) times the ratio of the two corrections above (each in
    # [0.99, upper]), so within a factor upper / 0.99 of it
    predicted = notch_pw / leaf_beam
    assert notch < leaf
    assert predicted * 0.99 / upper < notch / leaf < predicted * upper / 0.99


def test_quick_study_writes_files_and_moves_r_down(tmp_path, section_contract):
    out = hs.hinge_profile_study(tmp_path, quick=True)
    assert {r["profile"] for r in out["rows"]} == {"leaf", "filleted", "circular"}
    section_contract(tmp_path, out)
    leaf, filleted, circ, coarse = out["rows"]
    # closed form: stiffer hinges in rotation (more than axially) lower R and raise k_in
    closed = {r["profile"]: r for r in out["closed_form"]}
    assert closed["circular"]["R_rigid_arm"] < closed["leaf"]["R_rigid_arm"]
    assert circ["R_fem_per_side"] < filleted["R_fem_per_side"] < leaf["R_fem_per_side"]
    assert circ["k_in_N_per_m"] > filleted["k_in_N_per_m"] > leaf["k_in_N_per_m"]
    # stiffer hinges, same masses: the working mode rises
    assert circ["fn_working_Hz"] > leaf["fn_working_Hz"]
    # mesh check: R of the leaf converges to 0.3 % from size_factor 2.83 (docs/dbma.md);
    # the notch has no re-entrant corner, so 1 % between the two meshes is a loose bound
    assert circ["R_fem_per_side"] == pytest.approx(coarse["R_fem_per_side"], rel=0.01)
