"""Gravity torques of the five-bar ultrasound robot (Lessard et al., IFToMM 2007, Eqs. 2-12).

Coordinates: y horizontal (lateral), z vertical upwards, both in metres, in the plane of a
five-bar mechanism. The motors sit on the z axis (A at z_A, C at z_C); a proximal angle q is
measured from the upward vertical towards +y, so the elbow of arm 2 is at
B = (L2 sin q2, z_A + L2 cos q2) (Eqs. 8-11 and Appendix 1). Torques are in N m, positive in
the sense of q, and are the torques the motors must supply, tau = dV/dq (Eq. 12).
"""
from dataclasses import dataclass, fields

import numpy as np

from ...data import load_toml


@dataclass(frozen=True)
class FiveBarRobot:
    """Masses (kg), lengths (m) and gravity (m/s^2) of Appendix 3.

    One five-bar: motors A (z_A) and C (z_C), proximal links 2 (L2, r2 = AS2) and 3 (L3,
    r3 = CS3), distal links 7 (L7, r7 = ES7) and 8 (L8, r8 = ES8) meeting at E. Tool assembly:
    motor 6 (m6), strut parts 11 and 12 (r11, r12), tool 13 (r13), planes L_f apart (Eq. 2).
    The second five-bar (motors 4, 5) has the same values (Appendix 3).
    """

    g: float
    m2: float
    m3: float
    m6: float
    m7: float
    m8: float
    m11: float
    m12: float
    m13: float
    L2: float
    L3: float
    L7: float
    L8: float
    z_A: float
    z_C: float
    r2: float
    r3: float
    r7: float
    r8: float
    r11: float
    r12: float
    r13: float
    L_f: float

    def __post_init__(self):
        for f in fields(self):
            value = getattr(self, f.name)
            if not np.isfinite(value):
                raise ValueError(f"{f.name} = {value} must be finite")
            if f.name in ("z_A", "z_C", "r13"):
                continue
            if value <= 0.0:
                raise ValueError(f"{f.name} = {value} must be > 0")
        if self.r13 < 0.0:
            raise ValueError(f"r13 = {self.r13} must be >= 0")
        for r, length in (("r2", "L2"), ("r3", "L3"), ("r7", "L7"), ("r8", "L8")):
            if getattr(self, r) > getattr(self, length):
                raise ValueError(f"{r} = {getattr(self, r)} must be <= {length} = "
                                 f"{getattr(self, length)}")


def load_robot(**overrides) -> FiveBarRobot:
    """The robot of Appendix 3 (SI units), with the readings of docs/balancing.md.

    ``overrides`` replace single fields (e.g. ``r13=0.05``) for sensitivity studies.
    """
    data = load_toml("balancing_robot.toml")
    a = data["appendix3"]
    values = {k[: k.rfind("_")]: v for k, v in a.items() if k.endswith(("_kg", "_m"))}
    values["g"] = a["g_m_s2"]
    values["L_f"] = values.pop("garbled_L7_read_as_L_f")
    values["r13"] = data["assumed"]["r13_m"]
    values.update(overrides)
    return FiveBarRobot(**values)


# ---------------------------------------------------------------- tool holder (Eqs. 2-6)

def strut_length(L_f, alpha, beta):
    """Length L (m) of the telescopic strut, Eq. 2: L = L_f cos(beta) / cos(alpha).

    alpha: rotation about the vertical axis Z (rad), beta: about the lateral axis Y (rad).
    """
    return L_f * np.cos(beta) / np.cos(alpha)


def reaction_H_z(robot: FiveBarRobot, L):
    """Vertical reaction R_Hz (N) of the tool assembly on H, Eq. 3."""
    return ((robot.m12 * (L - robot.r12) + robot.m11 * robot.r11 + robot.m13 * robot.r13)
            * robot.g / L)


def reaction_E_z(robot: FiveBarRobot, R_Hz):
    """Vertical reaction R_Ez (N) on E, Eq. 4: the rest of the tool assembly's weight."""
    return (robot.m6 + robot.m11 + robot.m12 + robot.m13) * robot.g - R_Hz


def reaction_H_y(robot: FiveBarRobot, R_Hz, alpha, beta):
    """Horizontal reaction R_Hy (N) on H, Eq. 5: (m12 g - R_Hz) tan(beta) sin(alpha)."""
    return (robot.m12 * robot.g - R_Hz) * np.tan(beta) * np.sin(alpha)


def tool_reactions(robot: FiveBarRobot, alpha, beta):
    """(R_Ez, R_Ey, R_Hz, R_Hy) in N for tool angles alpha (about Z) and beta (about Y), rad.

    Eqs. 2-6; R_Ey = -R_Hy (Eq. 6).
    """
    L = strut_length(robot.L_f, alpha, beta)
    R_Hz = reaction_H_z(robot, L)
    R_Hy = reaction_H_y(robot, R_Hz, alpha, beta)
    return reaction_E_z(robot, R_Hz), -R_Hy, R_Hz, R_Hy


def strut_offset_yz(L_f, alpha, beta):
    """(dy, dz) in m from E to H, the strut's projection on the yz plane.

    The strut direction is the tool's x axis after a yaw alpha about Z and a pitch beta about
    Y, u = (cos b cos a, cos b sin a, -sin b), scaled so that its x extent is L_f.
    """
    return L_f * np.tan(alpha), -L_f * np.tan(beta) / np.cos(alpha)


# ---------------------------------------------------------------- five-bar kinematics

def proximal_angle(y_E, z_E, z_motor, L_prox, L_dist, branch):
    """Inverse kinematics of one leg: the proximal angle q (rad) that puts E at (y_E, z_E).

    The elbow lies on the circle of radius L_prox about the motor (0, z_motor) and on the
    circle of radius L_dist about E; ``branch`` = +1 or -1 picks the intersection (the
    working mode). Raises ValueError naming the point where the leg cannot reach.
    """
    y_E = np.asarray(y_E, dtype=float)
    dz = np.asarray(z_E, dtype=float) - z_motor
    rho = np.hypot(y_E, dz)
    with np.errstate(divide="ignore", invalid="ignore"):
        cos_gap = (L_prox**2 + rho**2 - L_dist**2) / (2.0 * L_prox * rho)
    bad = ~(np.abs(cos_gap) <= 1.0)
    if np.any(bad):
        i = np.flatnonzero(bad.ravel())[0]
        raise ValueError(
            f"point (y, z) = ({np.ravel(y_E)[i]:.4f}, {np.ravel(z_E * np.ones_like(y_E))[i]:.4f}) m "
            f"is out of reach of the leg on the motor at z = {z_motor} m "
            f"(distance {np.ravel(rho)[i]:.4f} m not in [{abs(L_prox - L_dist)}, "
            f"{L_prox + L_dist}] m)")
    return np.arctan2(y_E, dz) + branch * np.arccos(cos_gap)


def elbow_points(robot: FiveBarRobot, q2, q3):
    """Elbows B (of arm 2) and D (of arm 3) as ((y_B, z_B), (y_D, z_D)) in m."""
    B = (robot.L2 * np.sin(q2), robot.z_A + robot.L2 * np.cos(q2))
    D = (robot.L3 * np.sin(q3), robot.z_C + robot.L3 * np.cos(q3))
    return B, D


def distal_point(robot: FiveBarRobot, q2, q3, assembly):
    """Forward kinematics: E = (y_E, z_E) in m for motor angles q2, q3 (rad).

    E is at L7 from B and L8 from D; ``assembly`` = +1 or -1 picks the side of BD (the
    assembly mode). Works with complex angles too (complex-step derivatives).
    """
    (yB, zB), (yD, zD) = elbow_points(robot, q2, q3)
    dy, dz = yD - yB, zD - zB
    d2 = dy * dy + dz * dz
    d = np.sqrt(d2)
    a = (robot.L7**2 - robot.L8**2 + d2) / (2.0 * d)
    h = np.sqrt(robot.L7**2 - a * a)
    ym, zm = yB + a * dy / d, zB + a * dz / d
    return ym - assembly * h * dz / d, zm + assembly * h * dy / d


def assembly_mode(robot: FiveBarRobot, q2, q3, y_E, z_E):
    """+1 or -1: the side of the line BD on which E lies (see distal_point)."""
    (yB, zB), (yD, zD) = elbow_points(robot, q2, q3)
    return np.sign((yD - yB) * (z_E - zB) - (zD - zB) * (y_E - yB))


# ---------------------------------------------------------------- potential and torques

def potential_energy(robot: FiveBarRobot, q2, q3, y_E, z_E, R_z, R_y):
    """Potential energy V (J) of one five-bar loaded at E by the tool, Eqs. 7-11.

    R_z, R_y (N): the tool holder's reactions at the distal joint (R_Ez, R_Ey for the first
    five-bar, R_Hz, R_Hy for the second), held constant (they depend on orientation only).
    """
    r = robot
    z2 = r.z_A + r.r2 * np.cos(q2)                                        # Eq. 8
    z3 = r.z_C + r.r3 * np.cos(q3)                                        # Eq. 9
    z7 = (r.L2 * np.cos(q2) + r.z_A - z_E) * r.r7 / r.L7 + z_E            # Eq. 10
    z8 = (r.L3 * np.cos(q3) + r.z_C - z_E) * r.r8 / r.L8 + z_E            # Eq. 11
    return (r.m2 * z2 + r.m3 * z3 + r.m7 * z7 + r.m8 * z8) * r.g + R_z * z_E + R_y * y_E


def _moment_coefficients(robot: FiveBarRobot, R_z, R_y):
    """M1..M4 of Appendix 1 (N m, N m, N, N); M3 = g(...) + R_z (the printed g(... + R_Ez)
    multiplies a force by g: a misplaced parenthesis)."""
    r = robot
    M1 = r.g * (r.m2 * r.r2 + r.m7 * r.L2 * r.r7 / r.L7)
    M2 = r.g * (r.m3 * r.r3 + r.m8 * r.L3 * r.r8 / r.L8)
    M3 = r.g * (r.m7 * (r.L7 - r.r7) / r.L7 + r.m8 * (r.L8 - r.r8) / r.L8) + R_z
    return M1, M2, M3, R_y


def _loop_terms(robot, q2, q3, y_E, z_E):
    """Appendix 1's 2 L2(...), 2 L3(...) (dPhi/dq) and the determinant A of dPhi/dE."""
    r = robot
    s2, c2, s3, c3 = np.sin(q2), np.cos(q2), np.sin(q3), np.cos(q3)
    b2 = 2.0 * r.L2 * (-y_E * c2 + (z_E - r.z_A) * s2)
    b3 = 2.0 * r.L3 * (-y_E * c3 + (z_E - r.z_C) * s3)
    A = 4.0 * (r.L3 * (-y_E * c3 + (z_E - r.z_A) * s3) - r.L2 * (-y_E * c2 + (z_E - r.z_C) * s2)
               + r.L2 * r.L3 * np.sin(q2 - q3) + y_E * (r.z_A - r.z_C))
    return b2, b3, A


def input_torques(robot: FiveBarRobot, q2, q3, y_E, z_E, R_z, R_y):
    """Motor torques (tau2, tau3) in N m holding one five-bar against gravity, Eq. 12.

    tau = dV/dQ|_E + (dE/dQ)^T dV/dE, with dE/dQ from the loop closures
    Phi_1 = |E - B|^2 - L7^2 = 0, Phi_2 = |E - D|^2 - L8^2 = 0. Same terms as Appendix 1
    (M1..M4, A), with the y and z partial derivatives of V paired as the derivation gives
    (see input_torques_appendix1 and docs/balancing.md).
    """
    r = robot
    M1, M2, M3, M4 = _moment_coefficients(robot, R_z, R_y)
    b2, b3, A = _loop_terms(robot, q2, q3, y_E, z_E)
    s2, c2, s3, c3 = np.sin(q2), np.cos(q2), np.sin(q3), np.cos(q3)
    tau2 = -M1 * s2 + b2 * (2 * M3 * (y_E - r.L3 * s3) - 2 * M4 * (z_E - r.z_C - r.L3 * c3)) / A
    tau3 = -M2 * s3 + b3 * (2 * M4 * (z_E - r.z_A - r.L2 * c2) - 2 * M3 * (y_E - r.L2 * s2)) / A
    return tau2, tau3


def input_torques_appendix1(robot: FiveBarRobot, q2, q3, y_E, z_E, R_z, R_y):
    """(tau2, tau3) in N m exactly as Appendix 1 prints them (kept for comparison only).

    The printed form pairs M3 (the z load) with the z offsets of the loop; it disagrees with
    the virtual-work derivative except where the loop is symmetric (docs/balancing.md).
    """
    r = robot
    M1, M2, M3, M4 = _moment_coefficients(robot, R_z, R_y)
    b2, b3, A = _loop_terms(robot, q2, q3, y_E, z_E)
    s2, c2, s3, c3 = np.sin(q2), np.cos(q2), np.sin(q3), np.cos(q3)
    tau2 = -M1 * s2 + b2 * (2 * M3 * (z_E - r.z_C - r.L3 * c3) + 2 * M4 * (-y_E + r.L3 * s3)) / A
    tau3 = -M2 * s3 + b3 * (2 * M3 * (-z_E + r.z_A + r.L2 * c2) + 2 * M4 * (y_E - r.L2 * s2)) / A
    return tau2, tau3


# ---------------------------------------------------------------- workspace (Tables I-II)

@dataclass(frozen=True)
class Workspace:
    """A grid over the yz positioning workspace (Table I) and tool orientations (Table II).

    y_min, z_min (m): lower-left corner of the square seen in the plane of the first five-bar
    (the text does not place it; docs/balancing.md says why we put it there); size_y, size_z
    (m): Table I's 500 mm x 500 mm; alpha (about Z) and beta (about Y) ranges in rad (Table
    II); n_*: samples along each axis (>= 1; 1 means the range's midpoint, or 0 rad for angles
    when ``zero_orientation``). branches: working modes (arm 2, arm 3) of both five-bars.
    """

    y_min: float = 0.45
    z_min: float = -0.45
    size_y: float = 0.5
    size_z: float = 0.5
    n_y: int = 11
    n_z: int = 11
    alpha_range: tuple = (np.radians(-45.0), np.radians(45.0))
    beta_range: tuple = (np.radians(-50.0), np.radians(35.0))
    n_alpha: int = 5
    n_beta: int = 5
    zero_orientation: bool = False
    branches: tuple = (1, -1)

    def __post_init__(self):
        for name in ("size_y", "size_z"):
            if not getattr(self, name) > 0.0:
                raise ValueError(f"{name} = {getattr(self, name)} must be > 0")
        for name in ("n_y", "n_z", "n_alpha", "n_beta"):
            if int(getattr(self, name)) < 1:
                raise ValueError(f"{name} = {getattr(self, name)} must be >= 1")
        for name in ("alpha_range", "beta_range"):
            lo, hi = getattr(self, name)
            if not (-np.pi / 2 < lo <= hi < np.pi / 2):
                raise ValueError(f"{name} = {getattr(self, name)} must lie in (-pi/2, pi/2), "
                                 "low <= high")
        if any(b not in (1, -1) for b in self.branches) or len(self.branches) != 2:
            raise ValueError(f"branches = {self.branches} must be two of +1 / -1")


def workspace_samples(ws: Workspace):
    """Sample points of the workspace: dict of flat arrays y_E, z_E, alpha, beta (m, rad)."""
    y = np.linspace(ws.y_min, ws.y_min + ws.size_y, ws.n_y)
    z = np.linspace(ws.z_min, ws.z_min + ws.size_z, ws.n_z)

    def angles(lo, hi, n):
        if n == 1:
            return np.array([0.0 if ws.zero_orientation else 0.5 * (lo + hi)])
        return np.linspace(lo, hi, n)

    a = angles(*ws.alpha_range, ws.n_alpha)
    b = angles(*ws.beta_range, ws.n_beta)
    Y, Z, A, Bt = (g.ravel() for g in np.meshgrid(y, z, a, b, indexing="ij"))
    return {"y_E": Y, "z_E": Z, "alpha": A, "beta": Bt}


def _continuous(q):
    """Angles (rad) wrapped into one 2 pi window centred on their circular mean."""
    centre = np.angle(np.mean(np.exp(1j * q)))
    return centre + np.angle(np.exp(1j * (q - centre)))


def leg_angles(robot: FiveBarRobot, y, z, branches):
    """Motor angles (q_a, q_c) in rad of one five-bar whose distal joint is at (y, z), m."""
    qa = proximal_angle(y, z, robot.z_A, robot.L2, robot.L7, branches[0])
    qc = proximal_angle(y, z, robot.z_C, robot.L3, robot.L8, branches[1])
    return _continuous(qa), _continuous(qc)


@dataclass(frozen=True)
class WorkspaceTorques:
    """Motor angles q (rad) and gravity torques tau (N m), shape (N, 4) for motors 2, 3, 4, 5,
    at the N samples (dict of flat arrays: y_E, z_E, alpha, beta, y_H, z_H in m and rad)."""

    samples: dict
    q: np.ndarray
    tau: np.ndarray
    motors: tuple = (2, 3, 4, 5)


def workspace_torques(robot: FiveBarRobot, ws: Workspace) -> WorkspaceTorques:
    """Gravity torques of motors 2-5 over the workspace (Eqs. 2-12).

    The first five-bar carries (R_Ez, R_Ey) at E; the second, in the plane L_f away, carries
    (R_Hz, R_Hy) at H, offset from E by the strut's yz projection. Raises ValueError naming
    the first sample that does not assemble.
    """
    s = dict(workspace_samples(ws))
    R_Ez, R_Ey, R_Hz, R_Hy = tool_reactions(robot, s["alpha"], s["beta"])
    dy, dz = strut_offset_yz(robot.L_f, s["alpha"], s["beta"])
    s["y_H"], s["z_H"] = s["y_E"] + dy, s["z_E"] + dz
    q2, q3 = leg_angles(robot, s["y_E"], s["z_E"], ws.branches)
    q4, q5 = leg_angles(robot, s["y_H"], s["z_H"], ws.branches)
    t2, t3 = input_torques(robot, q2, q3, s["y_E"], s["z_E"], R_Ez, R_Ey)
    t4, t5 = input_torques(robot, q4, q5, s["y_H"], s["z_H"], R_Hz, R_Hy)
    return WorkspaceTorques(samples=s, q=np.column_stack([q2, q3, q4, q5]),
                            tau=np.column_stack([t2, t3, t4, t5]))
