"""``flexfem analyze MODEL.toml [--set NAME=VALUE ...] [--model beam] [--json]``: a user's
flexure from its model file (see docs/model_files.md); ``--model beam``: the beam model the file
declares."""
import argparse
from pathlib import Path

from ..lazy import Lazy
from ..options import add_model_options, count, length, size_factor
from ..out_folder import check_out
from .summary import LENGTH_UNITS, summarize

# the analyses, imported when a command runs
analyze = Lazy(".api:analyze", __package__)
load_model = Lazy(".api:load_model", __package__)
load_spec = Lazy("...geometry.user_model:load_spec", __package__)
with_mesh_size = Lazy(".mesh_choice:with_mesh_size", __package__)


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
    """:func:`~.api.analyze` of ``args.model`` with the ``--set`` overrides, as its dict
    (``Report.to_dict``); with ``--out DIR`` also its field files, pictures and page in DIR
    (``Report.write``), listed under "files"."""
    out = getattr(args, "out", None)
    if out is not None:  # a folder that cannot be written is refused before the solve
        check_out(out)
    sets = with_mesh_size(parse_sets(args.set), getattr(args, "mesh_size", None))
    model = load_model(args.model, sets, allow_code=args.allow_code,
                       dim=getattr(args, "dim", None))
    given = getattr(args, "size_factor", None)
    if args.reduced == "beam" and (given is not None
                                   or getattr(args, "mesh_size", None) is not None):
        raise ValueError(f"{model.source}: --size-factor and --mesh-size set the continuum's "
                         "mesh; the beam model (--model beam) has none")
    report = analyze(model, args.reduced, size_factor=given,
                     max_dofs=getattr(args, "max_dofs", None))
    units = "m" if getattr(args, "json", False) else getattr(args, "units", "m")  # summary only
    result = report.to_dict()
    if units != "m":
        result["display_units"] = units
    if out is not None:
        result["files"] = report.write(out, units)
    return result


def summarize_run(result: dict) -> str:
    """:func:`summarize`, and with ``--out`` the files written."""
    files = result.get("files")
    tail = (f"\nwrote {len(files)} files, the page {files[-1]}: "
            + ", ".join(Path(f).name for f in files[:-1])) if files else ""
    return summarize(result) + tail


def register(subparsers):
    parser = subparsers.add_parser(
        "analyze", help="analyse your own flexure from a model file (TOML + .geo/.step/.msh)")
    parser.add_argument("model", metavar="MODEL.toml", help="the model file")
    parser.add_argument("--set", action="append", metavar="NAME=VALUE", default=[],
                        help="override a [parameters] entry (SI), or TABLE.KEY such as "
                             "material.E; repeatable")
    add_model_options(parser, "continuum: the FEM of the geometry (default); beam: the beam "
                              "model the file declares ([[beam]], [[rigid]])", dest="reduced")
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
    """``flexfem export``: the outline of a model file of bodies and flexures as DXF or STEP;
    a spatial file's fused solid as STEP (geometry/spatial/export.py)."""
    from ...geometry.outline_files import UNIT

    spec = load_spec(args.model, parse_sets(args.set), allow_code=args.allow_code,
                     bodies_only="export")
    if spec.spatial is not None:
        from ...geometry.spatial.export import write_spatial_step

        path = write_spatial_step(spec.spatial, args.out)
        return {"model": spec.source, "out": str(path), "dim": 3, "format": "step",
                "units": UNIT}
    from ...geometry.mechanism.export import export

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
                        help="STEP: 2 the face (default), 3 the solid extruded by the depth; "
                             "a spatial file's STEP is always its solid")
    parser.add_argument("--allow-code", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.set_defaults(run=run_export, summarize=summarize_export)
