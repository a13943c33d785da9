"""The Chapter 6 driving linkage: Chebyshev lambda, mobility, opposite motion, flexure FEM."""
import numpy as np
import pytest

from flexfem.geometry.driving_linkage import (DrivingParams, build_driving_linkage,
                                              chebyshev_lambda_linkage, half_mobility,
                                              trace_driving, transmission_ratio)
from flexfem.geometry.straight_line import chebyshev_linkage, straight_line_deviation
from flexfem.geometry.linkage import PointCoordinate, Linkage, trace_from_reference

H = 0.1


def _lambda_closed_form(h, phi):
    """P of the lambda at crank angle phi (rad), by circle intersection (independent of Linkage)."""
    A = np.stack([h / 2 * np.cos(phi), h / 2 * np.sin(phi)], axis=1)
    C = np.array([h, 0.0])
    d = C - A
    dist = np.hypot(*d.T)
    r = 1.25 * h
    mid = A + d / 2
    half = np.sqrt(r**2 - (dist / 2) ** 2)
    n = np.stack([-d[:, 1], d[:, 0]], axis=1) / dist[:, None]
    B = mid + half[:, None] * n
    return 2 * B - A


def test_lambda_proportions_and_exact_points():
    mech = chebyshev_lambda_linkage(H)
    pts = {k: np.array(v) for link in mech.linkage.links for k, v in link.points.items()}
    assert np.isclose(np.linalg.norm(pts["C"] - pts["O"]), H)
    assert np.isclose(np.linalg.norm(pts["A"] - pts["O"]), H / 2)
    assert np.isclose(np.linalg.norm(pts["B"] - pts["A"]), 1.25 * H)
    assert np.isclose(np.linalg.norm(pts["B"] - pts["C"]), 1.25 * H)
    assert np.isclose(np.linalg.norm(pts["P"] - pts["A"]), 2.5 * H)
    # P on the line y = 2h at crank angles 90, 180, 270 deg (x = 2h, h, 0): exact by geometry
    P = _lambda_closed_form(H, np.radians([90.0, 180.0, 270.0]))
    assert np.allclose(P, [[2 * H, 2 * H], [H, 2 * H], [0.0, 2 * H]], atol=1e-12)


def test_lambda_is_the_cognate_of_the_thesis_chebyshev_linkage():
    """Section 2.3's linkage (|OC| = 2h, |AB| = h, |OA| = |BC| = 2.5h, P mid-AB) and the lambda
    trace the same straight stretch: same height at the same x, to solver round-off."""
    cheb = chebyshev_linkage(H)
    lam = chebyshev_lambda_linkage(H)
    lam_x = Linkage(lam.linkage.links, lam.linkage.joints, (PointCoordinate("coupler", "P", 0),))
    x = (0.02 * H, 1.98 * H)
    p1 = trace_from_reference(cheb.linkage, *x, 41).path(*cheb.tracer)
    p2 = trace_from_reference(lam_x, *x, 41).path(*lam.tracer)
    assert np.allclose(p1, p2, atol=1e-10 * H)


def test_lambda_straightness_matches_closed_form():
    mech = chebyshev_lambda_linkage(H)
    phi = np.linspace(np.pi / 2, 3 * np.pi / 2, 201)
    closed = straight_line_deviation(_lambda_closed_form(H, phi))
    traced = trace_from_reference(mech.linkage, -np.pi / 2, np.pi / 2, 201).path(*mech.tracer)
    dev = straight_line_deviation(traced)
    assert np.isclose(dev.band_m, closed.band_m, rtol=1e-6)
    assert np.isclose(dev.travel_m, 2 * H, rtol=1e-9)
    # P touches y = 2h at three points and bulges between them: band well under 1 % of the stroke
    assert 0 < dev.band_m < 0.01 * dev.travel_m


def test_mobility_counts():
    params = DrivingParams()
    whole = build_driving_linkage(params)
    assert whole.mobility == 1
    assert half_mobility(params) == 1
    assert build_driving_linkage(params, shuttle=False).mobility == 2   # two halves, two inputs


@pytest.fixture(scope="module")
def driving_trace():
    return trace_driving(DrivingParams(), n=41)


def test_suspensions_move_in_opposite_straight_lines(driving_trace):
    tr = driving_trace
    stroke = np.ptp(tr.dx_right)
    assert stroke > 0.5 * DrivingParams().input_travel
    # mirror image, solved independently: x_left(s) = -x_right(s) to Newton round-off
    assert np.max(np.abs(tr.dx_left + tr.dx_right)) < 1e-9 * stroke
    assert np.allclose(tr.ee_left[:, 1], tr.ee_right[:, 1], atol=1e-12)
    # the eight-bar's own straightness (< 0.1 % of its stroke) carries over
    assert tr.deviation_right.deviation_pct < 0.1
    assert np.sign(tr.dx_right[-1]) == -np.sign(tr.dx_left[-1])


def test_misfit_is_twice_the_coupler_path_error(driving_trace):
    tr = driving_trace
    p_r = tr.linkage.point_position(tr.poses, "lamR_coupler", "lamR_P")
    x_err = p_r[:, 0] - p_r[len(tr.s) // 2, 0]
    assert np.allclose(tr.misfit, 2 * x_err, atol=1e-12)
    assert np.max(np.abs(tr.misfit)) < 2 * DrivingParams().input_travel * 0.01


def test_transmission_ratio_from_crank_geometry(driving_trace):
    """In the drawn pose the crank is vertical, so Q moves along x at r per radian of crank, while
    P moves |dP/dphi| per radian (closed-form lambda, central difference): ratio r / |dP/dphi|."""
    p = DrivingParams()
    a = p.lambda_crank
    h = 2 * a
    dphi = 1e-6
    P = _lambda_closed_form(h, np.array([np.pi - dphi, np.pi + dphi]))
    ds_dphi = np.hypot(*(P[1] - P[0])) / (2 * dphi)
    expected = p.lever_length / ds_dphi   # Q moves r dphi along x per ds_dphi dphi of P
    assert np.isclose(abs(transmission_ratio(driving_trace)), expected, rtol=1e-3)


@pytest.mark.parametrize("kwargs", [dict(lambda_crank=-1.0), dict(lever_length=10e-3),
                                    dict(input_travel=0.2), dict(clearance=float("nan")),
                                    dict(suspension="x")])
def test_bad_input_raises(kwargs):
    with pytest.raises(ValueError):
        DrivingParams(**kwargs)


def test_bad_lambda_and_trace_inputs():
    with pytest.raises(ValueError, match="h ="):
        chebyshev_lambda_linkage(0.0)
    with pytest.raises(ValueError, match="n ="):
        trace_driving(DrivingParams(), n=2)


def test_flexure_fem_opposite_motion(tmp_path):
    from flexfem.studies.eightbar_driving import driving_study
    out = driving_study(tmp_path, quick=True)
    s = out["summary"]
    # the part is mirror-symmetric; only the unstructured mesh is not: ratio -1 to mesh level
    assert abs(s["ratio_left_right"] + 1) < 1e-3
    # flexures add compliance: the FEM transmission lies just below the rigid one
    assert 0.9 < s["transmission"] / s["rigid_transmission"] <= 1.0
    assert s["cross_motion_right"] < 0.01
    for name in out["figures"] + out["tables"]:
        assert (tmp_path / name).stat().st_size > 0
