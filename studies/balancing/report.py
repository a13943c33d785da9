"""The balancing section of the report: Tables III-V beside the paper, Fig. 10, the balancers
beyond the paper and the flexure pivots (Lessard, Bigras, Bonev, Briot, Arakelian, IFToMM
2007; docs/balancing.md)."""
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ..engine.tables import write_rows  # noqa: E402
from .design import (  # noqa: E402
    METHODS,
    PAPER_TABLES,
    balance_robot,
    beyond_paper,
    default_workspace,
    paper_table,
    pivot_designs,
    sensitivity_rows,
)
from .gravity import Workspace, load_robot, workspace_torques  # noqa: E402
from .negative_pivot_study import negative_pivot_study  # noqa: E402
from .pivot_fem import pivot_fem_study  # noqa: E402


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
    pivot_fem = pivot_fem_study(out_dir, quick=quick, workspace=ws)
    tables += pivot_fem["tables"]
    figures += pivot_fem["figures"]
    notes = [f"pivot FEM, motor {r['motor']} ({r['design']}, {r['formulation']}): stiffness "
             f"{r['stiffness_linear_Nm_per_rad']:.4g} N m/rad (beam theory "
             f"{100 * r['stiffness_error_linear']:+.2f} %), peak von Mises "
             f"{r['stress_fem_peak_Pa'] / 1e6:.0f} MPa (beam theory {r['stress_beam_Pa'] / 1e6:.0f} MPa), "
             f"safety factor {r['safety_factor_fem']:.2f} (beam theory {r['safety_factor_beam']:.2f})"
             for r in pivot_fem["rows"]]
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
