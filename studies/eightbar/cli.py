"""``flexfem linkage trace NAME``, ``flexfem eightbar trace`` (rigid-body straight-line paths),
``flexfem eightbar analyze`` (FEM of the flexure suspension), ``flexfem eightbar driving`` (the
driving linkage) and ``flexfem eightbar mesh OUT``; ``--model beam`` on analyze and driving."""
import argparse

from ..lazy import Lazy
from ..options import add_model_options, deferred, positive, whole_number

# what the commands compute with, imported when one runs (meshing, the FEM, the beam model)
write_mesh = Lazy("...fem:write_mesh", __package__)
EightBarFlexureParams = Lazy("...geometry.eightbar.flexure:EightBarFlexureParams", __package__)
mesh_eightbar_flexure = Lazy("...geometry.eightbar.flexure:mesh_eightbar_flexure", __package__)
EightBarParams = Lazy("...geometry.eightbar.rigid:EightBarParams", __package__)
analyze_eightbar = Lazy(".analysis:analyze_eightbar", __package__)
summary_row = Lazy(".analysis:summary_row", __package__)
analyze_eightbar_beam = Lazy(".beam:analyze_eightbar_beam", __package__)
analyze_driving = Lazy(".driving_models:analyze_driving", __package__)
eightbar_path_summary = Lazy(".path:eightbar_path_summary", __package__)
trace_classic = Lazy(".path:trace_classic", __package__)
stage_study = Lazy(".stage:stage_study", __package__)

BEAM_HELP = "continuum: 2-D FEM (default); beam: the reduced beam model (~0.1 s)"
LINKAGE_CHOICES = ["watt", "roberts", "chebyshev", "peaucellier", "modified_peaucellier"]
# points along a traced path: each costs ~2 ms (twice: the resolution check), 10,000 ~40 s;
# the tracer refuses fewer than 3 and a sampling too coarse for the path
points = whole_number(3, 10_000)  # a path needs 3 points to have a deviation


def travel(text: str) -> float:
    """An end-to-end travel (m) the eight-bar's linkage can trace: refused before meshing
    (EightBarParams' range; a travel too small against the links' size makes the
    large-deflection solve fail to converge, minutes later)."""
    value = positive(text)
    try:
        EightBarParams(travel=value)
    except ValueError as error:
        raise argparse.ArgumentTypeError(str(error)) from None
    return value


def _run_linkage_trace(args) -> dict:
    return trace_classic(args.name, n=args.points)


def _summarize_linkage_trace(result: dict) -> str:
    travel, deviation = result["travel_m"], result["max_deviation_m"]
    if deviation <= 1e-9 * travel:  # an exact straight-line linkage: round-off only
        shown = "0 (exact to round-off)"
    else:
        shown = f"{deviation * 1e6:.4g} um = {result['deviation_pct']:.3g} % of travel"
    return f"{result['linkage']}: travel {travel * 1e3:.2f} mm, max deviation {shown}"


def _run_eightbar_trace(args) -> dict:
    return eightbar_path_summary(EightBarParams(travel=args.travel), n=args.points)


def _summarize_eightbar_trace(result: dict) -> str:
    return (f"eight-bar (rigid body): travel {result['travel_m'] * 1e3:.2f} mm, max deviation "
            f"{result['max_deviation_m'] * 1e6:.3g} um = {result['deviation_pct']:.3g} % of travel "
            f"(band {result['band_m'] * 1e6:.3g} um), size {result['width_m'] * 1e3:.0f} x "
            f"{result['height_m'] * 1e3:.0f} mm, overlapping links: "
            f"{result['overlapping_links'] or 'none'}")


def _run_eightbar_analyze(args) -> dict:
    if args.dim == 3:
        if args.model == "beam":
            out = analyze_eightbar_beam(travel=args.travel, n_modes=4, nonlinear=False, dim=3)
            return {**summary_row(out), "model": "beam"}
        out = analyze_eightbar(travel=args.travel, size_factor=2.0 if args.quick else 1.0,
                               n_modes=4, nonlinear=False, dim=3)
        return summary_row(out)
    if args.model == "beam":
        out = analyze_eightbar_beam(travel=args.travel, steps=8, n_modes=2)
        return {**summary_row(out), "model": "beam"}
    out = analyze_eightbar(travel=args.travel, size_factor=2.0 if args.quick else 1.0,
                           steps=4 if args.quick else 8, both_halves=not args.quick,
                           n_modes=2)
    return summary_row(out)


def _summarize_eightbar_analyze(r: dict) -> str:
    loc = r["max_stress_location"]
    if r.get("dim") == 3:
        modes = ", ".join(f"{m['f_hz']:.4g}" for m in r["modes"])
        model = "3-D beam model" if r.get("model") == "beam" else "3-D FEM"
        return (f"eight-bar flexure suspension, {model} ({r['dofs']} DOFs): k_x = {r['k_x']:.4g} "
                f"N/m (pseudo-rigid-body {r['k_x_prbm']:.4g}), k_y = {r['k_y']:.4g} N/m; linear "
                f"max von Mises {r['max_von_mises'] / 1e6:.4g} MPa at x = "
                f"{r['travel_m'] / 2 * 1e3:.4g} mm, in {loc['flexure']}\nmodes {modes} Hz "
                "(no large-deflection trace in 3-D)")
    model = "beam model" if r.get("model") == "beam" else "2-D FEM"
    return (f"eight-bar flexure suspension, {model} ({r['dofs']} DOFs): k_x = {r['k_x']:.4g} N/m "
            f"(pseudo-rigid-body {r['k_x_prbm']:.4g}), k_y = {r['k_y']:.4g} N/m; linear max von "
            f"Mises {r['max_von_mises'] / 1e6:.4g} MPa at x = {r['travel_m'] / 2 * 1e3:.4g} mm, in "
            f"{loc['flexure']} ({loc['x'] * 1e3:.2f}, {loc['y'] * 1e3:.2f}) mm\n"
            f"large deflection over {r['travel_m'] * 1e3:.4g} mm: path deviation "
            f"{r['fem_deviation_m'] * 1e6:.4g} um = {r['fem_deviation_pct']:.3g} % (rigid body "
            f"{r['rigid_deviation_pct']:.3g} %), peak von Mises {r['peak_von_mises_travel'] / 1e6:.4g}"
            f" MPa in {r['peak_von_mises_flexure']} (yield / peak = {r['safety_factor']:.3g}), end "
            f"force {r['end_force_n']:.3g} N, first mode {r['modes'][0]['f_hz']:.3g} Hz")


def _run_eightbar_stage(args) -> dict:
    return stage_study(quick=args.quick)


def _summarize_eightbar_stage(r: dict) -> str:
    s, b = r["summary"], r["buckling"]
    return (f"eight-bar stage ({r['dofs']} DOFs) over {r['travel_m'] * 1e3:.4g} mm: k_x "
            f"{s['k_x_min']:.4g}-{s['k_x_max']:.4g} N/m, support k_y >= {s['k_y_min']:.4g} N/m "
            f"(k_y/k_x >= {s['support_ratio_min']:.4g}), k_theta >= {s['k_theta_min']:.4g} N m/rad, "
            f"parasitic y <= {s['parasitic_y_max']:.3g} m/m, rotation <= "
            f"{s['parasitic_rotation_max']:.3g} rad/m\nmodes f1 {s['f1_hz_min']:.4g}-"
            f"{s['f1_hz_max']:.4g} Hz, f2 {s['f2_hz_min']:.4g}-{s['f2_hz_max']:.4g} Hz, f3 "
            f"{s['f3_hz_min']:.4g}-{s['f3_hz_max']:.4g} Hz; buckling: drive force "
            f"{b['drive_critical_n']:.4g} N = {b['drive_factor']:.3g} x the end-of-stroke drive"
            f", off-axis (y) {b['off_axis_critical_n']:.4g} N\n" + _stage_buckling_table(r))


def _stage_buckling_table(r: dict) -> str:
    """The critical added loads along the stroke, continuum and beam model, and the ratio."""
    lines = ["buckling along the stroke (critical added force, N; beam / continuum):",
             f"{'x (mm)':>8} {'drive':>8} {'beam':>8} {'ratio':>6} {'+y':>8} {'beam':>8} "
             f"{'ratio':>6} {'-y':>8} {'beam':>8} {'ratio':>6}"]
    for row in r["stroke_buckling"]:
        cells = [f"{row['x_m'] * 1e3:8.3f}"]
        for key, ratio in (("drive_critical_n", "drive_ratio"),
                           ("off_axis_plus_y_n", "off_axis_plus_y_ratio"),
                           ("off_axis_minus_y_n", "off_axis_minus_y_ratio")):
            cells += [f"{row[key]:8.4g}", f"{row['beam_' + key]:8.4g}", f"{row[ratio]:6.3f}"]
        lines.append(" ".join(cells))
    b = r["buckling"]
    lines.append(f"beam model's worst ratio {b['beam_buckling_worst_ratio']:.3f} "
                 f"({b['beam_buckling_worst_case']} at x = {b['beam_buckling_worst_x_m'] * 1e3:.3g}"
                 f" mm): {'within' if b['beam_buckling_within'] else 'beyond'} 5 %")
    return "\n".join(lines)


def _run_eightbar_driving(args) -> dict:
    options = {"size_factor": 3.0 if args.quick else 1.5} if args.model == "continuum" else {}
    return analyze_driving(model=args.model, n_modes=args.modes, **options)


def _summarize_eightbar_driving(r: dict) -> str:
    model = "beam model" if r["model"] == "beam" else "2-D FEM"
    modes = ", ".join(f"{m['f_hz']:.4g}" for m in r.get("modes", []))
    return (f"driving linkage, {model} ({r['dofs']} DOFs): input stiffness "
            f"{r['stiffness_n_per_m']:.4g} N/m (pseudo-rigid-body {r['k_in_prbm']:.4g}), "
            f"transmission d x_R / d s = {r['transmission']:.5g} (rigid linkage "
            f"{r['rigid_transmission']:.5g}), left/right {r['ratio_left_right']:.6f}, peak "
            f"stress {r['max_von_mises_pa'] / r['input_m'] / 1e9:.4g} MPa per mm of input"
            + (f"\nmodes {modes} Hz" if modes else ""))


def _run_eightbar_mesh(args) -> dict:
    mesh, sizes = mesh_eightbar_flexure(EightBarFlexureParams(), size_factor=args.size_factor,
                                        dim=args.dim)
    path = write_mesh(mesh, args.out, order=args.order)
    return {"path": str(path), "order": args.order, "vertices": int(mesh.mesh.p.shape[1]),
            "cells": "tetrahedra" if args.dim == 3 else "triangles",
            "elements": int(mesh.mesh.t.shape[1]), "groups": mesh.group_names, **sizes}


def _summarize_eightbar_mesh(r: dict) -> str:
    return (f"wrote {r['path']}: {r['elements']} {r['cells']} of order {r['order']}, "
            f"{r['vertices']} vertices, flexure "
            f"element {r['flexure_size'] * 1e3:.3g} mm; groups {', '.join(r['groups'])}")


def add_eightbar_commands(eb_sub) -> None:
    """Add ``trace``, ``analyze``, ``stage`` and ``mesh`` to the ``eightbar`` sub-command
    parsers."""
    p = eb_sub.add_parser("trace", help="trace the rigid-body eight-bar's end-effector path")
    deferred(p, _trace_arguments)  # its default travel is the eight-bar geometry's
    p = eb_sub.add_parser("analyze", help="FEM of the flexure suspension: stiffness, stress, "
                          "large-deflection path")
    p.add_argument("--travel", type=travel, default=None,
                   help="end-to-end travel in m (default 0.0331, the thesis')")
    p.add_argument("--quick", action="store_true", help="coarse mesh, half stroke mirrored")
    add_model_options(p, BEAM_HELP, 2, "continuum in 2-D (plane stress, default) or 3-D (the "
                      "solid, 240k DOFs: linear and modal only, ~40 s); with --model beam, 3: "
                      "the spatial beam's modes (out of plane too)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(run=_run_eightbar_analyze, summarize=_summarize_eightbar_analyze)
    p = eb_sub.add_parser("driving", help="the Ch. 6 driving linkage (two lambdas, two "
                          "suspensions): input stiffness, transmission, stress, modes")
    add_model_options(p, BEAM_HELP)
    p.add_argument("--quick", action="store_true", help="continuum: 2x coarser mesh")
    p.add_argument("--modes", type=whole_number(0, 100), default=3,
                   help="natural frequencies computed")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(run=_run_eightbar_driving, summarize=_summarize_eightbar_driving)
    p = eb_sub.add_parser("stage", help="the suspension as a stage: compliance, support "
                          "stiffness, modes and buckling along the stroke (the beam "
                          "model's beside the continuum's)")
    p.add_argument("--quick", action="store_true", help="coarse mesh, half stroke mirrored")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(run=_run_eightbar_stage, summarize=_summarize_eightbar_stage)
    p = eb_sub.add_parser("mesh", help="write the flexure suspension's mesh (.msh .vtu .xdmf .inp)")
    p.add_argument("out", help="output file; the format follows the extension")
    p.add_argument("--size-factor", type=float, default=1.0, help="element size factor")
    p.add_argument("--dim", type=int, choices=(2, 3), default=2,
                   help="2: triangles (default); 3: the solid, tetrahedra in layers through t")
    p.add_argument("--order", type=int, default=2, choices=(1, 2),
                   help="element order written (default 2: the quadratic elements analyze solves)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(run=_run_eightbar_mesh, summarize=_summarize_eightbar_mesh)


def _trace_arguments(p) -> None:
    """``eightbar trace``'s options (its default travel from the eight-bar's geometry)."""
    from ...geometry.eightbar.flexure import THESIS_TRAVEL

    p.add_argument("--travel", type=positive, default=THESIS_TRAVEL,
                   help="end-effector stroke traced, m (default the thesis' 33.1 mm, Ch. 5)")
    p.add_argument("--points", type=points, default=251, help="points along the travel")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(run=_run_eightbar_trace, summarize=_summarize_eightbar_trace)


def _linkage_arguments(p) -> None:
    """``linkage trace``'s options (its choices: the linkages the tracer knows)."""
    from ...geometry.straight_line import CLASSIC_LINKAGES

    p.add_argument("name", choices=sorted(set(LINKAGE_CHOICES) & set(CLASSIC_LINKAGES)))
    p.add_argument("--points", type=points, default=201, help="points along the input range")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(run=_run_linkage_trace, summarize=_summarize_linkage_trace)


def register(subparsers) -> None:
    lk = subparsers.add_parser("linkage", help="classic straight-line linkages (thesis Ch. 2)")
    lk_sub = lk.add_subparsers(dest="linkage_command", required=True)
    p = lk_sub.add_parser("trace", help="trace a straight-line linkage and report its deviation")
    deferred(p, _linkage_arguments)

    eb = subparsers.add_parser("eightbar", help="the symmetric rectilinear eight-bar (thesis Ch. 5)")
    eb_sub = eb.add_subparsers(dest="eightbar_command", required=True)
    add_eightbar_commands(eb_sub)
