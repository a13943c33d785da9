"""Gravity torques of the five-bar robot (Lessard et al. 2007, Eqs. 2-12 and Appendix 1)."""
import numpy as np
import pytest
from flexfem.studies.balancing.gravity import (
    FiveBarRobot,
    Workspace,
    assembly_mode,
    distal_point,
    input_torques,
    input_torques_appendix1,
    leg_angles,
    load_robot,
    potential_energy,
    proximal_angle,
    tool_reactions,
    workspace_samples,
    workspace_torques,
)
from flexfem.studies.balancing.report import default_workspace

ROBOT = load_robot()


def _configurations():
    """Workspace samples with random tool loads, both five-bars' kind of point."""
    rng = np.random.default_rng(1)
    ws = default_workspace(quick=True)
    s = workspace_samples(ws)
    idx = rng.choice(s["y_E"].size, 12, replace=False)
    y, z = s["y_E"][idx], s["z_E"][idx]
    q2, q3 = leg_angles(ROBOT, y, z, ws.branches)
    R_z, R_y = rng.uniform(0.0, 8.0, 12), rng.uniform(-2.0, 2.0, 12)
    return q2, q3, y, z, R_z, R_y


def test_appendix3_values_loaded_in_si():
    assert ROBOT.L_f == 0.1 and ROBOT.r13 == 0.0 and ROBOT.L7 == ROBOT.L8 == 0.6
    assert (ROBOT.z_A, ROBOT.z_C, ROBOT.L2, ROBOT.L3) == (0.13, 0.28, 0.5, 0.7)
    assert ROBOT.m2 == 1.235 and ROBOT.g == 9.81


def test_closed_form_torques_equal_virtual_work_of_the_potential():
    """tau = dV/dq along the mechanism's own motion (E moving with the forward kinematics).

    Complex-step derivatives have no subtraction error, so the two agree to round-off
    (|tau| ~ 10 N m, double precision ~ 1e-15 relative; 1e-11 N m leaves a wide margin).
    Central differences (h = 1e-6 rad: truncation ~ h^2 |V'''| ~ 1e-11, round-off
    ~ 1e-16 |V| / h ~ 1e-9) agree to 1e-7 N m.
    """
    q2, q3, y, z, R_z, R_y = _configurations()
    asm = assembly_mode(ROBOT, q2, q3, y, z)
    tau2, tau3 = input_torques(ROBOT, q2, q3, y, z, R_z, R_y)

    def V(a, b):
        yE, zE = distal_point(ROBOT, a, b, asm)
        return potential_energy(ROBOT, a, b, yE, zE, R_z, R_y)

    h = 1e-30
    np.testing.assert_allclose(V(q2 + 1j * h, q3).imag / h, tau2, rtol=0, atol=1e-11)
    np.testing.assert_allclose(V(q2, q3 + 1j * h).imag / h, tau3, rtol=0, atol=1e-11)
    d = 1e-6
    np.testing.assert_allclose((V(q2 + d, q3) - V(q2 - d, q3)).real / (2 * d), tau2, atol=1e-7)
    np.testing.assert_allclose((V(q2, q3 + d) - V(q2, q3 - d)).real / (2 * d), tau3, atol=1e-7)


def test_appendix1_as_printed_pairs_the_loads_wrongly():
    """The printed Appendix 1 pairs M3 (vertical load) with z offsets: it misses the virtual
    work by far more than round-off, which is why input_torques re-derives the pairing."""
    q2, q3, y, z, R_z, R_y = _configurations()
    ours = np.array(input_torques(ROBOT, q2, q3, y, z, R_z, R_y))
    printed = np.array(input_torques_appendix1(ROBOT, q2, q3, y, z, R_z, R_y))
    assert np.max(np.abs(printed - ours)) > 0.1


def test_tool_reactions_share_the_tool_weight():
    """Eqs. 3-6: R_Ez + R_Hz is the tool assembly's weight; R_Ey = -R_Hy = 0 at beta = 0."""
    a = np.radians(np.array([-45.0, 0.0, 30.0]))
    b = np.radians(np.array([0.0, -50.0, 35.0]))
    R_Ez, R_Ey, R_Hz, R_Hy = tool_reactions(ROBOT, a, b)
    weight = (ROBOT.m6 + ROBOT.m11 + ROBOT.m12 + ROBOT.m13) * ROBOT.g
    np.testing.assert_allclose(R_Ez + R_Hz, weight, rtol=1e-14)
    np.testing.assert_allclose(R_Ey, -R_Hy, rtol=0, atol=0)
    assert R_Ey[0] == 0.0
    # Eq. 3 by hand at alpha = beta = 0 (L = L_f = 0.1 m), r13 = 0
    R_Hz0 = (0.083 * (0.1 - 0.0315) + 0.107 * 0.0355) * 9.81 / 0.1
    np.testing.assert_allclose(tool_reactions(ROBOT, 0.0, 0.0)[2], R_Hz0, rtol=1e-14)


def test_every_workspace_sample_assembles_and_round_trips():
    """Inverse kinematics has a real solution at every sample of the full workspace (both
    five-bars), and forward kinematics brings E (H) back to 1e-12 m (round-off of ~1 m)."""
    ws = default_workspace()
    wt = workspace_torques(ROBOT, ws)
    assert wt.q.shape == (11 * 11 * 5 * 5, 4) and np.all(np.isfinite(wt.tau))
    s = wt.samples
    for qa, qc, y, z in ((wt.q[:, 0], wt.q[:, 1], s["y_E"], s["z_E"]),
                         (wt.q[:, 2], wt.q[:, 3], s["y_H"], s["z_H"])):
        asm = assembly_mode(ROBOT, qa, qc, y, z)
        assert np.all(asm != 0)
        yE, zE = distal_point(ROBOT, qa, qc, asm)
        np.testing.assert_allclose(yE, y, atol=1e-12)
        np.testing.assert_allclose(zE, z, atol=1e-12)
    # the working mode keeps each motor angle inside one continuous range (< 2 pi wide)
    assert np.all(np.ptp(wt.q, axis=0) < np.pi)


def test_unreachable_point_raises_naming_it():
    with pytest.raises(ValueError, match=r"point \(y, z\) = \(1\.6000"):
        workspace_torques(ROBOT, Workspace(y_min=1.6, z_min=0.0, n_alpha=1, n_beta=1))
    with pytest.raises(ValueError, match="out of reach"):
        proximal_angle(0.0, 0.13, 0.13, 0.5, 0.6, 1)


@pytest.mark.parametrize("kwargs, word", [
    ({"size_y": -0.5}, "size_y"), ({"n_z": 0}, "n_z"), ({"branches": (1, 0)}, "branches"),
    ({"alpha_range": (-2.0, 0.0)}, "alpha_range")])
def test_workspace_validation(kwargs, word):
    with pytest.raises(ValueError, match=word):
        Workspace(**kwargs)


def test_robot_validation():
    with pytest.raises(ValueError, match="m2 = -1"):
        load_robot(m2=-1.0)
    with pytest.raises(ValueError, match="r7 = 0.7 must be <= L7"):
        load_robot(r7=0.7)
    assert isinstance(load_robot(r13=0.05), FiveBarRobot)
