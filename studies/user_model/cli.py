"""``flexfem analyze MODEL.toml [--set NAME=VALUE ...] [--model beam] [--json]``: a user's
flexure from its model file (see docs/model_files.md); ``--model beam``: the beam model the file
declares."""
import argparse
from pathlib import Path

from ...geometry.user_model import load_spec
from ..options import count, length, size_factor
from .analysis import analyze_model
from .mesh_choice import cli_size_factor, with_mesh_size

_AXES = ("x", "y", "z")


def parse_sets(items) -> dict:
    """['L=0.05', 'material.E=2e11'] -> {'L': 0.05, 'material.E': 2e11} (values as numbers;
    a value that is not a number stays a string, e.g. material.name=aluminium_6061_t6)."""
    out = {}
    for item in items or []:
        name, sep, value = item.partition("=")
        if not sep or not name.strip():
            raise ValueError(f"--set {item!r}: write NAME=VALUE, e.g. --set L=0.05")
        text = value.strip()
        try:
            number = float(text)
            out[name.strip()] = int(number) if text.lstrip("-").isdigit() else number
        except ValueError:
            out[name.strip()] = text
    return out


def run(args) -> dict:
    """analyze_model of ``args.model`` with the ``--set`` overrides; with ``--out DIR`` also
    its field files, pictures and page in DIR (page.py), listed under "files"."""
    out = getattr(args, "out", None)
    if out is not None:  # a folder that cannot be written is refused before the solve
        from .page import check_out, write_outputs

        check_out(out)
    sets = with_mesh_size(parse_sets(args.set), getattr(args, "mesh_size", None))
    spec = load_spec(args.model, sets, allow_code=args.allow_code,
                     dim=getattr(args, "dim", None))
    factor, choice = cli_size_factor(spec, args)  # mesh_choice.py: fits the budget in 3-D
    kept = {} if out is not None else None
    result = analyze_model(spec, factor, model=args.reduced,
                           max_dofs=getattr(args, "max_dofs", None), fields=kept)
    if choice is not None:
        result.update(size_factor=factor, mesh_choice=choice)
    if getattr(args, "units", "m") != "m" and not args.json:  # the summary's lengths only
        result["display_units"] = args.units
    if out is not None:
        result["files"] = write_outputs(out, spec, result, kept, summarize(result))
    return result


def summarize_run(result: dict) -> str:
    """:func:`summarize`, and with ``--out`` the files written."""
    files = result.get("files")
    tail = (f"\nwrote {len(files)} files, the page {files[-1]}: "
            + ", ".join(Path(f).name for f in files[:-1])) if files else ""
    return summarize(result) + tail


#: Length units of the human summary (--units): metres by default; --json stays SI.
LENGTH_UNITS = {"m": 1.0, "mm": 1e3, "um": 1e6}


def _vector(v, unit: str, scale: float = 1.0) -> str:
    return "(" + ", ".join(f"{c * scale:.4g}" for c in v) + f") {unit}"


def _lengths(result: dict) -> tuple[str, float]:
    """(unit, scale from m) of the summary's lengths."""
    unit = result.get("display_units", "m")
    return unit, LENGTH_UNITS[unit]


def summarize(result: dict) -> str:
    m, to = _lengths(result)
    lines = [f"{result['model']}: {result['dim']}-D, {result['dofs']} DOFs, solver "
             f"{result['solver']}, element size h = {result['h'] * to:.4g} {m}"]
    if result.get("mesh_choice") not in (None, "default"):
        lines.append(f"mesh: {result['mesh_choice']}" if result["mesh_choice"] != "given" else
                     f"mesh: size_factor {result['size_factor']:g} (given)")
    vm = result["max_von_mises"]
    where = _vector(result["max_von_mises_location"], m, to)
    strength = result["yield_strength"]
    share = (f" ({100 * vm / strength:.4g} % of yield)" if strength is not None and vm > 0 else
             " (% of yield not available: needs yield_strength)" if strength is None else "")
    lines.append(f"max von Mises stress {vm / 1e6:.4g} MPa at {where}{share}")
    for group, u in result["mean_displacement"].items():
        lines.append(f"mean displacement of {group!r}: {_vector(u, m, to)}")
    for group, f in result["reactions"].items():
        lines.append(f"reaction on {group!r}: {_vector(f, 'N')}")
    for group, by_axis in result["stiffness"].items():
        for axis, k in by_axis.items():
            lines.append(f"stiffness of {group!r} along {axis}: {k / to:.4g} N/{m}")
    if result.get("stroke_limit_yield") is not None or "stroke_group" in result:
        lines += _stroke_lines(result)
    if "frequencies_hz" in result:
        lines.append("natural frequencies: " + ", ".join(f"{f:.4g}" for f in
                                                          result["frequencies_hz"]) + " Hz")
    if "compliance" in result:
        c = result["compliance"]
        lines.append(f"compliance of {c['group']!r} (rigid face at {_vector(c['point_m'], m, to)}"
                     "): diagonal " + _vector([r[i] for i, r in enumerate(c["matrix"])],
                                              "(m/N, rad/(N m))"))
    if "buckling" in result:
        lines.append("buckling load factors: " + ", ".join(
            f"{f:.4g}" for f in result["buckling"]["load_factors"]))
    if "harmonic" in result:
        h = result["harmonic"]
        lines.append(f"harmonic response of {h['group']!r} along {h['component']} "
                     f"({100 * h['damping']:.3g} % damping): static {h['static'] * to:.4g} {m}, "
                     "resonances " + (", ".join(f"{f:.4g}" for f in h["resonances_hz"])
                                      or "none in range") + " Hz")
    if "nonlinear" in result:
        nl = result["nonlinear"]
        for group, u in nl["mean_displacement"].items():
            lines.append(f"large deflection ({nl['steps']} steps), mean displacement of "
                         f"{group!r}: {_vector(u, m, to)}")
    return "\n".join(lines + _output_lines(result))


def _output_lines(result: dict) -> list[str]:
    """The [outputs] (and, with steps, at the final step) and the rotations of the bodies
    and faces observed."""
    lines, why = [], result.get("not_available", {})
    m, to = _lengths(result)
    for name, value in result.get("outputs", {}).items():
        lines.append(f"output {name} = {value:.6g}" if value is not None else
                     f"output {name}: not available: {why.get('outputs.' + name, '')}")
    for name, value in result.get("nonlinear", {}).get("outputs", {}).items():
        if value is not None:
            lines.append(f"large deflection, output {name} = {value:.6g}")
    for group, o in result.get("observations", {}).items():
        turns = {k: v for k, v in o.items() if k.startswith("r") and v is not None}
        if turns and group not in result["mean_displacement"]:
            u = _vector([v for k, v in o.items() if k[0] == "u"], m, to)
            lines.append(f"observed {group!r}: u = {u}"
                         + "".join(f", {k} = {v:.4g} rad" for k, v in turns.items()))
    return lines


def _stroke_lines(result: dict) -> list[str]:
    """The stroke limits in a designer's words."""
    group, n = result["stroke_group"], result.get("safety_factor", 1.0)
    lines = []
    if "stroke_limit_where" not in result:  # no stress to size it by
        return [f"no stroke limit of {group!r}: sized by {result['stroke_stress_basis']}"]
    missing = result.get("not_available", {})
    if result["stroke_limit_yield"] is not None:
        lines.append(f"stroke of {group!r} to yield (safety factor {n:g}): "
                     f"{result['stroke_limit_yield'] * 1e3:.4g} mm")
    else:
        lines.append(f"stroke of {group!r} to yield: not available: "
                     f"{missing.get('stroke_limit_yield', 'no yield strength')}")
    if result["stroke_limit_fatigue"] is not None:
        mean = (f" about a mean of {result['mean_stroke'] * 1e3:.4g} mm"
                if result["mean_stroke"] else "")
        lines.append(f"stroke amplitude of {group!r} for {result['fatigue_cycles']:.3g} cycles "
                     f"({result['fatigue_criterion']}{mean}): "
                     f"{result['stroke_limit_fatigue'] * 1e3:.4g} mm")
    else:
        lines.append(f"fatigue-limited stroke amplitude of {group!r}: not available: "
                     f"{missing.get('stroke_limit_fatigue', 'no fatigue data')}")
    lines.append(f"  sized by the {result['stroke_stress_basis']}, at "
                 f"{_vector(result['stroke_limit_where'], *_lengths(result))}")
    if result.get("stroke_limit_basis"):
        lines.append(f"  stroke limits: {result['stroke_limit_basis']}" + _departed(result))
    return lines


def _departed(result: dict) -> str:
    """How far the large-deflection path departs from linear at the linear yield stroke."""
    check = result.get("stroke_check")
    if not check:
        return ""
    d = check["departure"]
    return (f" (at {check['at_stroke'] * 1e3:.4g} mm the {check['model']} model's force, "
            f"outputs and peak stress depart from linear by {100 * d['force']:+.1f} %, "
            f"{100 * d['output']:.1f} %, {100 * d['stress']:+.1f} %)")


def register(subparsers):
    parser = subparsers.add_parser(
        "analyze", help="analyse your own flexure from a model file (TOML + .geo/.step/.msh)")
    parser.add_argument("model", metavar="MODEL.toml", help="the model file")
    parser.add_argument("--set", action="append", metavar="NAME=VALUE", default=[],
                        help="override a [parameters] entry (SI), or TABLE.KEY such as "
                             "material.E; repeatable")
    parser.add_argument("--model", dest="reduced", choices=("continuum", "beam"),
                        default="continuum",
                        help="continuum: the FEM of the geometry (default); beam: the beam "
                             "model the file declares ([[beam]], [[rigid]])")
    parser.add_argument("--max-dofs", type=count, default=None, metavar="N",
                        help="refuse a mesh estimated above N unknowns, before meshing "
                             "(default: what half the available memory affords)")
    parser.add_argument("--size-factor", type=size_factor, default=None, metavar="F",
                        help="multiply every element size by F (default 1; with --dim 3, the "
                             "smallest F whose mesh fits the DOF budget)")
    parser.add_argument("--mesh-size", type=length, default=None, metavar="M",
                        help="the bodies' element size, m or with a unit ('2 mm'): "
                             "--set mesh.size=M")
    parser.add_argument("--dim", type=int, choices=(2, 3), default=None,
                        help="bodies and flexures: 2 (default) or 3, the continuum extruded by "
                             "the [section] thickness")
    parser.add_argument("--out", metavar="DIR", default=None,
                        help="also write the fields (VTU, for ParaView), pictures (PNG) and a "
                             "page (index.html) of the model solved into DIR (created if "
                             "missing)")
    parser.add_argument("--allow-code", action="store_true",
                        help="trust the model file: its .geo may run programs, write files "
                             "and read outside its folder (refused by default)")
    parser.add_argument("--units", choices=sorted(LENGTH_UNITS), default="m",
                        help="lengths of the human summary (stiffness per that length); "
                             "--json and the files stay SI")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.set_defaults(run=run, summarize=summarize_run)
    register_export(subparsers)


def run_export(args) -> dict:
    """``flexfem export``: the outline of a model file of bodies and flexures as DXF or STEP."""
    from ...geometry.mechanism.export import export
    from ...geometry.outline_files import UNIT

    spec = load_spec(args.model, parse_sets(args.set), allow_code=args.allow_code,
                     bodies_only="export")
    path = export(spec.mechanism, args.out, args.dim)
    return {"model": spec.source, "out": str(path), "dim": args.dim,
            "format": path.suffix.lower().lstrip("."), "units": UNIT}


def summarize_export(result: dict) -> str:
    return (f"{result['model']}: {result['dim']}-D outline written to {result['out']} "
            f"({result['format'].upper()}, {result['units']})")


def register_export(subparsers):
    parser = subparsers.add_parser(
        "export", help="write a model's outline for manufacture (DXF or STEP, in mm)")
    parser.add_argument("model", metavar="MODEL.toml", help="a model file of bodies and flexures")
    parser.add_argument("out", metavar="OUT.dxf|OUT.step", help="the file to write")
    parser.add_argument("--set", action="append", metavar="NAME=VALUE", default=[],
                        help="override a [parameters] entry (SI); repeatable")
    parser.add_argument("--dim", type=int, choices=(2, 3), default=2,
                        help="STEP: 2 the face (default), 3 the solid extruded by the depth")
    parser.add_argument("--allow-code", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.set_defaults(run=run_export, summarize=summarize_export)
