"""Peak stress of filleted hinges from the beam model: Roark's shoulder-fillet K_t
(data/stress_concentration.toml) checked on one filleted hinge against the 2-D continuum over
r/d and D/d, then on the DBMA (docs/beam_validation_dbma.md, "DBMA: peak stress at the fillets")."""
import dataclasses

import numpy as np
import pytest
from flexfem.fem import Fixed as FEFixed, Force, Material, Model, PlaneStress, solve_static
from flexfem.fem.beam import BeamModel, NodalLoad, Section, beam_chain, solve_beam_static
from flexfem.fem.beam.supports import NodeFixed
from flexfem.reduced.layout import profile_beam
from flexfem.geometry.hinge_profiles import mesh_hinge_specimen, profile_thickness
from flexfem.studies.dbma.beam_stress import filleted_peak_stress, shoulder_fillet_kt

MM = 1e-3
STEEL = Material("steel", E=200e9, nu=0.3, rho=7800.0)
W, L, LB, R = 5 * MM, 4.41 * MM, 5 * MM, 0.5 * MM  # out-of-plane width, hinge, block, fillet


def test_kt_rejects_what_the_fit_does_not_cover():
    with pytest.raises(ValueError, match="h / r"):
        shoulder_fillet_kt(1 * MM, 1.05 * MM, 0.5 * MM, "bending")  # h / r = 0.05
    with pytest.raises(ValueError, match="load"):
        shoulder_fillet_kt(1 * MM, 5 * MM, 0.5 * MM, "torsion")
    with pytest.raises(ValueError, match="r = "):
        shoulder_fillet_kt(1 * MM, 5 * MM, 0.0, "bending")


def test_kt_of_a_deep_shoulder_is_taken_at_the_end_of_the_fit():
    """h / r > 20: the fit is evaluated at h / r = 20 (same r, d)."""
    d, r = 0.6 * MM, 0.1 * MM
    deep = shoulder_fillet_kt(d, d + 2 * 40 * r, r, "bending")
    assert deep == shoulder_fillet_kt(d, d + 2 * 20 * r, r, "bending")
    assert deep > shoulder_fillet_kt(d, d + 2 * 2 * r, r, "bending") > 1.0


def _continuum_peaks(b, H, size_factor):
    """Peak von Mises over nominal stress (bending under a pure couple, tension) of one
    filleted hinge (l = 4.41 mm, r = 0.5 mm) between blocks H tall, 2-D plane stress."""
    mesh = mesh_hinge_specimen(L, b, "filleted", R, H, LB, 4, size_factor)
    model = Model(mesh, STEEL, PlaneStress(W), order=2)
    M, P = 0.5, 100.0
    couple = solve_static(model, [FEFixed("fixed")],
                          [Force("top", (M / H, 0.0)), Force("bottom", (-M / H, 0.0))])
    pull = solve_static(model, [FEFixed("fixed")], [Force("tip", (P, 0.0))])
    return couple.max_von_mises / (6 * M / (W * b * b)), pull.max_von_mises / (P / (W * b))


def _beam_peaks(b, H):
    """The same specimen as a beam model (the filleted profile, Timoshenko blocks): the peak
    of :func:`filleted_peak_stress` over the nominal stress, under the couple and the pull."""
    fn = lambda s: profile_thickness("filleted", L, b, R, s)
    hinge = profile_beam((0.0, 0.0), (L, 0.0), fn, W, (R, L - R), 40, blocks=(H, H),
                         vectorized=True)
    a, z = hinge.nodes[hinge.point_nodes[0]], hinge.nodes[hinge.point_nodes[1]]
    mesh = (beam_chain([(-LB, 0.0), tuple(a)], Section.rect(W, H), 4).join(hinge, tol=1e-12)
            .join(beam_chain([tuple(z), (L + LB, 0.0)], Section.rect(W, H), 4), tol=1e-12))
    model = BeamModel(mesh.nodes, mesh.elements, mesh.sections, STEEL, shear=True)
    tip, root = mesh.node_at((L + LB, 0.0)), mesh.node_at((-LB, 0.0))
    kt_t = shoulder_fillet_kt(b, H, R, "tension")
    kt_b = shoulder_fillet_kt(b, H, R, "bending")
    M, P = 0.5, 100.0
    out = []
    for load, nominal in ((NodalLoad(tip, m=M), 6 * M / (W * b * b)),
                          (NodalLoad(tip, fx=P), P / (W * b))):
        state = solve_beam_static(model, [NodeFixed(root)], [load])
        out.append(filleted_peak_stress(model, state, b, kt_t, kt_b)[0] / nominal)
    return out, (kt_b, kt_t)


def test_beam_peak_is_kt_times_the_nominal_stress():
    """Under a couple / a pull the beam's straight part carries exactly 6 M / (w b^2) /
    P / (w b): the peak is K_t times that (the K_t of the load, the other term zero)."""
    (bend, pull), (kt_b, kt_t) = _beam_peaks(0.6 * MM, 10 * MM)
    assert bend == pytest.approx(kt_b, rel=1e-6)
    assert pull == pytest.approx(kt_t, rel=1e-6)


def test_bending_kt_against_the_continuum_on_the_dbma_hinge():
    """b = 0.6 mm, r/d = 0.83, D/d = 16.7 (the DBMA's hinge): continuum 1.13 (size_factor
    0.5; 1.16 at 0.25) against the fit's 1.154."""
    bend, _ = _continuum_peaks(0.6 * MM, 10 * MM, 0.5)
    assert bend == pytest.approx(shoulder_fillet_kt(0.6 * MM, 10 * MM, R, "bending"), rel=0.03)


@pytest.mark.slow
@pytest.mark.parametrize("b", [0.3 * MM, 0.6 * MM, 1.0 * MM])
@pytest.mark.parametrize("H", [3 * MM, 10 * MM])
def test_kt_against_the_continuum_over_r_over_d_and_d_over_d(b, H):
    """r/d = 0.5-1.7, D/d = 3-33: in bending the fit is within 4 % of the continuum
    (size_factor 0.5); in tension it is high by up to 12 % (conservative), never low."""
    bend, pull = _continuum_peaks(b, H, 0.5)
    assert shoulder_fillet_kt(b, H, R, "bending") == pytest.approx(bend, rel=0.04)
    assert 1.0 <= shoulder_fillet_kt(b, H, R, "tension") / pull <= 1.12


def _tension_peak(d, D, r, size_factor):
    """Peak von Mises over P / (w d) of a flat bar d wide between shoulders D wide with
    fillets of radius r, pulled (2-D plane stress; 5 mm between the fillets)."""
    mesh = mesh_hinge_specimen(5 * MM, d, "filleted", r, D, LB, 16, size_factor)
    model = Model(mesh, STEEL, PlaneStress(W), order=2)
    pull = solve_static(model, [FEFixed("fixed")], [Force("tip", (100.0, 0.0))])
    return pull.max_von_mises / (100.0 / (W * d))


@pytest.mark.slow
@pytest.mark.parametrize("D_over_d, r_over_d, low, high", [
    (2.0, 0.2, 0.0, 0.04), (2.0, 0.3, 0.0, 0.04), (5.0, 0.5, 0.04, 0.12)])
def test_tension_kt_excess_grows_with_the_shoulder_depth(D_over_d, r_over_d, low, high):
    """Why the tension fit reads high on the DBMA's hinges: on ordinary shoulders (D/d = 2,
    r/d = 0.2-0.3) it is +1.7 and +2.2 % above the continuum (size_factor 0.5; 0.25 moves
    the continuum by < 1.3 %), +8.6 % on a deep one (D/d = 5, r/d = 0.5), where the DBMA's
    hinges (D/d 5-33) sit; in bending it holds on both (above)."""
    d = 1 * MM
    peak = _tension_peak(d, D_over_d * d, r_over_d * d, 0.5)
    excess = shoulder_fillet_kt(d, D_over_d * d, r_over_d * d, "tension") / peak - 1
    assert low <= excess <= high


FILLETED_DESIGNS = [{}, {"b": 0.3 * MM, "l": 6 * MM}, {"e": 30 * MM, "b": 1.0 * MM},
                    {"a": 7 * MM}, {"h": 1.2 * MM}]


@pytest.mark.slow
@pytest.mark.parametrize("params", FILLETED_DESIGNS)
def test_dbma_fillet_stress_against_the_continuum(params):
    """The DBMA with filleted hinges (r_f = 0.5 mm) under the actuator's 100 N: the beam's
    peak with K_t within 10 % of the continuum's peak von Mises (size_factor 1), and closer
    than the nominal stress (11-23 % low on these designs); R and k_in within 3 % (measured
    within 1.0 %: each hinge corrected by its own 2-D model, reduced/hinge_patch.py)."""
    from flexfem.geometry.dbma.drawing import DBMALayout
    from flexfem.geometry.dbma.params import paper_design
    from flexfem.studies.dbma import analysis as fem
    from flexfem.studies.dbma.beam import analyze_dbma_beam

    p = dataclasses.replace(paper_design(), **params)
    layout = DBMALayout(hinge_profile="filleted")
    static = fem.static_response(fem.build_model(p, layout, 2, 1.0), 100.0)
    cont = static["max_von_mises"]
    beam = analyze_dbma_beam(p, layout, n_modes=0)
    for key in ("R_fem", "k_in"):
        assert beam[key] == pytest.approx(static[key], rel=0.03), key
    err, nominal = beam["max_von_mises"] / cont - 1, beam["nominal_stress"] / cont - 1
    assert abs(err) <= 0.10
    assert abs(err) < abs(nominal)
    assert np.isfinite(beam["kt_tension"]) and beam["kt_bending"] > 1.0
