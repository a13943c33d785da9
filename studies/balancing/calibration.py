"""The workspace the paper does not give, fitted on Table III's RMS reductions alone.

The paper gives the workspace's size (Table I, 500 mm x 500 mm) but not where it lies, and the
RMS reductions of every balancer depend on both. Three numbers (the square's lower corner
y_min, z_min and its side, m) are fitted so that the springs' RMS reductions match Table III:
a declared calibration, reported apart from agreement. What the fitted workspace then
predicts for the torsion springs (Table IV) and the counterweights' sizes and angles (Table V)
is the test of the reading; the counterweights' RMS reductions equal the springs' by theory
(the same optimum), so they test nothing and are left out.
"""
import numpy as np
from scipy.optimize import minimize

from ..report.comparison import Comparison
from .design import balance_robot, default_workspace, paper_table
from .gravity import Workspace

FITTED = ("y_min", "z_min", "size")
START = (0.25, -0.25, 0.5)          # m: the uncalibrated default (default_workspace)
NOT_ASSEMBLED = 1e4                 # misfit (pp^2) of a workspace the robot cannot reach


def workspace_of(x, quick: bool = False) -> Workspace:
    """The square workspace with lower corner (x[0], x[1]) and side x[2] (m)."""
    y_min, z_min, size = (float(v) for v in x)
    return default_workspace(quick, y_min=y_min, z_min=z_min, size_y=size, size_z=size)


def rms_reductions(method: str, ws: Workspace) -> dict:
    """{motor: RMS torque reduction (%)} of ``method``'s optimal balancer over ``ws``."""
    return {r["motor"]: r["rms_reduction_pct"] for r in balance_robot(method, ws)["results"]}


def misfit(x, quick: bool = False) -> float:
    """Sum of squared differences (pp^2) of the springs' RMS reductions from Table III."""
    if not x[2] > 0:
        return NOT_ASSEMBLED
    try:
        ours = rms_reductions("spring", workspace_of(x, quick))
    except ValueError:  # a sample the five-bar cannot reach
        return NOT_ASSEMBLED
    return float(sum((ours[row["motor"]] - row["rms_reduction_pct"]) ** 2
                     for row in paper_table("spring")))


def calibrate_workspace(quick: bool = False) -> dict:
    """Fit (y_min, z_min, size) on Table III's RMS reductions (Nelder-Mead from the default):
    the fitted values (m), the RMS misfit before and after (percentage points) and the number
    of evaluations."""
    result = minimize(misfit, START, args=(quick,), method="Nelder-Mead",
                      options={"xatol": 1e-3, "fatol": 1e-2, "maxiter": 300})
    n = len(paper_table("spring"))
    return {**dict(zip(FITTED, (float(v) for v in result.x))),
            "rms_misfit_before_pp": float(np.sqrt(misfit(START, quick) / n)),
            "rms_misfit_after_pp": float(np.sqrt(result.fun / n)),
            "evaluations": int(result.nfev)}


def calibration_comparisons(fit: dict, quick: bool = False, tolerance_pp: float = 5.0,
                            tolerance_angle_deg: float = 5.0, tolerance_size: float = 0.10) -> list:
    """Comparisons of the fitted workspace: Table III's RMS reductions (calibrated: shown
    apart) and its predictions of Table IV and of Table V's counterweights."""
    ws = workspace_of([fit[k] for k in FITTED], quick)
    results = balance_robot("all", ws)["results"]
    out = []
    for r in results:
        method, motor = r["method"], r["motor"]
        paper = {row["motor"]: row for row in paper_table(method)}.get(motor)
        if paper is None:
            continue
        table = {"spring": "Table III", "torsion": "Table IV", "counterweight": "Table V"}[method]
        if method == "spring":
            out.append(Comparison(f"fitted workspace: RMS torque reduction, motor {motor}, spring",
                                  r["rms_reduction_pct"], paper["rms_reduction_pct"], "%", table,
                                  "calibrated", note="the three workspace numbers are fitted here"))
        elif method == "torsion":
            out.append(Comparison(f"fitted workspace: RMS torque reduction, motor {motor}, torsion",
                                  r["rms_reduction_pct"], paper["rms_reduction_pct"], "%", table,
                                  tolerance=tolerance_pp, note="predicted by the fitted workspace",
                                  headline=True))
        else:
            p = r["params"]
            out += [Comparison(f"fitted workspace: q_c, motor {motor}, counterweight",
                               np.degrees(p["q_c_rad"]), paper["q_deg"], "deg", table,
                               tolerance=tolerance_angle_deg, note="predicted by the fitted workspace"),
                    Comparison(f"fitted workspace: C, motor {motor}, counterweight", p["C_Nm"],
                               paper["param"], "N m", table, tolerance=tolerance_size,
                               note="predicted by the fitted workspace")]
    return out

