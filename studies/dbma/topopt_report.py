"""Report section "DBMA: a topology-optimised amplifier in its envelope": the amplifier
problem of flexfem.topopt.amplifier (the DBMA's quarter; its input stiffness, its quarter's
working mode and its peak stress as constraints, computed by flexfem's DBMA model in the
same run) optimised without and with a minimum hinge width (the DBMA's b, by the robust
formulation: studies/dbma/topopt_robust.py), then verified on its body-fitted shape, beside
the DBMA read the same way: R, k_in, working mode and peak von Mises stress at 800 N
(docs/topopt_amplifier.md). The quick report reads the stored robust design
(examples/topopt/dbma_amplifier.py writes it). SI units."""
import math
from pathlib import Path
import time

import numpy as np

from ...geometry.dbma.drawing import hinge_boxes
from ...geometry.dbma.params import paper_design
from ...topopt import optimize
from ...topopt.amplifier import (amplifier_problem, dbma_quarter, shape_readings,
                                 verify_amplifier)
from ..engine.tables import write_rows
from ..report.figures import pyplot, save
from .analysis import analyze_dbma, published
from .topopt_robust import (FORCE, K_ACTUATOR, K_OUTPUT, SIZE, dbma_limits, read_stored,
                            reverify, run_robust, verdict)

ELEMENT = 0.5e-3                 # m, the plain design's grid
THRESHOLD = 0.3                  # the outline's density level
COLUMNS = ("design", "R", "k_in", "fn_lowest", "fn_working", "working_mode",
           "peak_stress", "peak_stress_fine", "corner_angle", "reading")


def amplifier(limits: dict) -> tuple:
    """(problem, result, verification, seconds) of the amplifier in the DBMA's envelope
    without length control, at the DBMA's ``limits`` (topopt_robust.dbma_limits)."""
    start = time.perf_counter()
    problem = amplifier_problem(FORCE, limits["k_in_min"], K_ACTUATOR, K_OUTPUT,
                                element=ELEMENT, iterations=400, radius=3.0,
                                fn_min=limits["fn_min"], stress_max=limits["stress_max"])
    result = optimize(problem)
    verified = verify_amplifier(result, threshold=THRESHOLD, size=SIZE)
    return problem, result, verified, time.perf_counter() - start


def at_hinge_corner(where, p=None) -> bool:
    """True where ``where`` (m) lies within a hinge thickness of a corner of a DBMA hinge
    (the leaf's square roots: sharp re-entrant corners)."""
    p = p or paper_design()
    corners = np.array([(x, y) for r in hinge_boxes(p) for x in (r.x0, r.x1)
                        for y in (r.y0, r.y1)])
    return bool(np.min(np.hypot(*(corners - np.asarray(where[:2])).T)) <= p.b)


def _mpa(value) -> str:
    return f"{value / 1e6:.0f} MPa"


def _body_fitted_stress(r: dict) -> str:
    """'621 -> 664 MPa (triangles 0.25 -> 0.125 mm), at a 270 deg corner: singular'."""
    where = ("at a {:.0f} deg corner: singular (Williams: ~ r^-{:.2f})".format(
        r["corner_angle"], r["singularity_exponent"]) if r["singularity_exponent"] > 0
             else "not at a re-entrant corner")
    return (f"{_mpa(r['peak_stress'])} -> {_mpa(r['peak_stress_fine'])} (triangles "
            f"{SIZE * 1e3:g} -> {SIZE * 5e2:g} mm), {where}")


def _modes(r: dict) -> str:
    lowest = r["frequencies_hz"][0]
    rest = f"; lowest {lowest:.0f} Hz" if r["working_mode"] > 1 else ""
    return f"{r['fn_working']:.0f} Hz (mode {r['working_mode']}{rest})"


def dbma_rows(full: dict) -> list:
    """The DBMA's rows: flexfem's 2-D FEM of the whole part and the paper's numbers."""
    paper = published()
    amp, freq = paper["amplification"], paper["frequency"]
    corner = "sharp hinge corner: singular" if at_hinge_corner(
        full["max_von_mises_location"]) else "not at a hinge corner"
    return [
        {"design": "DBMA, flexfem 2-D FEM (whole part)", "R": full["R_fem"],
         "k_in": full["k_in"], "fn_lowest": full["frequencies_hz"][0],
         "fn_working": full["fn_working"], "working_mode": full["working_mode"],
         "peak_stress": full["max_von_mises"], "corner_angle": math.nan,
         "reading": "mounting face held; modes: pads held along x", "_stress": corner},
        {"design": "DBMA, paper", "R": amp["R_fem"] / 2, "k_in": math.nan, "fn_lowest": math.nan,
         "fn_working": freq["fn_fem_Hz"], "working_mode": freq["working_mode_order"],
         "peak_stress": math.nan, "corner_angle": math.nan,
         "reading": "the paper's FEM, R per side / 2",
         "_measured": f"{amp['R_measured_min'] / 2:.2f}-{amp['R_measured_max'] / 2:.2f}",
         "_fn_measured": freq["fn_measured_Hz"]},
    ]


def shape_row(design: str, r: dict, reading: str) -> dict:
    """A CSV row of ``shape_readings``' numbers."""
    return {"design": design, "R": r.get("R", r.get("R_fitted")), "k_in": r["k_in"],
            "fn_lowest": r["frequencies_hz"][0], "fn_working": r["fn_working"],
            "working_mode": r["working_mode"], "peak_stress": r["peak_stress"],
            "peak_stress_fine": r["peak_stress_fine"], "corner_angle": r["corner_angle"],
            "reading": reading}


def density_row(verified: dict, result) -> dict:
    """The CSV row of the density model: R and k_in under the force alone, its lowest
    eigenfrequency and stress p-norm (Pa) with its springs, as the optimiser read them."""
    c = result.constraints
    return {"design": "optimised, density model", "R": verified["R_density"],
            "k_in": verified["k_in_density"], "fn_lowest": c["frequency"],
            "fn_working": math.nan, "working_mode": math.nan, "peak_stress": math.nan,
            "corner_angle": math.nan,
            "reading": f"with its springs: stress p-norm {c['stress']:.4g} Pa (P = 8)"}


def key_rows(full: dict, rows: list, quarter=None, verified=None, result=None) -> list:
    """The printed table: R, k_in, working mode, peak stress at 800 N, one row a design."""
    out = [[rows[0]["design"], f"{full['R_fem']:.2f}", f"{full['k_in'] / 1e6:.2f} MN/m",
            _modes(full), f"{_mpa(full['max_von_mises'])}, {rows[0]['_stress']}"],
           [rows[1]["design"], f"{rows[1]['R']:.2f} FEM; {rows[1]['_measured']} measured",
            "-", f"{rows[1]['fn_working']:.0f} Hz FEM (mode {rows[1]['working_mode']}); "
                 f"{rows[1]['_fn_measured']:.0f} Hz measured", "not printed"]]
    if quarter is None:
        return out + [["DBMA quarter; optimised without length control (density, body-fitted)",
                       "in the default report (not run with --quick)", "-", "-", "-"]]
    c = result.constraints
    return out + [
        ["DBMA quarter, read as the optimised", f"{quarter['R']:.2f}",
         f"{quarter['k_in'] / 1e6:.2f} MN/m", _modes(quarter), _body_fitted_stress(quarter)],
        ["optimised, density model", f"{verified['R_density']:.1f} "
         f"({verified['R_density_springs']:.1f} with the springs)",
         f"{verified['k_in_density'] / 1e6:.2f} MN/m",
         f"{c['frequency']:.0f} Hz (lowest, with its springs)",
         f"p-norm {_mpa(c['stress'])} (with its springs; not a peak)"],
        ["optimised, body-fitted", f"{verified['R_fitted']:.2f}",
         f"{verified['k_in'] / 1e6:.0f} MN/m", _modes(verified), _body_fitted_stress(verified)]]


CAPTION = ("The amplifier optimised in the DBMA's quarter (actuator's pad at the right, "
           "output face on top, symmetry lines x = 0 and y = 0): its densities (left) and "
           "the body-fitted shape verified (right: the outline at density {t}, hinges closed "
           "into 0.6 mm necks; blue dashes, the DBMA's quarter; crosses, the peak von Mises "
           "stress at 800 N, red the optimised shape's, blue the DBMA's).")


def _fill(ax, shape, **style) -> None:
    for part in getattr(shape, "geoms", [shape]):
        ax.fill(*(np.asarray(part.exterior.xy) * 1e3), **style)
        for ring in part.interiors:
            ax.fill(*(np.asarray(ring.xy) * 1e3), color="white")


def plot_design(result, verified, quarter, path) -> dict:
    """The density field beside the body-fitted outline (mm), the DBMA's quarter dashed."""
    plt = pyplot()
    g = result.problem.grid
    fig, (left, right) = plt.subplots(1, 2, figsize=(7.0, 3.4))
    left.imshow(g.image(result.density), cmap="gray_r", vmin=0, vmax=1,
                extent=(0, g.lx * 1e3, 0, g.ly * 1e3))
    left.set_title("density model", fontsize="medium")
    _fill(right, verified["outline"].shape, color="0.6")
    dbma = dbma_quarter().shape
    for ring in [dbma.exterior, *dbma.interiors]:
        right.plot(*(np.asarray(ring.xy) * 1e3), "b--", lw=0.8)
    for r, mark in ((verified, "rx"), (quarter, "bx")):
        right.plot(r["peak_where"][0] * 1e3, r["peak_where"][1] * 1e3, mark, ms=8)
    right.set_title(f"body-fitted, R = {verified['R_fitted']:.2f} (DBMA {quarter['R']:.2f})",
                    fontsize="medium")
    for ax in (left, right):
        ax.set(aspect="equal", xlim=(-1, g.lx * 1e3 + 1), ylim=(-1, g.ly * 1e3 + 1),
               xlabel="x (mm)")
    left.set_ylabel("y (mm)")
    return save(fig, path, CAPTION.format(t=THRESHOLD))


def robust_rows(record: dict) -> list:
    """The CSV rows of the design with the minimum hinge width: its density model (the
    intermediate design, with the worst-of-three constraint values) and its shape."""
    v, c, p = record["verified"], record["result"]["constraints"], record["problem"]
    hinge = f"min_hinge {p['min_hinge'] * 1e3:g} mm"
    return [{"design": f"optimised, {hinge}, density model", "R": v["R_density"],
             "k_in": v["k_in_density"], "fn_lowest": c["frequency"], "fn_working": math.nan,
             "working_mode": math.nan, "peak_stress": math.nan, "corner_angle": math.nan,
             "reading": f"worst of three designs: stress p-norm {c['stress']:.4g} Pa (P = 8)"},
            shape_row(f"optimised, {hinge}, body-fitted", v,
                      f"outline at {p['threshold']}, necks >= {hinge}")]


def _necks(record: dict) -> str:
    widths = sorted(n["width"] for n in record["necks"])
    if not widths:
        return "no neck under twice min_hinge"
    return "necks " + ", ".join(f"{w * 1e3:.2f}" for w in widths[:4]) + " mm"


def robust_key_rows(record: dict) -> list:
    """The printed rows of the design with the minimum hinge width."""
    v, c, p = record["verified"], record["result"]["constraints"], record["problem"]
    hinge = f"min_hinge {p['min_hinge'] * 1e3:g} mm"
    return [[f"optimised, {hinge}, density model", f"{v['R_density']:.2f} "
             f"({v['R_density_springs']:.2f} with the springs)",
             f"{v['k_in_density'] / 1e6:.2f} MN/m",
             f"{c['frequency']:.0f} Hz (lowest, with its springs)",
             f"p-norm {_mpa(c['stress'])} (worst of three designs; not a peak)"],
            [f"optimised, {hinge}, body-fitted ({_necks(record)})", f"{v['R_fitted']:.2f}",
             f"{v['k_in'] / 1e6:.2f} MN/m", _modes(v), _body_fitted_stress(v)]]


def verdict_text(record: dict, r_dbma: float) -> str:
    """One sentence: beats the bow, or by how much it falls short and what binds."""
    w = verdict(record, r_dbma)
    lim = record["limits"]
    bind = (", ".join(w["binding"]) or "none") + " binding" + (
        ", " + ", ".join(w["violated"]) + " violated" if w["violated"] else "") + (
        " in the density model")
    failed = ("every constraint met on the shape" if not w["failed"] else
              "not met on the shape: " + ", ".join(w["failed"]))
    if "min_hinge" in w["failed"]:
        failed += (f" (its narrowest neck {w['narrowest_neck'] * 1e3:.2f} mm against "
                   f"{record['problem']['min_hinge'] * 1e3:g} mm)")
    if w["beats"]:
        head = f"it beats the bow: R = {w['R_fitted']:.2f} against the DBMA's {r_dbma:.2f}"
    elif w["R_fitted"] > r_dbma:
        head = (f"its shape amplifies more than the bow, R = {w['R_fitted']:.2f} against the "
                f"DBMA's {r_dbma:.2f}, but not at the DBMA's hinge width")
    else:
        head = (f"it falls short of the bow by {100 * w['shortfall']:.0f} %: R = "
                f"{w['R_fitted']:.2f} against the DBMA's {r_dbma:.2f}")
    return (f"With min_hinge = {record['problem']['min_hinge'] * 1e3:g} mm {head} ({bind}; "
            f"{failed}; limits k_in >= {lim['k_in_min'] / 1e6:.2f} MN/m, working mode >= "
            f"{lim['fn_min']:.0f} Hz, peak <= {lim['stress_max'] / 1e6:.0f} MPa; its "
            f"body-fitted R is {w['fitted_over_density']:.2f} of its density model's).")


def large_text(record: dict) -> str:
    """One sentence on the density model read with large displacements at the same force."""
    if "large" not in record:
        return ""
    small, large = record["large"]["small"], record["large"]["large"]
    return (f" Read with large displacements at {record['problem']['force']:g} N (the "
            f"density model with its springs, topopt's large-displacement solver) its R is "
            f"{large['R']:.3f} against {small['R']:.3f} with small ones "
            f"({100 * (large['R'] / small['R'] - 1):+.2f} %; u_out {large['u_out'] * 1e6:.1f} "
            f"um): at the DBMA's force the geometry barely changes, and the design was "
            "optimised with small displacements.")


def _paragraph(quick: bool, full: dict, record: dict, quarter=None, verified=None,
               result=None) -> str:
    """What was done, the constraints' values and what the rows mean."""
    p = record["problem"]
    robust = (
        f"With a minimum hinge width (the DBMA's b = {p['min_hinge'] * 1e3:g} mm, by the "
        f"robust formulation: eroded, intermediate and dilated designs at thresholds "
        f"{' / '.join(f'{t:g}' for t in p['thresholds'])}, filter radius "
        f"{p['filter_radius']:.3g} elements of {p['element'] * 1e3:g} mm on a "
        f"{p['nelx']} x {p['nely']} grid) the design ran "
        f"{record['result']['iterations']} MMA iterations"
        + (f", begun from the design at {record['start']['from']}" if "start" in record
           else "")
        + f" ({'converged' if record['result']['converged'] else 'not converged'}). "
        + verdict_text(record, full["R_fem"]) + large_text(record))
    if quick:
        return ("An amplifier optimised by flexfem.topopt in the DBMA's quarter, its "
                "constraints the DBMA's own (k_in and peak stress of the whole part's 2-D "
                "FEM, its quarter's working mode), verified on its body-fitted shape "
                "(docs/topopt_amplifier.md). This quick run computes the DBMA's rows and "
                "reads the stored design with the minimum hinge width (written by "
                "examples/topopt/dbma_amplifier.py; the default report verifies it again and "
                "runs the design without length control, --full reruns both). " + robust)
    c = result.constraints
    lim = record["limits"]
    state = "converged" if result.converged else "not converged"
    active = [name for name, value, bound in (("frequency", c["frequency"], lim["fn_min"]),
                                              ("stress", c["stress"], lim["stress_max"]))
              if abs(value / bound - 1) < 0.02]
    return (
        "Can topology optimisation beat the bow type in the DBMA's envelope? flexfem.topopt "
        "poses the DBMA's task on its quarter (docs/topopt_amplifier.md): maximise the "
        f"output's motion with the actuator ({K_ACTUATOR / 1e6:g} MN/m) and a load "
        f"({K_OUTPUT / 1e3:g} kN/m) as springs, at most 0.3 of the quarter solid, u_in <= "
        f"(F / 2) / {lim['k_in_min'] / 1e6:.3g} MN/m (with the springs), the lowest "
        f"eigenfrequency >= {lim['fn_min']:.0f} Hz (the DBMA quarter's working mode) and "
        f"the stress p-norm <= {lim['stress_max'] / 1e6:.0f} MPa (the DBMA's peak), each "
        "limit computed by flexfem's DBMA model in this run; then it verifies the design as "
        "a shape on flexfem's body-fitted FEM and reads the DBMA's own quarter by the same "
        "code. The quarter's symmetry makes its modes the part's doubly symmetric ones (the "
        "outputs moving apart; pads held along x); held on its mounting face (the paper's "
        "reading) the DBMA's working mode is lower, as its input members then move too. "
        f"Without length control, after {result.iterations} MMA iterations ({state}) the "
        "frequency and stress constraints are "
        f"{'active: ' + ', '.join(active) if active else 'inactive'} "
        f"({c['frequency']:.0f} Hz, {c['stress'] / 1e6:.0f} MPa). The density model's R of "
        f"{verified['R_density']:.1f} rests on grey hinges of no width; drawn as a shape "
        f"the same topology gives R = {verified['R_fitted']:.2f} against the DBMA quarter's "
        f"{quarter['R']:.2f} (the whole part's {full['R_fem']:.2f}), at "
        f"{verified['k_in'] / quarter['k_in']:.0f} times its input stiffness. " + robust
        + " Both peaks sit at re-entrant corners and grow as the mesh is refined: they rank "
        "the designs, they are no strength values.")


def reproduce(out_dir, quick: bool = False, full: bool = False) -> dict:
    """The table and the paragraph; quick: the DBMA's rows and the stored design with the
    minimum hinge width as stored; default: the design without length control run, the
    stored design with the minimum hinge width verified again (its body-fitted reading and
    necks recomputed), and the figure; full: both designs run."""
    rerun = full
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    full = analyze_dbma(dim=2, force=FORCE)
    rows = dbma_rows(full)
    timing = {"dbma_fem": time.perf_counter() - start}
    summary = {"figures": []}
    if quick:
        record = read_stored()
        rows += robust_rows(record)
        table = key_rows(full, rows) + robust_key_rows(record)
        summary["paragraph"] = _paragraph(True, full, record)
    else:
        start = time.perf_counter()
        limits = dbma_limits(full)
        quarter = limits["quarter"]
        timing["dbma_quarter"] = time.perf_counter() - start
        problem, result, verified, timing["optimised"] = amplifier(limits)
        start = time.perf_counter()
        run = run_robust(limits) if rerun else reverify()
        record = run["record"]
        timing["optimised_min_hinge"] = time.perf_counter() - start
        rows += [shape_row("DBMA quarter, read as the optimised", quarter,
                           "body-fitted quarter, pads held along x"),
                 density_row(verified, result),
                 shape_row("optimised, body-fitted", verified,
                           f"outline at {THRESHOLD}, 0.6 mm necks")] + robust_rows(record)
        table = key_rows(full, rows, quarter, verified, result) + robust_key_rows(record)
        summary["figures"] = [plot_design(result, verified, quarter,
                                          out_dir / "dbma_topopt.png")]
        summary["paragraph"] = _paragraph(False, full, record, quarter, verified, result)
        summary["optimised"] = {k: v for k, v in verified.items() if k != "outline"}
        summary["constraints"] = result.constraints
    summary["min_hinge"] = {"verdict": verdict(record, full["R_fem"]),
                            "verified": record["verified"], "necks": record["necks"],
                            "constraints": record["result"]["constraints"],
                            "limits": record["limits"], "iterations":
                            record["result"]["iterations"]}
    write_rows(out_dir / "dbma_topopt.csv", rows, COLUMNS)
    return {**summary, "tables": ["dbma_topopt.csv"], "timing_s": timing,
            "key_tables": [{"title": f"The DBMA beside amplifiers optimised in its envelope "
                                     f"(2-D plane stress, {FORCE:g} N)",
                            "columns": ["design", "R = u_out / elongation", "k_in",
                                        "working mode", "peak von Mises"],
                            "rows": table}]}
