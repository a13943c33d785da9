"""Optimum static balancing of the five-bar ultrasound robot over its workspace.

Source: Lessard, Bigras, Bonev, Briot, Arakelian, IFToMM 2007 (hal-00451939). The gravity
model is in balancing_gravity, the optimal balancers in balancing_optimum and the flexure
pivots in balancing_pivots; this module runs them over the workspace (report.py compares
with the paper, docs/balancing.md).
"""

import numpy as np

from ...data import load_toml
from ...fem import material as library_material
from .gravity import Workspace, load_robot, workspace_torques
from .optimum import (
    max_reduction_pct,
    optimal_counterweight,
    optimal_coupled_springs,
    optimal_spring,
    optimal_spring_and_torsion,
    optimal_torsion_spring,
    rms_reduction_pct,
)
from .pivots import negative_stiffness_preload, size_flexure_pivot

METHODS = {"spring": optimal_spring, "torsion": optimal_torsion_spring,
           "counterweight": optimal_counterweight}
PAPER_TABLES = {"spring": "table3_spring", "torsion": "table4_torsion",
                "counterweight": "table5_counterweight"}


def default_workspace(quick: bool = False, **overrides) -> Workspace:
    """Table I's 0.5 m x 0.5 m square, y in [0.25, 0.75] m, z in [-0.25, 0.25] m, both
    proximal arms in working mode -1, Table II's yaw (about Z) and pitch (about Y) ranges.

    The paper does not place the square; this placement (centre 0.5 m out from the motor axis,
    at the level z = 0 just below motor A) is, among all the placements and working modes
    where every sample assembles, near the one whose spring optima agree best with Tables III
    and V (docs/balancing.md). quick: a 6 x 6 x 3 x 3 grid instead of 11 x 11 x 5 x 5.
    """
    n = dict(n_y=6, n_z=6, n_alpha=3, n_beta=3) if quick else {}
    table2 = load_toml("balancing_robot.toml")["table2_orientation"]
    settings = dict(y_min=0.25, z_min=-0.25, size_y=0.5, size_z=0.5, branches=(-1, -1),
                    alpha_range=tuple(np.radians(table2["around_z_deg"])),
                    beta_range=tuple(np.radians(table2["around_y_deg"])), **n)
    settings.update(overrides)
    return Workspace(**settings)


def paper_table(method: str) -> list:
    """Rows of Table III, IV or V for ``method``: dicts motor, q_deg, param, rms, max (%)."""
    table = load_toml("balancing_robot.toml")[PAPER_TABLES[method]]
    angle = table.get("q_k_deg", table.get("q_c_deg"))
    param = table.get("K_Nm_per_rad", table.get("C_Nm"))
    return [{"motor": m, "q_deg": a, "param": p, "rms_reduction_pct": r, "max_reduction_pct": x}
            for m, a, p, r, x in zip(table["motor"], angle, param, table["rms_reduction_pct"],
                                     table["max_reduction_pct"])]


def _check_method(method: str):
    if method not in (*METHODS, "all"):
        raise ValueError(f"method = {method!r} must be one of {[*METHODS, 'all']}")


def balance_robot(method: str = "all", workspace: Workspace | None = None, robot=None) -> dict:
    """Optimal balancers of motors 2-5 over the workspace, with RMS and max reductions (%).

    Returns {"results": [{motor, method, params (SI), rms_reduction_pct,
    max_reduction_pct}, ...], "n_samples": N}. method: spring, torsion, counterweight or all.
    """
    _check_method(method)
    workspace = workspace or default_workspace()
    robot = robot or load_robot()
    wt = workspace_torques(robot, workspace)
    methods = list(METHODS) if method == "all" else [method]
    results = []
    for name in methods:
        for i, motor in enumerate(wt.motors):
            q, tau = wt.q[:, i], wt.tau[:, i]
            balancer = METHODS[name](q, tau)
            balanced = tau + balancer.torque(q)
            results.append({"motor": motor, "method": name, "params": balancer.params(),
                            "rms_reduction_pct": rms_reduction_pct(tau, balanced),
                            "max_reduction_pct": max_reduction_pct(tau, balanced)})
    return {"results": results, "n_samples": int(wt.q.shape[0])}


def beyond_paper(workspace: Workspace | None = None, robot=None) -> list:
    """More variables at once (the paper's conclusion): per motor, the RMS reduction (%) of
    the paper's spring, of a spring plus a torsion spring, and of arm springs plus one spring
    coupling the two arms of each five-bar (jointly optimal for the pair)."""
    workspace = workspace or default_workspace()
    wt = workspace_torques(robot or load_robot(), workspace)
    rows = []
    for a, b in ((0, 1), (2, 3)):
        sa, sb, c = optimal_coupled_springs(wt.q[:, a], wt.q[:, b], wt.tau[:, a], wt.tau[:, b])
        coupling = c * np.sin(wt.q[:, a] - wt.q[:, b])
        for i, arm_spring, sign in ((a, sa, 1.0), (b, sb, -1.0)):
            q, tau = wt.q[:, i], wt.tau[:, i]
            both = optimal_spring_and_torsion(q, tau)
            coupled = tau + arm_spring.torque(q) + sign * coupling
            rows.append({
                "motor": wt.motors[i],
                "spring_rms_reduction_pct": rms_reduction_pct(tau, tau + optimal_spring(q, tau).torque(q)),
                "spring_torsion_rms_reduction_pct": rms_reduction_pct(tau, tau + both.torque(q)),
                "spring_torsion_max_reduction_pct": max_reduction_pct(tau, tau + both.torque(q)),
                "spring_torsion_params": both.params(),
                "coupled_rms_reduction_pct": rms_reduction_pct(tau, coupled),
                "coupled_max_reduction_pct": max_reduction_pct(tau, coupled),
                "coupling_C_Nm": c})
    return rows


def pivot_designs(workspace: Workspace | None = None, robot=None, material="spring_steel_aisi1095",
                  safety_factor=2.0, max_pivot_rotation_rad=np.radians(15.0)) -> list:
    """Flexure pivots replacing the optimal torsion springs of motors with K > 0.

    Two readings per motor: (1) the pivot unstressed at q_k of Table IV (its rotation is
    q - q_k over the workspace): sized if possible, else the reason; (2) the pivot unstressed
    at the middle of the motor's range, a constant torque K (q_k - q_mid) supplied apart
    (e.g. by the arm spring or a counterweight), through the smallest integer transmission
    ratio N keeping the pivot rotation <= max_pivot_rotation_rad. K < 0: the compressive
    preload (N) on a 0.1 m lever that would give it. SI units throughout.
    """
    wt = workspace_torques(robot or load_robot(), workspace or default_workspace())
    mat = library_material(material)
    rows = []
    for i, motor in enumerate(wt.motors):
        q, tau = wt.q[:, i], wt.tau[:, i]
        spring = optimal_torsion_spring(q, tau)
        row = {"motor": motor, "K_Nm_per_rad": spring.K, "q_k_rad": spring.q_k}
        if spring.K <= 0.0:
            row["negative_stiffness_preload_N_at_0.1m"] = negative_stiffness_preload(spring.K, 0.1)
            rows.append(row)
            continue
        try:
            row["at_q_k"] = size_flexure_pivot(spring.K, (q - spring.q_k).tolist(), mat,
                                               safety_factor).as_dict()
        except ValueError as error:
            row["at_q_k"] = {"infeasible": str(error)}
        q_mid = 0.5 * (q.min() + q.max())
        half = 0.5 * (q.max() - q.min())
        ratio = float(np.ceil(half / max_pivot_rotation_rad))
        row["constant_torque_Nm"] = spring.K * (spring.q_k - q_mid)
        try:
            row["at_mid_range"] = size_flexure_pivot(spring.K, (q - q_mid).tolist(), mat,
                                                     safety_factor,
                                                     transmission_ratio=ratio).as_dict()
        except ValueError as error:
            row["at_mid_range"] = {"infeasible": str(error)}
        rows.append(row)
    return rows


def sensitivity_rows(quick: bool = False) -> list:
    """Spring-balanced RMS reductions (%) per motor under the readings the text leaves open:
    the workspace size (Table I vs a smaller square, the 'first prototype'), the orientation
    ranges (Table II vs alpha = beta = 0) and r13 (not printed in Appendix 3)."""
    variants = [("as chosen (Table I square, Table II angles)", {}, {}),
                ("0.3 m x 0.3 m square, same centre", {"y_min": 0.35, "z_min": -0.15,
                                                       "size_y": 0.3, "size_z": 0.3}, {}),
                ("alpha = beta = 0 only", {"n_alpha": 1, "n_beta": 1,
                                           "zero_orientation": True}, {}),
                ("r13 = L_f / 2 = 0.05 m", {}, {"r13": 0.05}),
                ("r13 = L_f = 0.1 m (the garbled 0.1 m read as r13)", {}, {"r13": 0.1})]
    rows = []
    for label, ws_overrides, robot_overrides in variants:
        result = balance_robot("spring", default_workspace(quick, **ws_overrides),
                               load_robot(**robot_overrides))
        row = {"variant": label}
        for r in result["results"]:
            row[f"motor{r['motor']}_rms_reduction_pct"] = r["rms_reduction_pct"]
            row[f"motor{r['motor']}_q_k_deg"] = float(np.degrees(r["params"]["q_k_rad"]))
        rows.append(row)
    return rows

