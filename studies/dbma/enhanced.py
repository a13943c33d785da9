"""An elastic-beam (compliance) model of the DBMA beyond the paper's pseudo-rigid-body model.

Each hinge is an Euler-Bernoulli beam with its axial AND bending compliance (length l,
thickness b, width d); each arm is a Timoshenko beam (width c, thickness d) joining the two
hinge roots, which sit h apart across the arm; the input and output blocks are rigid. This is
the "translational and rotational stiffness" modelling of Ling et al. (Smart Mater. Struct. 25
(2016) 075022), solved here by the matrix displacement (stiffness/compliance) method on the
quarter of one bow-type row (references in data/literature_models.toml).

Quarter of a row, x from the input block to the output block:
  node 0 (input-block root of hinge 1) -- hinge 1 -- node 1 -- arm -- node 2 -- hinge 2 -- node 3
  node 0 at (0, 0), node 1 at (l, 0), node 2 at (l + e, h), node 3 at (2 l + e, h).
  Input block: ux0 = -delta (half the actuator stroke), uy0 = 0, theta0 = 0 (symmetry).
  Output block: ux3 = 0, theta3 = 0 (symmetry), uy3 free: the output.
The row's ratio is r = |uy3| / delta. The DBMA's two rows share the actuator stroke and their
outputs add ("two bow-type amplifiers used in series", Section 2), so R = 2 r.

All quantities in SI units (m, Pa, N/m).
"""
import numpy as np

from ...data import load_toml
from ...geometry.dbma.params import DBMAParams

ROWS = 2  # bow-type rows whose outputs add (Section 2, Figure 3)
# Timoshenko shear coefficient of a rectangular section (data/literature_models.toml)
SHEAR_FACTOR = load_toml("literature_models.toml")["timoshenko_shear"]["shear_coefficient_rectangle"]
RIGID = 1e6  # axial-stiffness multiplier for 'axially rigid' hinges (conditioning ~ 1e6 l^2/b^2)


def frame_element_stiffness(x1, y1, x2, y2, E, A, I, G=None, kappa=SHEAR_FACTOR):
    """6x6 global stiffness of a straight planar frame element (N/m, N, N m).

    Euler-Bernoulli bending when G is None, Timoshenko (shear parameter
    phi = 12 E I / (kappa G A L^2)) otherwise; dofs (ux, uy, theta) at each end.
    """
    L = np.hypot(x2 - x1, y2 - y1)
    c, s = (x2 - x1) / L, (y2 - y1) / L
    phi = 0.0 if G is None else 12 * E * I / (kappa * G * A * L**2)
    k = E * I / ((1 + phi) * L**3)
    a = E * A / L
    local = np.array([
        [a, 0, 0, -a, 0, 0],
        [0, 12 * k, 6 * k * L, 0, -12 * k, 6 * k * L],
        [0, 6 * k * L, (4 + phi) * k * L**2, 0, -6 * k * L, (2 - phi) * k * L**2],
        [-a, 0, 0, a, 0, 0],
        [0, -12 * k, -6 * k * L, 0, 12 * k, -6 * k * L],
        [0, 6 * k * L, (2 - phi) * k * L**2, 0, -6 * k * L, (4 + phi) * k * L**2],
    ])
    T = np.zeros((6, 6))
    for i in (0, 3):
        T[i:i + 3, i:i + 3] = [[c, s, 0], [-s, c, 0], [0, 0, 1]]
    return T.T @ local @ T


def _member_sections(p: DBMAParams, axially_rigid_hinges: bool) -> dict:
    """(A, I, G) of each member kind (m^2, m^4, Pa): hinges Euler-Bernoulli, arms Timoshenko."""
    G = p.E / (2 * (1 + p.nu))
    axial = RIGID if axially_rigid_hinges else 1.0
    return {"hinge": (p.d * p.b * axial, p.d * p.b**3 / 12, None),
            "arm": (p.d * p.c, p.d * p.c**3 / 12, G)}


def solve_frame(p: DBMAParams, xy, members, fixed: dict, loads: dict, rigid_links=(),
                axially_rigid_hinges: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Small-displacement solution of a planar frame of DBMA hinges and arms.

    xy: node coordinates (m); members: (node i, node j, "hinge" | "arm"); rigid_links:
    (master, slave) node pairs joined by a rigid body (slave follows master: ux_s = ux_m -
    dy theta_m, uy_s = uy_m + dx theta_m, theta_s = theta_m); fixed {dof: m or rad} and loads
    {dof: N or N m} on dofs 3 node + (0: ux, 1: uy, 2: theta), never on a slave node.
    Returns (u, K): the displacements of every dof and the assembled stiffness (SI units).
    """
    n = len(xy)
    sections = _member_sections(p, axially_rigid_hinges)
    K = np.zeros((3 * n, 3 * n))
    for i, j, kind in members:
        A, I, G = sections[kind]
        dofs = [3 * i, 3 * i + 1, 3 * i + 2, 3 * j, 3 * j + 1, 3 * j + 2]
        K[np.ix_(dofs, dofs)] += frame_element_stiffness(*xy[i], *xy[j], p.E, A, I, G)
    slaves = {slave: master for master, slave in rigid_links}
    keep = [k for k in range(3 * n) if k // 3 not in slaves]
    column = {k: c for c, k in enumerate(keep)}
    T = np.zeros((3 * n, len(keep)))
    for k in keep:
        T[k, column[k]] = 1.0
    for slave, master in slaves.items():
        dx, dy = np.subtract(xy[slave], xy[master])
        m = [column[3 * master + q] for q in range(3)]
        T[3 * slave, m] = [1.0, 0.0, -dy]
        T[3 * slave + 1, m] = [0.0, 1.0, dx]
        T[3 * slave + 2, m] = [0.0, 0.0, 1.0]
    Kr = T.T @ K @ T
    f = np.zeros(len(keep))
    for dof, value in loads.items():
        f[column[dof]] = value
    known = np.array(sorted(column[dof] for dof in fixed))
    free = np.setdiff1d(np.arange(len(keep)), known)
    q = np.zeros(len(keep))
    q[known] = [fixed[keep[c]] for c in known]
    q[free] = np.linalg.solve(Kr[np.ix_(free, free)], f[free] - Kr[np.ix_(free, known)] @ q[known])
    return T @ q, K


def _quarter(p: DBMAParams, rigid_arm: bool):
    """Nodes, members and rigid links of the quarter row (module docstring)."""
    xy = [(0.0, 0.0), (p.l, 0.0), (p.l + p.e, p.h), (2 * p.l + p.e, p.h)]
    members = [(0, 1, "hinge"), (2, 3, "hinge")] + ([] if rigid_arm else [(1, 2, "arm")])
    return xy, members, [(1, 2)] if rigid_arm else []


def _solve_quarter(p, fixed, loads, rigid_arm=False, axially_rigid_hinges=False):
    xy, members, links = _quarter(p, rigid_arm)
    return solve_frame(p, xy, members, fixed, loads, links, axially_rigid_hinges)


STROKE = 1e-6  # input-block displacement delta of the linear solves (m)


def _stroke(p: DBMAParams, rigid_arm: bool = False, axially_rigid_hinges: bool = False):
    """(u, K) of the quarter row with the input block moved by -STROKE along x, no rotation,
    the output block free along y (no load, no rotation, no x motion: symmetry)."""
    return _solve_quarter(p, {0: -STROKE, 1: 0.0, 2: 0.0, 9: 0.0, 11: 0.0}, {}, rigid_arm,
                          axially_rigid_hinges)


def row_amplification_ratio(p: DBMAParams, rigid_arm: bool = False,
                            axially_rigid_hinges: bool = False) -> float:
    """Output displacement over input stroke of one bow-type row, r = |uy3| / delta (-).

    Input block moved by -delta along x with no rotation, output block free along y with
    no load, no rotation and no x motion (symmetry).
    """
    u, _ = _stroke(p, rigid_arm, axially_rigid_hinges)
    return float(abs(u[10])) / STROKE


def amplification_ratio_enhanced(p: DBMAParams, rigid_arm: bool = False) -> float:
    """Amplification ratio of the DBMA from the elastic-beam model, R = 2 r (-)."""
    return ROWS * row_amplification_ratio(p, rigid_arm=rigid_arm)


def amplification_ratio_rigid_arm(p: DBMAParams) -> float:
    """Closed form of the elastic-hinge, rigid-arm model: R = 2 (e + l) h / (h^2 + b^2/3) (-).

    Derived in docs/dbma-analytical.md: with no output load the hinges carry the axial force
    N and the moments +-N h/2 (the paper's Eq. 4), so delta = N l (2/(E A) + h^2/(2 E I))
    and uy = (e + l) N h l / (2 E I); with I/A = b^2/12 the row ratio is
    (e + l) h / (h^2 + b^2/3). It tends to the kinematic 2 (e + l)/h for b -> 0 and to 0
    for h -> 0.
    """
    return ROWS * (p.e + p.l) * p.h / (p.h**2 + p.b**2 / 3)


def amplification_ratio_kinematic(p: DBMAParams) -> float:
    """Rigid-body limit: pivots at the hinge centres, R = 2 (e + l) / h (-)."""
    if p.h == 0:
        raise ValueError("h = 0.0 m: the kinematic ratio is unbounded; it needs h > 0")
    return ROWS * (p.e + p.l) / p.h


def output_stiffness_enhanced(p: DBMAParams, rigid_arm: bool = False,
                              input_blocked: bool = True) -> float:
    """Output stiffness of the DBMA, force over output displacement (N/m).

    One quarter row gives k_q = Fy / uy3, with the input block clamped (input_blocked: the
    actuator held, the working mode with the actuator in place) or free to slide along x
    (no actuator: only hinge bending resists). A row's output block is held by two quarters
    in parallel and the row spans two output blocks in series, so a row has k_q; the two rows
    in series give k_q / 2.
    """
    fixed = {1: 0.0, 2: 0.0, 9: 0.0, 11: 0.0}
    if input_blocked:
        fixed[0] = 0.0
    force = 1.0
    u, _ = _solve_quarter(p, fixed, {10: force}, rigid_arm)
    return force / float(abs(u[10])) / ROWS


def input_stiffness_enhanced(p: DBMAParams, rigid_arm: bool = False) -> float:
    """Stiffness the actuator sees with the output free: force over total stroke (N/m).

    Each input block of a row carries two quarters (force 2 F_q) and the stroke 2 delta spans
    the two input blocks, so a row has F_q / delta; the two rows share the stroke (parallel).
    """
    return _input_stiffness(*_stroke(p, rigid_arm))


def _input_stiffness(u, K) -> float:
    return ROWS * float(abs((K @ u)[0])) / STROKE


def amplification_ratio_post_chain(p: DBMAParams, post_rotation_blocked: bool = False) -> float:
    """R of the "two stages in one chain" layout: input block - row-1 arm - post - row-2 arm -
    output beam, per quarter (the layout of geometry/dbma.py as of this writing), (-).

    Nodes (m): hinge 1a 0 -> 1, arm 1 -> 2, hinge 1b 2 -> 3 (post, bottom), the post a rigid
    body from 3 to 4 (ll - c higher), hinge 3b 4 -> 5, arm 5 -> 6, hinge 3a 6 -> 7 (output
    beam). Input block: ux0 = +delta, uy0 = theta0 = 0; output beam: ux7 = theta7 = 0 (the
    symmetry axis), uy7 free. R = uy7 / delta, signed (> 0: the beam rises), with the bottom
    half mirrored (output 2 uy7 for the stroke 2 delta). The post is a free lever unless
    post_rotation_blocked: the two arms then share the stroke and R tends to r, not 2 r.
    """
    lever = p.ll - p.c  # distance between the post's two hinge lines (m)
    xy = [(0.0, 0.0), (p.l, 0.0), (p.l + p.e, p.h), (2 * p.l + p.e, p.h),
          (2 * p.l + p.e, p.h + lever), (p.l + p.e, p.h + lever), (p.l, lever), (0.0, lever)]
    members = [(0, 1, "hinge"), (1, 2, "arm"), (2, 3, "hinge"),
               (4, 5, "hinge"), (5, 6, "arm"), (6, 7, "hinge")]
    delta = 1e-6
    fixed = {0: delta, 1: 0.0, 2: 0.0, 21: 0.0, 23: 0.0}
    if post_rotation_blocked:
        fixed[11] = 0.0
    u, _ = solve_frame(p, xy, members, fixed, {}, rigid_links=[(3, 4)])
    return float(u[22]) / delta


def enhanced_metrics(p: DBMAParams) -> dict:
    """Elastic-beam model for one design: ratios (-) and stiffnesses (N/m), keyed as in
    ``dbma_figures.analytical_metrics``."""
    u, K = _stroke(p)  # R_enhanced and K_in_enhanced: one solve
    return {
        "R_enhanced": ROWS * float(abs(u[10])) / STROKE,
        "R_rigid_arm": amplification_ratio_rigid_arm(p),
        "R_kinematic": amplification_ratio_kinematic(p) if p.h > 0 else float("inf"),
        "K_out_enhanced": output_stiffness_enhanced(p),
        "K_out_free_input_enhanced": output_stiffness_enhanced(p, input_blocked=False),
        "K_in_enhanced": _input_stiffness(u, K),
        "R_post_chain": amplification_ratio_post_chain(p),
        "R_post_chain_guided": amplification_ratio_post_chain(p, post_rotation_blocked=True),
    }
