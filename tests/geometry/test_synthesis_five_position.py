"""Five-position synthesis: RR dyads (Eqs. 3.20-3.28) and eight-bar RR constraints (Eqs. 4.1-4.6),
checked by recovering the joints of linkages that generated the task positions."""
import numpy as np
import pytest
from flexfem.geometry.linkage import CrankAngle, Joint, Link, Linkage, trace
from flexfem.geometry.synthesis import (
    ThreeRChain,
    eightbar_constraint_synthesis,
    planar_transform,
    relative_displacements,
    rr_constraint_residual,
    rr_dyad_synthesis,
    three_r_inverse_kinematics,
    three_r_link_poses,
)
from flexfem.studies.eightbar.path import synthesis_check


def four_bar_coupler_frames(O, C, a, h, b, angles):
    """Coupler frames (origin A, x axis along AB) of a four-bar by circle intersection."""
    frames = []
    for phi in angles:
        A = np.array(O) + a * np.array([np.cos(phi), np.sin(phi)])
        d = np.hypot(*(np.array(C) - A))
        u = (np.array(C) - A) / d
        along = (h**2 - b**2 + d**2) / (2 * d)
        B = A + along * u + np.sqrt(h**2 - along**2) * np.array([-u[1], u[0]])
        frames.append(planar_transform(np.arctan2(*(B - A)[::-1]), *A))
    return np.array(frames)


def test_dyad_synthesis_recovers_both_dyads_of_a_four_bar():
    O, C, a, h, b = (0.0, 0.0), (0.3, 0.05), 0.1, 0.25, 0.2
    tasks = four_bar_coupler_frames(O, C, a, h, b, np.linspace(1.0, 1.6, 5))
    dyads = rr_dyad_synthesis(tasks)
    assert 2 <= len(dyads) <= 4                         # Section 3.4: at most four real dyads
    A1 = tasks[0][:2, 2]
    B1 = tasks[0][:2, :2] @ [h, 0] + A1
    for g, w, length in ((O, A1, a), (C, B1, b)):
        # Newton converged to residual < 1e-10 scale^2: pivots to ~1e-9 m
        assert min(np.hypot(*np.subtract(d.g1, g)) + np.hypot(*np.subtract(d.w1, w))
                   for d in dyads) < 1e-8
        assert any(d.length == pytest.approx(length, rel=1e-8) for d in dyads)
    rel = relative_displacements(tasks)
    for d in dyads:      # every returned dyad satisfies Eqs. 3.24-3.28
        assert np.max(np.abs(rr_constraint_residual(
            np.r_[d.g1, d.w1], np.broadcast_to(np.eye(3), rel.shape), rel))) < 1e-10


def test_three_r_inverse_kinematics_round_trip():
    chain = ThreeRChain(planar_transform(0.3, 0.01, -0.02), 0.1, 0.08, planar_transform(0.2, 0.03, 0.0), -1)
    t = (0.4, -0.9, 0.3)
    from flexfem.geometry.synthesis import joint_transform
    task = (chain.base @ joint_transform(t[0], 0) @ joint_transform(t[1], chain.a1)
            @ joint_transform(t[2], chain.a2) @ chain.tool)
    assert np.allclose(three_r_inverse_kinematics(chain, task), t, atol=1e-12)
    frames = three_r_link_poses(chain, [task])
    assert np.allclose(frames[2, 0] @ chain.tool, task, atol=1e-12)
    with pytest.raises(ValueError, match="out of reach"):
        three_r_inverse_kinematics(chain, planar_transform(0, 1.0, 1.0))
    with pytest.raises(ValueError, match="elbow"):
        ThreeRChain(np.eye(3), 0.1, 0.1, np.eye(3), 0)


def _eightbar_with_a_floating_constraint():
    """An eight-bar: 3R chains Oa-A1-Pa and Ob-B1-Pb to the end-effector, an RR link X1-Y1
    between link 1 of chain a and link 2 of chain b, and an RR link Z-Y2 from the ground to
    link 2 of chain b. Points (m) in the drawn pose."""
    p = {"Oa": (0.0, 0.0), "A1": (0.05, 0.12), "Pa": (0.12, 0.2), "Pb": (0.25, 0.21),
         "B1": (0.3, 0.1), "Ob": (0.35, 0.0), "X1": (0.03, 0.07), "Y1": (0.27, 0.16),
         "Z": (0.45, 0.05), "Y2": (0.29, 0.17)}

    def link(name, *keys):
        return Link(name, {k: p[k] for k in keys})

    links = (link("ground", "Oa", "Ob", "Z"), link("a1", "Oa", "A1", "X1"), link("a2", "A1", "Pa"),
             link("b1", "Ob", "B1"), link("b2", "B1", "Pb", "Y1", "Y2"), link("ee", "Pa", "Pb"),
             link("r1", "X1", "Y1"), link("r2", "Z", "Y2"))
    joints = tuple(Joint(k, pair) for k, pair in (
        ("Oa", ("ground", "a1")), ("A1", ("a1", "a2")), ("Pa", ("a2", "ee")), ("Ob", ("ground", "b1")),
        ("B1", ("b1", "b2")), ("Pb", ("b2", "ee")), ("X1", ("a1", "r1")), ("Y1", ("r1", "b2")),
        ("Z", ("ground", "r2")), ("Y2", ("r2", "b2"))))
    return Linkage(links, joints, (CrankAngle("a1"),)), p


def _frames(linkage, poses, name, origin, toward):
    """Frames of a link: origin at a point, x axis toward another point (both on the link)."""
    out = []
    for q in poses:
        o, t = linkage.point_position(q, name, origin), linkage.point_position(q, name, toward)
        out.append(planar_transform(np.arctan2(*(t - o)[::-1]), *o))
    return np.array(out)


def _chain(p, base, elbow_point, wrist, task1, link1_frame1):
    a1 = np.hypot(*np.subtract(p[elbow_point], p[base]))
    a2 = np.hypot(*np.subtract(p[wrist], p[elbow_point]))
    tool = np.linalg.inv(planar_transform(0, *(np.linalg.inv(task1) @ np.r_[p[wrist], 1])[:2]))
    for elbow in (1, -1):
        chain = ThreeRChain(planar_transform(0, *p[base]), a1, a2, tool, elbow)
        if np.allclose(three_r_link_poses(chain, [task1])[1, 0][:2, 2], p[elbow_point], atol=1e-9):
            return chain
    raise AssertionError("no elbow branch matches")


def test_constraint_between_two_moving_links_is_recovered():
    linkage, p = _eightbar_with_a_floating_constraint()
    assert linkage.mobility == 1
    poses = trace(linkage, np.linspace(0.0, 0.2, 5), tol=1e-15).poses
    tasks = _frames(linkage, poses, "ee", "Pa", "Pb")
    chain_a = _chain(p, "Oa", "A1", "Pa", tasks[0], None)
    chain_b = _chain(p, "Ob", "B1", "Pb", tasks[0], None)
    pair = (("a", 1), ("b", 2))
    sols = eightbar_constraint_synthesis(chain_a, chain_b, tasks, [pair])[pair]
    # the drawn pose is task position 1, so G1 = X1 and W1 = Y1 (Eq. 4.5). The task frames
    # carry the trace's joint gaps (~1e-16 m with tol 1e-15); the synthesis Jacobian's
    # condition number here is ~6e4 (entries ~0.03 m), so pivots agree to ~1e-10 m
    assert min(np.hypot(*np.subtract(s.g1, p["X1"])) + np.hypot(*np.subtract(s.w1, p["Y1"]))
               for s in sols) < 1e-8
    ground_pair = (("ground",), ("b", 2))
    sols = eightbar_constraint_synthesis(chain_a, chain_b, tasks, [ground_pair])[ground_pair]
    assert min(np.hypot(*np.subtract(s.g1, p["Z"])) + np.hypot(*np.subtract(s.w1, p["Y2"]))
               for s in sols) < 1e-8


def test_eightbar_rocker_recovered_from_its_own_trace():
    check = synthesis_check()
    # tolerance: synthesis residual 1e-10 scale^2 and trace tolerance 1e-12: pivots to < 1e-8 m
    assert check["four_bar_pivot_error_m"] < 1e-8
    assert check["eightbar_rocker_error_m"] < 1e-8
    assert check["eightbar_constraints_found"] >= 2     # the rocker and the crank at least


def test_synthesis_rejects_wrong_number_of_positions():
    with pytest.raises(ValueError, match="must be"):
        rr_dyad_synthesis(np.broadcast_to(np.eye(3), (4, 3, 3)))
