"""Optimum static balancing of the five-bar ultrasound robot: Tables III-V, Fig. 10, and more.

Source: Lessard, Bigras, Bonev, Briot, Arakelian, IFToMM 2007 (hal-00451939). The gravity
model is in balancing_gravity, the optimal balancers in balancing_optimum and the flexure
pivots in balancing_pivots; this module runs them over the workspace and compares with the
paper (docs/balancing.md).
"""
from pathlib import Path

import numpy as np

from ..data import load_toml
from .balancing_gravity import Workspace, load_robot, workspace_torques
from .balancing_optimum import (
    max_reduction_pct, optimal_counterweight, optimal_coupled_springs,
    optimal_spring, optimal_spring_and_torsion, optimal_torsion_spring, rms_reduction_pct)
from .balancing_pivots import (
    flexure_material, negative_stiffness_preload, size_flexure_pivot)
from .tables import write_rows

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
    mat = flexure_material(material)
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


# ---------------------------------------------------------------- reproduction of the paper

def _rel_diff(ours, published):
    return (ours - published) / abs(published) if published else None


def comparison_rows(result: dict) -> list:
    """Our Tables III-V beside the paper's: rows {quantity, flexfem, published, rel_diff,
    note}; angles in degrees, C in N m, K in N m/rad, reductions in %."""
    rows = []
    for method in METHODS:
        ours = {r["motor"]: r for r in result["results"] if r["method"] == method}
        table = {"spring": "Table III", "torsion": "Table IV", "counterweight": "Table V"}[method]
        for paper in paper_table(method):
            r = ours.get(paper["motor"])
            if r is None:
                continue
            p = r["params"]
            angle_key = "q_c_rad" if method == "counterweight" else "q_k_rad"
            value_key = "K_Nm_per_rad" if method == "torsion" else "C_Nm"
            unit = "N m/rad" if method == "torsion" else "N m"
            angle = np.degrees(p[angle_key])        # a torsion q_k is not periodic: no wrap
            note = f"{table} {method}, motor {paper['motor']}"
            items = [(f"{angle_key[:3]} motor {paper['motor']} {method} (deg)", angle,
                      paper["q_deg"], note + f"; difference {angle - paper['q_deg']:+.1f} deg"),
                     (f"{value_key.split('_')[0]} motor {paper['motor']} {method} ({unit})",
                      p[value_key], paper["param"],
                      note + ("; Table III's C is ~44x below Table V's for the same optimum"
                              if method == "spring" else "")),
                     (f"RMS reduction motor {paper['motor']} {method} (%)",
                      r["rms_reduction_pct"], paper["rms_reduction_pct"], note),
                     (f"max torque reduction motor {paper['motor']} {method} (%)",
                      r["max_reduction_pct"], paper["max_reduction_pct"], note)]
            rows += [{"quantity": q, "flexfem": float(v), "published": float(pub),
                      "rel_diff": _rel_diff(float(v), float(pub)), "note": n}
                     for q, v, pub, n in items]
    return rows


def _flat(d: dict, prefix="") -> dict:
    out = {}
    for k, v in d.items():
        if isinstance(v, dict):
            out.update(_flat(v, f"{prefix}{k}."))
        else:
            out[prefix + k] = v
    return out


def plot_torques_zero_orientation(path: Path, workspace: Workspace, result: dict, robot=None):
    """Fig. 10: motor torques (N m) over the workspace at alpha = beta = gamma = 0, without
    and with the optimal springs of ``result`` (fitted over the whole workspace)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    flat = default_workspace(n_alpha=1, n_beta=1, zero_orientation=True,
                             n_y=workspace.n_y, n_z=workspace.n_z,
                             y_min=workspace.y_min, z_min=workspace.z_min,
                             size_y=workspace.size_y, size_z=workspace.size_z,
                             branches=workspace.branches)
    wt = workspace_torques(robot or load_robot(), flat)
    springs = {r["motor"]: r["params"] for r in result["results"] if r["method"] == "spring"}
    fig, axes = plt.subplots(2, 2, figsize=(10, 7), sharex=True)
    s = np.arange(wt.q.shape[0])
    for i, (ax, motor) in enumerate(zip(axes.ravel(), wt.motors)):
        q, tau = wt.q[:, i], wt.tau[:, i]
        p = springs[motor]
        ax.plot(s, tau, "k--", label="unbalanced")
        ax.plot(s, tau + p["C_Nm"] * np.sin(q - p["q_k_rad"]), "b-", label="spring balanced")
        ax.set_title(f"actuator {motor}")
        ax.set_ylabel("torque (N m)")
        ax.grid(True, alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel(f"sample ({flat.n_y} columns in y, z varying fastest over {flat.n_z})")
    axes[0, 0].legend()
    fig.suptitle("Motor torques at alpha = beta = gamma = 0 (cf. Lessard et al. Fig. 10)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def reproduce(out_dir: Path, quick: bool = False) -> dict:
    """Tables III-V (CSV, beside the paper), Fig. 10 (PNG), the beyond-the-paper balancers
    and the flexure pivot sizing, written into out_dir; returns the JSON-able summary."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    ws = default_workspace(quick=quick)
    result = balance_robot("all", ws)
    comparisons = comparison_rows(result)
    tables, figures = [], []
    for method in METHODS:
        name = f"balancing_{PAPER_TABLES[method]}.csv"
        write_rows(out_dir / name, [r for r in comparisons if f" {method}" in r["quantity"]])
        tables.append(name)
    beyond = beyond_paper(ws)
    write_rows(out_dir / "balancing_beyond_paper.csv", [_flat(r) for r in beyond])
    pivots = pivot_designs(ws)
    pivot_rows = [_flat(r) for r in pivots]
    keys = ["motor"] + sorted({k for r in pivot_rows for k in r} - {"motor"})
    write_rows(out_dir / "balancing_pivots.csv", pivot_rows, keys)
    sensitivity = sensitivity_rows(quick)
    write_rows(out_dir / "balancing_sensitivity.csv", sensitivity)
    tables += ["balancing_beyond_paper.csv", "balancing_pivots.csv", "balancing_sensitivity.csv"]
    plot_torques_zero_orientation(out_dir / "balancing_fig10.png", ws, result)
    figures.append("balancing_fig10.png")
    from .balancing_pivot_fem import pivot_fem_study  # gmsh: only when run
    pivot_fem = pivot_fem_study(out_dir, quick=quick, workspace=ws)
    tables += pivot_fem["tables"]
    figures += pivot_fem["figures"]
    notes = [f"pivot FEM, motor {r['motor']} ({r['design']}, {r['formulation']}): stiffness "
             f"{r['stiffness_linear_Nm_per_rad']:.4g} N m/rad (beam theory "
             f"{100 * r['stiffness_error_linear']:+.2f} %), peak von Mises "
             f"{r['stress_fem_peak_Pa'] / 1e6:.0f} MPa (beam theory {r['stress_beam_Pa'] / 1e6:.0f} MPa), "
             f"safety factor {r['safety_factor_fem']:.2f} (beam theory {r['safety_factor_beam']:.2f})"
             for r in pivot_fem["rows"]]
    from .balancing_negative_pivot import negative_pivot_study  # gmsh: only when run
    negative = negative_pivot_study(out_dir, quick=quick, workspace=ws)
    tables += negative["tables"]
    figures += negative["figures"]
    notes += [f"negative-stiffness leaf, motor {r['motor']}: K {r['stiffness_at_motor_Nm_per_rad']:.3g} N m/rad at "
              f"the motor (N = {r['transmission_ratio']:g}), L {r['L_m'] * 1e3:.0f} mm, t {r['t_m'] * 1e3:.2f} mm, "
              f"w {r['w_m'] * 1e3:.0f} mm, preload {r['P_N']:.0f} N; FEM small-angle K "
              f"{r['fem_stiffness_fem_small_Nm_per_rad']:.4g} N m/rad at the pivot (beam-column "
              f"{r['fem_stiffness_closed_Nm_per_rad']:.4g}), peak von Mises {r['fem_stress_fem_peak_nodal_Pa'] / 1e6:.0f} MPa, "
              f"RMS reduction {r['rms_reduction_leaf_fem_pct']:.1f} % (ideal torsion spring "
              f"{r['rms_reduction_ideal_torsion_pct']:.1f} %)" for r in negative["rows"]]
    return {"comparisons": comparisons, "figures": figures, "tables": tables, "notes": notes,
            "pivot_fem": pivot_fem["rows"], "negative_pivot": negative["rows"],
            "n_samples": result["n_samples"], "results": result["results"],
            "beyond_paper": beyond, "pivots": pivots, "sensitivity": sensitivity,
            "workspace": {"y_range_m": [ws.y_min, ws.y_min + ws.size_y],
                          "z_range_m": [ws.z_min, ws.z_min + ws.size_z],
                          "branches": list(ws.branches)}}
