"""Report section "DBMA: a topology-optimised amplifier in its envelope": the amplifier
problem of flexfem.topopt.amplifier (the DBMA's quarter; its input stiffness, its quarter's
working mode and its peak stress as constraints) optimised, then verified on its body-fitted
shape, beside the DBMA read the same way: R, k_in, working mode and peak von Mises stress at
800 N (docs/topopt.md, "An amplifier in the DBMA's envelope"). SI units."""
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

FORCE = 800.0                    # N, the actuator's force (the top of the paper's Fig. 14)
K_IN_MIN = 4.36e6                # N/m, the DBMA's k_in (2-D FEM)
K_ACTUATOR, K_OUTPUT = 4e7, 1e5  # N/m, the actuator and the output's load (full part)
FN_MIN = 754.0                   # Hz, the DBMA quarter's working mode (this section's row)
STRESS_MAX = 655e6               # Pa, the DBMA's peak at 800 N (2-D FEM)
ELEMENT, SIZE = 0.5e-3, 0.25e-3  # m, the grid's elements and the body-fitted triangles
THRESHOLD = 0.3                  # the outline's density level
COLUMNS = ("design", "R", "k_in", "fn_lowest", "fn_working", "working_mode",
           "peak_stress", "peak_stress_fine", "corner_angle", "reading")


def amplifier() -> tuple:
    """(problem, result, verification, seconds) of the amplifier in the DBMA's envelope."""
    start = time.perf_counter()
    problem = amplifier_problem(FORCE, K_IN_MIN, K_ACTUATOR, K_OUTPUT, element=ELEMENT,
                                iterations=400, radius=3.0, fn_min=FN_MIN,
                                stress_max=STRESS_MAX)
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
        return out + [["DBMA quarter; optimised (density, body-fitted)",
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


def _paragraph(quick: bool, full: dict, quarter=None, verified=None, result=None) -> str:
    """What was done, the constraints' values and what the rows mean."""
    if quick:
        return ("An amplifier optimised by flexfem.topopt in the DBMA's quarter and verified "
                "on its body-fitted shape (docs/topopt.md) runs in the default report (about "
                "100 s); this quick run gives the DBMA's rows.")
    c = result.constraints
    state = "converged" if result.converged else "not converged"
    active = [name for name, value, bound in (("frequency", c["frequency"], FN_MIN),
                                              ("stress", c["stress"], STRESS_MAX))
              if abs(value / bound - 1) < 0.02]
    return (
        "Can topology optimisation beat the bow type in the DBMA's envelope? flexfem.topopt "
        "poses the DBMA's task on its quarter (docs/topopt.md): maximise the output's motion "
        f"with the actuator ({K_ACTUATOR / 1e6:g} MN/m) and a load ({K_OUTPUT / 1e3:g} kN/m) "
        f"as springs, at most 0.3 of the quarter solid, u_in <= (F / 2) / {K_IN_MIN / 1e6:g} "
        f"MN/m (with the springs), the lowest eigenfrequency >= {FN_MIN:g} Hz (the DBMA "
        f"quarter's working mode) and the stress p-norm <= {STRESS_MAX / 1e6:g} MPa (the "
        "DBMA's peak); then it verifies the design as a shape on flexfem's body-fitted FEM "
        "and reads the DBMA's own quarter by the same code. The quarter's symmetry makes its "
        "modes the part's doubly symmetric ones (the outputs moving apart; pads held along "
        "x); held on its mounting face (the paper's reading) the DBMA's working mode is "
        "lower, as its input members then move too. "
        f"After {result.iterations} MMA iterations ({state}) the frequency and stress "
        f"constraints are {'active: ' + ', '.join(active) if active else 'inactive'} "
        f"({c['frequency']:.0f} Hz, {c['stress'] / 1e6:.0f} MPa). The density model's R of "
        f"{verified['R_density']:.1f} rests on grey hinges of no width; drawn as a shape "
        f"the same topology gives R = {verified['R_fitted']:.2f} against the DBMA quarter's "
        f"{quarter['R']:.2f} (the whole part's {full['R_fem']:.2f}), at "
        f"{verified['k_in'] / quarter['k_in']:.0f} times its input stiffness: its working "
        "mode is higher and its stress lower because it is that much stiffer, not a better "
        "amplifier. Both peaks sit at re-entrant corners (the DBMA's square hinge roots, the "
        "optimised outline's facets where its necks were closed) and grow as the mesh is "
        "refined: they rank the designs, they are no strength values.")


def reproduce(out_dir, quick: bool = False) -> dict:
    """The table (quick: the DBMA's rows only) and the figure (not in quick)."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    full = analyze_dbma(dim=2, force=FORCE)
    rows = dbma_rows(full)
    timing = {"dbma_fem": time.perf_counter() - start}
    summary = {"figures": []}
    if quick:
        table = key_rows(full, rows)
        summary["paragraph"] = _paragraph(True, full)
    else:
        problem, result, verified, timing["optimised"] = amplifier()
        start = time.perf_counter()
        quarter = shape_readings(problem, dbma_quarter(), SIZE)
        timing["dbma_quarter"] = time.perf_counter() - start
        rows += [shape_row("DBMA quarter, read as the optimised", quarter,
                           "body-fitted quarter, pads held along x"),
                 density_row(verified, result),
                 shape_row("optimised, body-fitted", verified,
                           f"outline at {THRESHOLD}, 0.6 mm necks")]
        table = key_rows(full, rows, quarter, verified, result)
        summary["figures"] = [plot_design(result, verified, quarter,
                                          out_dir / "dbma_topopt.png")]
        summary["paragraph"] = _paragraph(False, full, quarter, verified, result)
        summary["optimised"] = {k: v for k, v in verified.items() if k != "outline"}
        summary["constraints"] = result.constraints
    write_rows(out_dir / "dbma_topopt.csv", rows, COLUMNS)
    return {**summary, "tables": ["dbma_topopt.csv"], "timing_s": timing,
            "key_tables": [{"title": f"The DBMA beside an amplifier optimised in its envelope "
                                     f"(2-D plane stress, {FORCE:g} N)",
                            "columns": ["design", "R = u_out / elongation", "k_in",
                                        "working mode", "peak von Mises"],
                            "rows": table}]}
