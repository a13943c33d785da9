"""``flexfem dbma``: FEM analysis and mesh of the double-row bow-type amplifier (DBMA)."""
import dataclasses
from pathlib import Path

from ...fem.export import write_mesh
from ...geometry.dbma.drawing import mesh_dbma
from ...geometry.dbma.params import paper_design
from .analysis import analyze_dbma, published
from .beam import analyze_dbma_beam

MESH_SUFFIXES = (".msh", ".vtu", ".xdmf", ".inp")


def _params(args):
    """The paper's design with --h / --b (m) replaced; invalid values raise ValueError."""
    changes = {k: getattr(args, k) for k in ("h", "b") if getattr(args, k) is not None}
    return dataclasses.replace(paper_design(), **changes)


def run_analyze(args) -> dict:
    if args.model == "beam":
        force = float(published()["loading"]["force_max_N"])
        return {**analyze_dbma_beam(_params(args), force=force), "dim": "beam"}
    return analyze_dbma(_params(args), dim=args.dim, size_factor=args.size_factor)


def summarize_analyze(r: dict) -> str:
    freqs = ", ".join(f"{f:.1f}" for f in r["frequencies_hz"])
    x, y = (1e3 * v for v in r["max_von_mises_location"][:2])
    model = "beam model" if r["dim"] == "beam" else f"{r['dim']}-D FEM"
    return "\n".join([
        f"DBMA, {model}, {r['dofs']} DOFs",
        f"R FEM (output / elongation)         {r['R_fem']:.3f}",
        f"R FEM (output / one pad's motion)   {r['R_fem_per_side']:.3f}",
        f"R Eq. 7 / enhanced model            {r['R_eq7']:.3f} / {r['R_enhanced']:.3f}",
        f"Ke Eq. 14                           {r['Ke_eq14']:.4g} N/m",
        f"input stiffness k_in                {r['k_in']:.4g} N/m",
        f"{'max von Mises at %.0f N' % r['force']:<36}{r['max_von_mises'] / 1e6:.1f} MPa at "
        f"({x:.2f}, {y:.2f}) mm, safety factor {r['safety_factor']:.2f}",
        f"{'first %d frequencies (Hz)' % len(r['frequencies_hz']):<36}{freqs}",
        f"working mode                        {r['working_mode']} "
        f"({r['fn_working']:.1f} Hz; Eq. 20: {r['fn_eq20']:.1f} Hz)",
    ])


def run_mesh(args) -> dict:

    path = Path(args.out)
    if path.suffix not in MESH_SUFFIXES:
        raise ValueError(f"OUT = {args.out!r}: the extension must be one of {MESH_SUFFIXES}")
    mesh = mesh_dbma(_params(args), dim=args.dim, size_factor=args.size_factor)
    write_mesh(mesh, path)
    return {"path": str(path), "dim": args.dim, "vertices": int(mesh.mesh.p.shape[1]),
            "elements": int(mesh.mesh.t.shape[1]), "groups": mesh.group_names}


def summarize_mesh(r: dict) -> str:
    return (f"wrote {r['path']}: {r['dim']}-D, {r['vertices']} vertices, {r['elements']} "
            f"elements, groups {', '.join(r['groups'])}")


def _positive(text: str) -> float:
    value = float(text)
    if not value > 0:
        raise ValueError(f"{text!r} must be > 0")
    return value


def register(subparsers):
    parser = subparsers.add_parser("dbma", help="double-row bow-type amplifier: FEM and mesh")
    commands = parser.add_subparsers(dest="dbma_command", required=True, metavar="ACTION")
    analyze = commands.add_parser("analyze", help="static and modal FEM beside the formulas")
    analyze.add_argument("--h", type=float, help="hinge offset h (m), default the paper's 2.6e-3")
    analyze.add_argument("--b", type=float, help="hinge thickness b (m), default 0.6e-3")
    analyze.add_argument("--dim", type=int, choices=(2, 3), default=3)
    analyze.add_argument("--size-factor", type=_positive, default=1.0,
                         help="mesh size multiplier (default 1)")
    analyze.add_argument("--model", choices=("continuum", "beam"), default="continuum",
                         help="continuum: FEM (default); beam: the reduced beam model")
    analyze.add_argument("--json", action="store_true", help="print one JSON object")
    analyze.set_defaults(run=run_analyze, summarize=summarize_analyze)
    mesh = commands.add_parser("mesh", help="write the default mesh that analyze solves")
    mesh.add_argument("out", help="output file: .msh, .vtu, .xdmf or .inp")
    mesh.add_argument("--h", type=float, help="hinge offset h (m), default the paper's 2.6e-3")
    mesh.add_argument("--b", type=float, help="hinge thickness b (m), default 0.6e-3")
    mesh.add_argument("--dim", type=int, choices=(2, 3), default=3)
    mesh.add_argument("--size-factor", type=_positive, default=1.0)
    mesh.add_argument("--json", action="store_true", help="print one JSON object")
    mesh.set_defaults(run=run_mesh, summarize=summarize_mesh)
