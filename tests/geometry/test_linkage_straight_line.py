"""The Chapter 2 straight-line linkages traced with the linkage model, against their theory."""
import numpy as np
import pytest
from flexfem.geometry.linkage import trace_from_reference
from flexfem.geometry.straight_line import (
    chebyshev_linkage,
    modified_peaucellier_linkage,
    peaucellier_linkage,
    roberts_linkage,
    straight_line_deviation,
    trace_straight_line,
    watt_linkage,
)


def test_straight_line_deviation_of_a_known_parabola():
    x = np.linspace(-1, 1, 2001)
    dev = straight_line_deviation(np.column_stack([x, 0.01 * x**2]))
    # symmetric parabola: TLS line is y = mean(y) = 0.01/3 (continuous limit, tilt 0);
    # farthest points are the ends, 0.01 - 0.01/3 = 0.00667 away; band = 0.01
    assert dev.travel_m == pytest.approx(2.0, rel=1e-6)
    assert dev.max_deviation_m == pytest.approx(0.01 * 2 / 3, rel=1e-3)
    assert dev.band_m == pytest.approx(0.01, rel=1e-6)
    assert dev.deviation_pct == pytest.approx(100 * 0.01 / 3, rel=1e-3)
    with pytest.raises(ValueError, match="shape"):
        straight_line_deviation(np.zeros((1, 2)))


@pytest.mark.parametrize("builder", [peaucellier_linkage, modified_peaucellier_linkage])
def test_peaucellier_traces_an_exact_line(builder):
    mech = builder()
    path, dev = trace_straight_line(mech, 61)
    assert mech.linkage.mobility == 1
    # exact mechanism: only Newton's tolerance remains (joint gaps < 1e-12 of the length scale,
    # amplified at most ~10x through the cell)
    assert dev.max_deviation_m < 1e-11 * mech.linkage.length_scale
    assert dev.deviation_pct < 1e-9
    assert dev.travel_m > 0.1


def test_peaucellier_line_positions_follow_the_inversion():
    a, b, c = 0.3, 0.2, 0.1
    path, _ = trace_straight_line(peaucellier_linkage(a, b, c), 21)
    # OC * OP = a^2 - b^2 with C on a circle through O: P on x = (a^2 - b^2) / (2c) (Eq. 2.2)
    assert np.allclose(path[:, 0], (a**2 - b**2) / (2 * c), atol=1e-12)
    a, b = 0.1, 0.2
    path, _ = trace_straight_line(modified_peaucellier_linkage(a, b, c), 21)
    # modified cell: P' on the other side of O, x = -(b^2 - a^2) / (2c) (Eqs. 2.3-2.4)
    assert np.allclose(path[:, 0], -(b**2 - a**2) / (2 * c), atol=1e-12)


def _halving_ratio(a, b, h=0.05, r=0.04):
    """Deviation over crank range +-r divided by that over +-r/2."""
    devs = [trace_straight_line(watt_linkage(a, b, h, crank_range=(-x, x)), 41)[1] for x in (r, r / 2)]
    return devs[0].max_deviation_m / devs[1].max_deviation_m


def test_watt_proportions_and_order_of_straightness():
    a, b, h = 0.12, 0.08, 0.05
    lk = watt_linkage(a, b, h).linkage
    O, C = np.array(lk.link("ground").points["O"]), np.array(lk.link("ground").points["C"])
    A, P, B = (np.array(lk.link("coupler").points[k]) for k in "APB")
    x = np.hypot(*(P - B))                                                    # measured from B
    assert x / (h - x) == pytest.approx(a / b)                                # Section 2.1
    assert np.sum((C - O) ** 2) == pytest.approx(h**2 + (a + b) ** 2)         # g^2 = h^2 + (a+b)^2
    # |AP|/|PB| = b/a cancels the path's curvature in the middle (A and B bend oppositely by
    # s^2/2a and s^2/2b), so the deviation over a stroke falls at least as s^3 (ratio >= 8 when
    # the range is halved); a point with curvature left would give ratio 4.
    assert _halving_ratio(a, b) > 12
    # a = b: the linkage is centrally symmetric about P, the path is odd, and P is a Ball
    # point: deviation ~ s^5, ratio 32
    assert _halving_ratio(0.1, 0.1) == pytest.approx(32, rel=0.05)
    _, dev = trace_straight_line(watt_linkage(), 41)
    assert dev.deviation_pct < 0.05


def test_roberts_passes_through_the_ground_line_midpoint_and_is_symmetric():
    mech = roberts_linkage(a=0.2, h=0.1)
    tr = trace_from_reference(mech.linkage, -0.1, 0.1, 21)
    path = tr.path(*mech.tracer)
    assert np.allclose(path[10], (0.0, 0.0), atol=1e-14)
    # mirror symmetry of the linkage: x(-t) = -x(t) only approximately (crank input), so
    # compare the path's y at mirrored x by interpolation: even function to 1e-9 m
    order = np.argsort(path[:, 0])
    xs, ys = path[order, 0], path[order, 1]
    probe = np.linspace(0, 0.8 * min(-xs[0], xs[-1]), 7)
    assert np.allclose(np.interp(probe, xs, ys), np.interp(-probe, xs, ys), atol=2e-6)
    _, dev = trace_straight_line(mech, 81)
    assert dev.deviation_pct < 0.1


def test_chebyshev_three_exact_points_and_known_deviation():
    h = 0.1
    mech = chebyshev_linkage(h)
    tr = trace_from_reference(mech.linkage, 0.0, 2 * h, 81)
    path = tr.path(*mech.tracer)
    # P is exactly at height 2h above O, at the middle and above C (Section 2.3 geometry)
    for k in (0, 40, 80):
        assert path[k, 1] == pytest.approx(2 * h, abs=1e-12)
    _, dev = trace_straight_line(mech, 401)
    # between the exact points P rises at most to 2h + 0.0048769 h (circle intersection on
    # 2e5 crank angles, independent of the linkage model); the TLS line is horizontal to
    # O(1e-4), so the band equals that rise to 0.1 % (401 samples miss the peak by < 1e-5)
    assert dev.band_m == pytest.approx(0.0048769 * h, rel=1e-3)
    assert dev.deviation_pct == pytest.approx(100 * 0.0048769 / 2 / 2, rel=0.05)


def test_builders_reject_bad_dimensions():
    with pytest.raises(ValueError, match="a = "):
        peaucellier_linkage(a=0.1, b=0.2)
    with pytest.raises(ValueError, match="a = "):
        modified_peaucellier_linkage(a=0.3, b=0.2)
    with pytest.raises(ValueError, match="h = "):
        chebyshev_linkage(h=-1.0)
