"""The symmetric rectilinear eight-bar (rigid body): structure, symmetry, straightness, layout."""
from dataclasses import replace

import numpy as np
import pytest
from flexfem.geometry.eightbar.rigid import (
    BASE_JOINTS,
    EightBarParams,
    build_eightbar,
    eightbar_joints,
    eightbar_points,
    overall_size,
    trace_eightbar,
)
from flexfem.geometry.linkage import Trace
from flexfem.geometry.linkage_clearance import overlapping_links_along


@pytest.fixture(scope="module")
def traced():
    params = replace(EightBarParams(), travel=33.1e-3)
    return params, trace_eightbar(params, n=101)


def test_eight_links_ten_joints_one_degree_of_freedom():
    linkage = build_eightbar(EightBarParams())
    assert len(linkage.links) == 8 and len(linkage.joints) == 10
    assert linkage.mobility == 1


def test_drawn_pose_is_mirror_symmetric():
    pts = eightbar_points(EightBarParams())
    for name, (x, y) in pts.items():
        if name.endswith("_L"):
            xr, yr = pts[name[:-2] + "_R"]
            assert (xr, yr) == pytest.approx((-x, y), abs=1e-15)
    assert pts["E"][0] == 0.0


def test_end_effector_translates_on_a_straight_line(traced):
    params, tr = traced
    # thesis (Ch. 5): at least 33 mm of travel within 0.1 % deviation; our design reaches it
    assert tr.deviation.travel_m == pytest.approx(33.1e-3, rel=1e-9)
    assert tr.deviation.deviation_pct < 0.1
    assert tr.deviation.band_m < 0.1e-2 * tr.deviation.travel_m
    # both halves trace the same even path, so the end-effector does not rotate (round-off)
    assert np.max(np.abs(tr.rotation)) < 1e-12
    # the path is even about the middle: y(s) = y(-s) to the trace tolerance
    assert np.allclose(tr.points[:, 1], tr.points[::-1, 1], atol=1e-12)


def test_size_and_no_overlap(traced):
    params, tr = traced
    width, height = overall_size(params, tr)
    # thesis Section 1.1: "approximately 200 mm x 150 mm"
    assert width == pytest.approx(0.200, abs=0.01)
    assert height == pytest.approx(0.150, abs=0.01)
    linkage = build_eightbar(params)
    assert overlapping_links_along(Trace(linkage, tr.displacements[:, None], tr.poses[::10]), 2e-3) == []


def test_joints_geometry_for_the_flexure_phase():
    params = EightBarParams()
    geo = eightbar_joints(params, 0.01)
    assert len(geo["joints"]) == 10
    assert {j["name"] for j in geo["joints"] if j["base"]} == set(BASE_JOINTS)
    positions = {j["name"]: np.array(j["position"]) for j in geo["joints"]}
    # link lengths are kept in the displaced pose: crank |O A| = a
    assert np.hypot(*(positions["A_L"] - positions["O_L"])) == pytest.approx(params.crank_length, rel=1e-10)
    # the end-effector has moved 10 mm along x
    ee = np.array(geo["links"]["end_effector"])
    assert ee[1][0][0] - eightbar_points(params)["E_L"][0] == pytest.approx(0.01, abs=1e-6)
    # every segment end is a joint or a point of the same link; the couplers are T-shaped
    assert len(geo["links"]["coupler_L"]) == 3
    assert "ground" not in geo["links"]


@pytest.mark.parametrize("field, value, match", [
    ("crank_length", -1.0, "crank_length = -1.0"),
    ("crank_length", 0.01, "crank_length = 0.01 m, must be > "),
    ("module_spacing", 0.05, "module_spacing"),
    ("travel", 0.2, "travel"),
    ("ee_drop", float("nan"), "ee_drop"),
])
def test_invalid_parameters_raise(field, value, match):
    with pytest.raises(ValueError, match=match):
        replace(EightBarParams(), **{field: value})
