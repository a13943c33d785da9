"""The planar linkage model: Gruebler count, loop closure, continuation, errors, overlaps."""
import numpy as np
import pytest
from flexfem.geometry.linkage import (
    AssemblyError,
    CrankAngle,
    Joint,
    Link,
    Linkage,
    assemble,
    gruebler_mobility,
    trace,
    trace_from_reference,
)
from flexfem.geometry.linkage_clearance import overlapping_links, overlapping_links_along, segment_distance
from flexfem.geometry.straight_line import chebyshev_linkage


def four_bar_closed_form(O, C, a, h, b, phi, upper=True):
    """Coupler joints of a four-bar by circle intersection (independent of Newton)."""
    A = np.array(O) + a * np.array([np.cos(phi), np.sin(phi)])
    d = np.hypot(*(np.array(C) - A))
    u = (np.array(C) - A) / d
    along = (h**2 - b**2 + d**2) / (2 * d)
    across = np.sqrt(max(h**2 - along**2, 0.0))   # 0 at a toggle, up to round-off
    n = np.array([-u[1], u[0]])
    return A, A + along * u + (across if upper else -across) * n


def test_gruebler_counts_of_known_linkages():
    assert gruebler_mobility(4, 4) == 1      # four-bar
    assert gruebler_mobility(8, 10) == 1     # eight-bar
    assert gruebler_mobility(5, 5) == 2      # five-bar
    assert chebyshev_linkage().linkage.mobility == 1


def test_reference_pose_closes_and_jacobian_matches_finite_differences():
    lk = chebyshev_linkage(h=0.1).linkage
    q0 = np.zeros(3 * len(lk.moving_links))
    assert np.max(np.abs(lk.residual(q0, [0.1]))) < 1e-15   # input: P's x = h
    q = np.random.default_rng(1).normal(scale=0.05, size=q0.size)
    jac = lk.jacobian(q)
    eps = 1e-7
    fd = np.column_stack([(lk.residual(q + eps * e, [0.0]) - lk.residual(q - eps * e, [0.0])) / (2 * eps)
                          for e in np.eye(q.size)])
    # central differences: error O(eps^2 * |q''|) ~ 1e-14 plus round-off ~ 1e-16/eps ~ 1e-9
    assert np.max(np.abs(jac - fd)) < 1e-8


def test_traced_chebyshev_matches_closed_form_four_bar():
    h = 0.1
    lk = chebyshev_linkage(h).linkage
    tr = trace_from_reference(lk, 0.0, 2 * h, 15)
    for q in tr.poses:
        # crank angle from the traced pose, then the coupler by circle intersection
        A_traced = lk.point_position(q, "crank", "A")
        A, B = four_bar_closed_form((0, 0), (2 * h, 0), 2.5 * h, h, 2.5 * h, np.arctan2(*A_traced[::-1]))
        got_b = lk.point_position(q, "coupler", "B")
        if np.hypot(*(got_b - B)) > 1e-6:   # crossed cranks: B may be on the other branch
            A, B = four_bar_closed_form((0, 0), (2 * h, 0), 2.5 * h, h, 2.5 * h,
                                        np.arctan2(*A_traced[::-1]), upper=False)
        # Newton converged to 1e-12 of the length scale: agreement at that level (the two
        # ends are toggles of a crank, where B is sensitive: 1e-9)
        assert np.allclose(got_b, B, atol=1e-9)


def test_unreachable_input_raises_naming_the_value():
    lk = chebyshev_linkage(h=0.1).linkage
    with pytest.raises(AssemblyError, match=r"input \[") as info:
        trace(lk, np.linspace(0.1, 0.5, 9))   # P cannot reach x = 0.5 m: the coupler tears
    assert isinstance(info.value, ValueError)


def test_trace_keeps_the_branch_continuous():
    tr = trace_from_reference(chebyshev_linkage(h=0.1).linkage, 0.0, 0.2, 41)
    path = tr.path("coupler", "B")
    # P moves 5 mm a step; a branch jump would move B by about a link length (0.1 m)
    assert np.hypot(*np.diff(path, axis=0).T).max() < 0.02


def test_singular_configuration_is_reported():
    # parallelogram four-bar folded flat at the reference pose: the Jacobian loses rank
    lk = Linkage((Link("ground", {"O": (0, 0), "C": (2, 0)}), Link("crank", {"O": (0, 0), "A": (1, 0)}),
                  Link("coupler", {"A": (1, 0), "B": (3, 0)}), Link("rocker", {"B": (3, 0), "C": (2, 0)})),
                 (Joint("O", ("ground", "crank")), Joint("A", ("crank", "coupler")),
                  Joint("B", ("coupler", "rocker")), Joint("C", ("rocker", "ground"))),
                 (CrankAngle("crank"),))
    with pytest.raises(AssemblyError, match="singular"):
        assemble(lk, [0.0])


def test_bad_definitions_raise_value_errors():
    with pytest.raises(ValueError, match="must coincide"):
        Linkage((Link("ground", {"O": (0, 0)}), Link("bar", {"O": (0.1, 0)})),
                (Joint("O", ("ground", "bar")),), ())
    with pytest.raises(ValueError, match="no ground"):
        Linkage((Link("bar", {"O": (0, 0)}),), (), ())
    with pytest.raises(ValueError, match="outline point"):
        Link("bar", {"O": (0, 0)}, outline=("O", "X"))


def test_segment_distance_cases():
    assert segment_distance((0, 0), (1, 0), (0.5, -1), (0.5, 1)) == 0.0       # crossing
    assert segment_distance((0, 0), (1, 0), (0, 1), (1, 1)) == pytest.approx(1.0)  # parallel
    assert segment_distance((0, 0), (1, 0), (2, 1), (3, 1)) == pytest.approx(np.sqrt(2))


def test_overlap_detection_flags_crossing_links_only():
    # two bars pivoted on the ground that cross each other, and a third far away
    links = (Link("ground", {"O": (0, 0), "Q": (1, 0), "R": (5, 0)}),
             Link("a", {"O": (0, 0), "A": (1, 1)}), Link("b", {"Q": (1, 0), "B": (0, 1)}),
             Link("c", {"R": (5, 0), "C": (5, 1)}))
    joints = (Joint("O", ("ground", "a")), Joint("Q", ("ground", "b")), Joint("R", ("ground", "c")))
    lk = Linkage(links, joints, ())
    assert overlapping_links(lk, np.zeros(9), width=0.05) == [("a", "b")]
    with pytest.raises(ValueError, match="width"):
        overlapping_links(lk, np.zeros(9), width=0.0)


def test_crank_driven_chebyshev_stops_at_its_toggle_instead_of_jumping():
    # driven by the crank, the Chebyshev linkage reaches a toggle (A, B, C collinear) at
    # crank rotation -16.26 deg from the drawn pose; tracing past it must raise, naming an input
    mech = chebyshev_linkage(h=0.1)
    lk = Linkage(mech.linkage.links, mech.linkage.joints, (CrankAngle("crank"),))
    toggle = np.arctan2(1.5, 2.0) - np.arctan2(2.0, 1.5)
    tr = trace(lk, np.linspace(0.0, 0.9 * toggle, 10))
    assert tr.path("coupler", "P")[-1][0] > 0.15       # went most of the way towards x = 2h
    with pytest.raises(AssemblyError, match="input"):
        trace(lk, np.linspace(0.0, 1.2 * toggle, 10))


def test_coarse_steps_land_on_the_same_branch_as_fine_steps():
    lk = chebyshev_linkage(h=0.1).linkage
    fine = trace_from_reference(lk, 0.0, 0.2, 81)
    coarse = trace_from_reference(lk, 0.0, 0.2, 5)   # 50 mm steps: subdivided where needed
    assert np.allclose(coarse.poses, fine.poses[::20], atol=1e-10)


def test_chebyshev_crossed_cranks_overlap_and_watt_does_not():
    from flexfem.geometry.straight_line import watt_linkage
    cheb = chebyshev_linkage(h=0.1)
    tr = trace_from_reference(cheb.linkage, *cheb.input_range, 11)
    assert ("crank", "rocker") in overlapping_links_along(tr, 1e-3)     # the cranks cross
    watt = watt_linkage()
    tr = trace_from_reference(watt.linkage, *watt.input_range, 11)
    assert overlapping_links_along(tr, 1e-3) == []
