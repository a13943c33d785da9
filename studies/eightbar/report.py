"""``reproduce()`` of the eight-bar flexure suspension: figures, tables, a VTU and the
comparisons with the thesis (Chapters 5-8), and the MEMS scaling with its design-rule check."""
from pathlib import Path

from matplotlib.tri import Triangulation
import numpy as np

from ...data import load_toml
from ...fem import material, write_result
from ...geometry.design_rules import (
    check_design_rules,
    fabrication_rules,
    violation_summary,
)
from ...geometry.eightbar.flexure import (
    EightBarFlexureParams,
    eightbar_layout,
    joint_rotation_rates,
    prbm_flexure_loads,
)
from ...geometry.eightbar.rigid import trace_eightbar
from ..engine.tables import write_rows
from ..report.comparison import Comparison, rows as comparison_rows
from ..report.figures import axis_label, entry, legend_outside, pyplot, save
from ..report.stroke import fatigue_note, fatigue_stress, stroke_limits, stroke_table
from ..report.tolerances import add_to_section, tolerance_report

from .analysis import analyze_eightbar, evaluate, stress_convergence, summary_row
from .driving import driving_study

MICRO = load_toml("fabrication_rules.toml")["thesis_micro_design"]


def stress_limited_travel(params: EightBarFlexureParams, strength: float | None = None) -> float:
    """End-to-end travel (m) at which the first flexure reaches ``strength`` (Pa, default the
    material's) in pure bending, sigma_j = E w_j |dphi_j/dx| s / (2 L_j), s the stroke from the
    middle (pseudo-rigid-body estimate)."""
    mat = material(params.material)
    strength = strength or mat.yield_strength
    rates = joint_rotation_rates(params)
    half = min(2 * params.flexure_size(j)[0] * strength / (mat.E * params.flexure_size(j)[1] * abs(r))
               for j, r in rates.items())
    return 2 * half


def mems_check(params: EightBarFlexureParams) -> dict:
    """The design scaled to micrometres (factor from data, 1e-3) in single-crystal silicon, put
    through the thesis' design rules as scaled, and with its flexures widened to the minimum
    beam width: violations of each, and the stress-limited travel of the compliant one."""
    rules = fabrication_rules("thesis_mems")
    micro = params.scaled(MICRO["scale_factor"], "silicon_110")
    widened = EightBarFlexureParams(
        rigid=micro.rigid, link_width=micro.link_width,
        base_flexure_length=micro.base_flexure_length,
        base_flexure_width=max(micro.base_flexure_width, rules.min_beam_width),
        flexure_length=micro.flexure_length,
        flexure_width=max(micro.flexure_width, rules.min_beam_width),
        thickness=micro.thickness, material=micro.material,
        root_fillet_radius=micro.root_fillet_radius)
    out = {}
    for name, p in (("scaled", micro), ("widened", widened)):
        v = check_design_rules(eightbar_layout(p).parts, rules)
        out[name] = {"violations": [x.as_dict() for x in v], "summary": violation_summary(v),
                     "stress_limited_travel_m": stress_limited_travel(p),
                     "flexure_width_m": p.flexure_width, "base_flexure_width_m": p.base_flexure_width}
    out["published_travel_m"] = MICRO["travel_um"] * 1e-6
    return out


def prbm_table(out: dict, params: EightBarFlexureParams) -> list:
    """Per flexure at half the travel: the PRBM stiffness share, pure-bending stress, shear,
    axial force, end moment and root stress (:func:`prbm_flexure_loads`), beside the FEM's
    maximum nodal von Mises in that flexure (linear solve), SI units."""
    loads = prbm_flexure_loads(params, out["travel_m"] / 2)["joints"]
    lin = out["linear_result"]
    mesh = lin.model.mesh
    rows = []
    for j, k in out["k_x_prbm_joints"].items():
        vertices = np.unique(mesh.mesh.t[:3, mesh.subdomains[f"flexure_{j}"]])
        rows.append({"joint": j, "stiffness_share_n_per_m": k,
                     "bending_stress_pa": out["prbm_bending_stress"][j],
                     "spring_moment_nm": loads[j]["moment_nm"], "shear_n": loads[j]["shear_n"],
                     "axial_n": loads[j]["axial_n"], "end_moment_nm": loads[j]["end_moment_nm"],
                     "prbm_root_stress_pa": loads[j]["root_stress_pa"],
                     "fem_max_von_mises_nodal_pa": float(lin.von_mises_nodal[vertices].max())})
    return rows


def convergence_note(rows: list) -> str:
    """One sentence per fillet radius: the max von Mises (nodal / element, MPa) over the size
    factors of :func:`stress_convergence`, and where the finest mesh puts it."""
    parts = []
    for radius in sorted({r["root_fillet_radius_m"] for r in rows}):
        sub = [r for r in rows if r["root_fillet_radius_m"] == radius]
        series = ", ".join(f"{r['max_von_mises_nodal_pa'] / 1e6:.1f}/{r['max_von_mises_element_pa'] / 1e6:.1f}"
                           for r in sub)
        last = sub[-1]
        label = "sharp roots" if radius == 0 else f"root fillets r = {radius * 1e3:.2g} mm"
        factors = ", ".join(f"{r['size_factor']:g}" for r in sub)
        parts.append(f"{label}: max von Mises nodal/element {series} MPa at size factors "
                     f"{factors} (finest: {last['flexure']} "
                     f"at ({last['x_m'] * 1e3:.2f}, {last['y_m'] * 1e3:.3f}) mm)")
    return "stress convergence (linear, half travel): " + "; ".join(parts)


def plot_fields(out: dict, path: Path) -> dict:
    """Deformed shape at the end of the stroke (nonlinear) and linear von Mises at half travel."""
    plt = pyplot()
    lin = out["linear_result"]
    mesh = lin.model.mesh.mesh
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.5))
    mm = 1e3
    if "final_result" in out:
        nl = out["final_result"]
        u = np.stack([nl.u[-1][d] for d in nl.model.basis.nodal_dofs], axis=1)
        title = f"displacement at x = {out['travel_m'] / 2 * mm:.2f} mm (nonlinear), mm"
    else:
        u = lin.displacement
        title = "displacement (linear), mm"
    tri = Triangulation((mesh.p[0] + u[:, 0]) * mm, (mesh.p[1] + u[:, 1]) * mm, mesh.t.T)
    c = axes[0].tripcolor(tri, np.linalg.norm(u, axis=1) * mm, shading="gouraud", cmap="viridis")
    axes[0].triplot(Triangulation(mesh.p[0] * mm, mesh.p[1] * mm, mesh.t.T), lw=0.05, color="0.6")
    fig.colorbar(c, ax=axes[0], shrink=0.8)
    axes[0].set_title(title, fontsize=10)
    tri0 = Triangulation(mesh.p[0] * mm, mesh.p[1] * mm, mesh.t.T)
    # the links carry almost nothing: a colour range clipped at the 99.5th percentile, pale
    # at zero, shows the flexures; the inset zooms on the peak
    vm = lin.von_mises_nodal / 1e6
    top = float(np.percentile(vm, 99.5))
    c = axes[1].tripcolor(tri0, vm, shading="gouraud", cmap="YlOrRd", vmin=0.0, vmax=top)
    fig.colorbar(c, ax=axes[1], shrink=0.8, extend="max")
    loc = out["max_stress_location"]
    axes[1].plot(loc["x"] * mm, loc["y"] * mm, "b*", ms=12)
    zoom = axes[1].inset_axes([0.3, 0.12, 0.4, 0.42])
    zoom.tripcolor(tri0, vm, shading="gouraud", cmap="YlOrRd", vmin=0.0, vmax=vm.max())
    zoom.plot(loc["x"] * mm, loc["y"] * mm, "b*", ms=10)
    zoom.set_xlim(loc["x"] * mm - 3, loc["x"] * mm + 3)
    zoom.set_ylim(loc["y"] * mm - 1.5, loc["y"] * mm + 1.5)
    zoom.set_aspect("equal")
    zoom.tick_params(labelsize=7)
    zoom.set_title(f"peak {vm.max():.0f} MPa (full range)", fontsize=8)
    axes[1].set_title(f"von Mises (MPa), linear, x = {out['travel_m'] / 2 * mm:.2f} mm\n"
                      f"colours clipped at {top:.0f} MPa; peak in {loc['flexure']}", fontsize=10)
    for ax in axes:
        ax.set_aspect("equal")
        ax.set_xlabel(axis_label("x", "mm"))
        ax.set_ylabel(axis_label("y", "mm"))
    fig.tight_layout()
    return save(fig, path, "The eight-bar flexure suspension: displacement magnitude on the "
                "deformed shape at the end of the half stroke (left) and the linear von Mises "
                "stress at half the travel with its maximum marked (right; colours clipped at "
                "the 99.5th percentile, the inset at the peak with the full range).")


def plot_path(out: dict, rigid_rows, path: Path) -> dict:
    """Path across the line (um) against the stroke (mm): FEM vs rigid body."""
    plt = pyplot()
    rows = out["path"]
    x = np.array([r["x_m"] for r in rows])
    y = np.array([r["y_m"] for r in rows])
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(x * 1e3, (y - y[np.argmin(abs(x))]) * 1e6, "o-", label=f"flexure FEM (band "
            f"{out['fem_band_m'] * 1e6:.1f} um, {out['fem_deviation_pct']:.3g} %)")
    ax.plot(rigid_rows[:, 0] * 1e3, (rigid_rows[:, 1] - rigid_rows[len(rigid_rows) // 2, 1]) * 1e6,
            "-", label=f"rigid body (band {out['rigid_band_m'] * 1e6:.2f} um, "
            f"{out['rigid_deviation_pct']:.2g} %)")
    ax.set_xlabel(axis_label("end-effector x", "mm"))
    ax.set_ylabel(axis_label("y - y(0)", "um"))
    ax.grid(alpha=0.3)
    legend_outside(ax)
    fig.tight_layout()
    return save(fig, path, "Path of the end effector across its line over the travel: the "
                "flexure suspension by nonlinear FEM beside the rigid-body linkage.")


def plot_force(out: dict, path: Path, limits: dict | None = None) -> dict:
    """Force-displacement and peak von Mises along the travel against yield (and, with the
    section's stroke ``limits``, the fatigue-limited stress amplitude)."""
    plt = pyplot()
    rows = out["path"]
    x = np.array([r["x_m"] for r in rows]) * 1e3
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    a.plot(x, [r["force_x_n"] for r in rows], "o-", label="FEM (nonlinear)")
    a.plot(x, out["k_x"] * x / 1e3, "--", label=f"linear k_x = {out['k_x']:.3g} N/m")
    a.plot(x, out["k_x_prbm"] * x / 1e3, ":", label=f"PRBM {out['k_x_prbm']:.3g} N/m")
    a.set_xlabel(axis_label("x", "mm"))
    a.set_ylabel(axis_label("drive force F_x", "N"))
    a.legend(fontsize=8)
    a.grid(alpha=0.3)
    b.plot(x, [r["peak_von_mises_pa"] / 1e6 for r in rows], "o-", label="peak von Mises (element)")
    b.axhline(out["yield_strength"] / 1e6, color="r", label="yield strength")
    amplitude = fatigue_stress(limits) if limits else None
    if amplitude is not None:
        cycles = f"{limits['fatigue_cycles']:.0e}".replace("e+0", "e").replace("e+", "e")
        b.axhline(amplitude / 1e6, color="g", ls="--",
                  label=f"fatigue amplitude (Goodman, {cycles} cycles)")
    if limits:
        mark_stroke_limits(b, limits, 1e3)
    b.set_xlabel(axis_label("x", "mm"))
    b.set_ylabel(axis_label("von Mises stress", "MPa"))
    b.legend(fontsize=7, loc="upper center", framealpha=0.9)
    b.grid(alpha=0.3)
    fig.tight_layout()
    return save(fig, path, "Drive force against stroke (nonlinear FEM beside the linear and "
                "pseudo-rigid-body stiffness) and the peak von Mises stress along the stroke "
                "against the yield strength" + (" and the stress amplitude the material "
                                                "endures for its fatigue life (Goodman, fully "
                                                "reversed about the middle)"
                                                if amplitude is not None else "")
                + ("; dashed: the linear solve scaled, to the stroke limits (x: yield, "
                   "diamond: fatigue-limited amplitude)" if limits else "") + ".")


def mark_stroke_limits(ax, limits: dict, scale: float) -> None:
    """On a stress (MPa) against stroke axes (stroke x ``scale``): the linear scaling of
    ``limits`` (:func:`..report.stroke.stroke_limits`) out to 1.1 times its yield-limited
    stroke each way, and the yield (x) and fatigue-limited (diamond) strokes marked."""
    top = 1.1 * limits["stroke_limit_yield"]
    ax.plot(np.array([-top, 0, top]) * scale,
            np.array([top, 0, top]) * limits["stress_per_stroke"] / 1e6, color="0.4", ls="--",
            lw=1, label="linear scaling (stroke limits)")
    marks = [(limits["stroke_limit_yield"], "x", "tab:red", "yield-limited stroke")]
    if limits["stroke_limit_fatigue_goodman"] is not None:
        marks.append((limits["stroke_limit_fatigue_goodman"], "D", "tab:green",
                      "fatigue-limited amplitude"))
    for at, marker, color, label in marks:
        ax.plot(np.array([-at, at]) * scale, [limits["stress_per_stroke"] * at / 1e6] * 2,
                marker, color=color, mfc="none", mew=1.5, ms=7, ls="none", label=label)


def comparisons(out: dict, mems: dict) -> list[Comparison]:
    """The flexure suspension beside the thesis' design targets (SI units)."""
    targets = load_toml("eightbar_thesis.toml")["design_targets"]
    C = Comparison
    return [
        C("travel traced by the flexure FEM", out["fem_travel_m"], targets["travel_mm"] * 1e-3,
          "m", "Ch. 5", "input", note="the end-effector face is driven over the thesis' stroke"),
        C("flexure FEM path deviation (% of travel)", out["fem_deviation_pct"],
          targets["max_deviation_pct"], "% of travel", "Ch. 5 design bound", limit="upper",
          note=f"the bound is the thesis' for its rigid path; the long flexures' pivots shift "
               f"under load and bow the path (band {out['fem_band_m'] * 1e6:.0f} um); a longer "
               "coupler straightens it (docs/eightbar_driving.md)", headline=True),
        C("rigid-body path deviation (% of travel)", out["rigid_deviation_pct"],
          targets["max_deviation_pct"], "% of travel", "Ch. 5 design bound", limit="upper",
          note="flexfem's linkage (Ch. 5 rigid design), same measure"),
        C("micro version: stress-limited travel, flexures widened to 3 um",
          mems["widened"]["stress_limited_travel_m"], mems["published_travel_m"], "m", "Ch. 8",
          limit="lower", note="scaled by 1e-3 the flexures break the 3 um minimum width; "
          "widened to 3 um they reach silicon's 1 GPa before the thesis' travel (PRBM "
          "bending stress)", headline=True),
    ]


def eightbar_stroke_limits(out: dict, params: EightBarFlexureParams) -> list:
    """The end effector's stroke limits from the middle, from the linear solve's peak von
    Mises at half the travel (at a root fillet: it converges, see the stress convergence
    note), scaled linearly."""
    half = out["travel_m"] / 2
    basis = (f"peak von Mises at the flexures' root fillets (r = {params.root_fillet_radius * 1e3:.2g}"
             f" mm), linear solve at x = {half * 1e3:.4g} mm scaled linearly; the thesis' "
             f"travel is ±{half * 1e3:.4g} mm")
    return [stroke_limits(out["max_von_mises"] / half, material(params.material),
                          "end effector's travel from the middle", "m", basis)]


def paragraph(out: dict, params: EightBarFlexureParams) -> str:
    """What the flexure FEM did and what it means, with the run's own numbers."""
    loc = out["max_stress_location"]
    return (f"The eight-bar's pivots are replaced by beam flexures (root fillets r = "
            f"{params.root_fillet_radius * 1e3:.2g} mm) and the suspension is solved by FEM: "
            f"linear stiffness k_x = {out['k_x']:.3g} N/m along the motion and "
            f"k_y = {out['k_y']:.3g} N/m across it, and a large-deflection trace over the "
            f"thesis' stroke, whose path stays within {out['fem_deviation_pct']:.2g} % of the "
            f"travel of a straight line. The largest linear von Mises stress at half the travel, "
            f"{out['max_von_mises'] / 1e6:.0f} MPa, is in flexure {loc['flexure']}, not beside "
            "the base link as the thesis expects: the A flexures lie across the cranks, whose "
            "axial force shears them (see eightbar_fem_prbm.csv).")


# The tolerance study of examples/eightbar_tolerances.toml (a test keeps the two the same):
# the wire-EDM shop's +-5 um on the flexures' widths and +-10 um on the root fillets, on the
# beam model with the large-deflection path; its base sample n by the report's size. The
# designs at the extremes of the outputs shown are re-checked by the 2-D continuum FEM with
# its large-deflection path (engine/tolerance.py: confirm_extremes; at most 6 designs, ~20 s
# each on one core), except with --quick.
TOLERANCES = {
    "mechanism": "eightbar", "name": "eightbar_tolerances",
    "options": {"model": "beam", "nonlinear": True},
    "tolerances": {"n": 64, "seed": 0, "metrics": ["k_x", "f1_hz", "fem_deviation_pct"],
                   "parameters": {
        "flexure_width": {"nominal": 0.3e-3, "tolerance": 5e-6, "distribution": "normal"},
        "base_flexure_width": {"nominal": 0.4e-3, "tolerance": 5e-6, "distribution": "normal"},
        "root_fillet_radius": {"nominal": 0.3e-3, "tolerance": 10e-6,
                               "distribution": "normal"}},
        "confirm": {"model": "continuum", "size_factor": 2.0}}}
TOLERANCE_OUTPUTS = {"k_x": ("drive stiffness k_x", "N/m"), "f1_hz": ("first mode f1", "Hz"),
                     "fem_deviation_pct": ("path deviation (% of travel)", "")}
TOLERANCE_LABELS = {"flexure_width": "flexure width", "base_flexure_width": "base flexure width",
                    "root_fillet_radius": "root fillet radius"}


def tolerance_study(out_dir: Path, quick: bool = False, full: bool = False,
                    n: int | None = None) -> dict:
    """The eight-bar's tolerance study (:data:`TOLERANCES`) into ``out_dir``/tolerances: n =
    8 (40 designs, ~25 s) with ``quick``, 16 by default, 64 (the example's) with ``full``
    (or ``n``); the extremes re-checked as its ``confirm`` table says unless ``quick``."""
    table = TOLERANCES if not quick else {**TOLERANCES, "tolerances": {
        k: v for k, v in TOLERANCES["tolerances"].items() if k != "confirm"}}
    return tolerance_report(table, evaluate, Path(out_dir) / "tolerances",
                            TOLERANCE_OUTPUTS, TOLERANCE_LABELS,
                            "a wire-EDM shop's tolerances on the eight-bar's "
                            "flexures", n=n or (8 if quick else (64 if full else 16)),
                            # 40 designs: in this process (~0.55 s of CPU each) beats
                            # starting workers; the larger samples use every CPU
                            workers=1 if quick else None, confirm=not quick,
                            figure="eightbar_tolerances.png", prefix="tolerances/")


def reproduce(out_dir, quick: bool = False, full: bool = False) -> dict:
    """Run the analysis (quick: coarse mesh, half the stroke mirrored; full: a finer mesh) and
    write figures, CSV tables, the linear VTU; return the summary with comparison rows."""

    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    params = EightBarFlexureParams()
    size_factor = 2.0 if quick else (0.7 if full else 1.0)
    out = analyze_eightbar(params, size_factor=size_factor, steps=4 if quick else 8,
                           both_halves=not quick, n_modes=2 if quick else 4)
    rigid = trace_eightbar(params.rigid, n=101)
    rigid_rows = np.column_stack([rigid.displacements, rigid.points[:, 1]])
    limits = eightbar_stroke_limits(out, params)
    figures = [plot_fields(out, out_dir / "eightbar_fem_fields.png"),
               plot_path(out, rigid_rows, out_dir / "eightbar_fem_path.png"),
               plot_force(out, out_dir / "eightbar_fem_force.png", limits[0])]
    tables = [write_rows(out_dir / "eightbar_fem_path.csv", out["path"]).name,
              write_rows(out_dir / "eightbar_fem_modes.csv", out["modes"]).name,
              write_rows(out_dir / "eightbar_fem_prbm.csv", prbm_table(out, params)).name]
    convergence = stress_convergence(params, (2.0, 1.0) if quick else (1.0, 0.7, 0.5))
    tables.append(write_rows(out_dir / "eightbar_fem_stress_convergence.csv", convergence).name)
    write_result(out["linear_result"], out_dir / "eightbar_linear.vtu")
    mems = mems_check(params)
    violations = mems["scaled"]["violations"] + mems["widened"]["violations"]
    if violations:
        tables.append(write_rows(out_dir / "eightbar_mems_violations.csv", violations).name)
    rows = comparison_rows(comparisons(out, mems))
    figures.append(entry("eightbar_linear.vtu", "the linear solve's fields, for ParaView"))
    summary = {"paragraph": paragraph(out, params), "comparisons": rows, "figures": figures,
               "tables": tables, "stroke_limits": limits,
               "key_tables": [stroke_table(limits)], "summary_figure": "eightbar_fem_path.png",
               "lead": (f"The thesis' eight-bar traced over its {out['travel_m'] * 1e3:.3g} mm "
                        "travel, as a rigid linkage and as a flexure suspension by FEM"),
               "analysis": summary_row(out), "mems": {k: (v if k == "published_travel_m" else
                                                          {kk: vv for kk, vv in v.items() if kk != "violations"})
                                                      for k, v in mems.items()},
               "mesh": {"dofs": out["dofs"], "elements": out["n_elements"], **out["mesh_sizes"]},
               "params": {"link_width": params.link_width,
                          "base_flexure_length": params.base_flexure_length,
                          "base_flexure_width": params.base_flexure_width,
                          "flexure_length": params.flexure_length,
                          "flexure_width": params.flexure_width, "thickness": params.thickness,
                          "root_fillet_radius": params.root_fillet_radius,
                          "material": params.material}}
    driving = driving_study(out_dir / "driving", quick=quick)
    summary["comparisons"] = rows + driving["comparisons"]
    summary["notes"] = ([convergence_note(convergence)] + driving.get("notes", [])
                        + [fatigue_note(limits)])
    summary["stress_convergence"] = convergence
    summary["tolerances"] = add_to_section(summary, tolerance_study(out_dir, quick, full),
                                           before="eightbar_linear.vtu")
    summary["tables"] += [f"driving/{t}" for t in driving["tables"]]
    summary["figures"] += [{**f, "file": f"driving/{f['file']}"}
                           for f in driving["figures"]]
    return summary
