"""``flexfem dbma``: FEM analysis and mesh of the double-row bow-type amplifier (DBMA)."""
import dataclasses
from pathlib import Path

from ..lazy import Lazy
from ..options import add_model_options, count, damping_ratio, positive

# what the commands compute with, imported when one runs (meshing, the FEM, the beam model)
deck_lines = Lazy("...fem.calculix:deck_lines", __package__)
write_mesh = Lazy("...fem.export:write_mesh", __package__)
mesh_dbma = Lazy("...geometry.dbma.drawing:mesh_dbma", __package__)
paper_design = Lazy("...geometry.dbma.params:paper_design", __package__)
actuator_loads = Lazy(".analysis:actuator_loads", __package__)
analyze_dbma = Lazy(".analysis:analyze_dbma", __package__)
build_model = Lazy(".analysis:build_model", __package__)
modal_supports = Lazy(".analysis:modal_supports", __package__)
published = Lazy(".analysis:published", __package__)
static_supports = Lazy(".analysis:static_supports", __package__)
frf_study = Lazy(".dynamics:frf_study", __package__)
analyze_dbma_beam = Lazy(".beam:analyze_dbma_beam", __package__)

MESH_SUFFIXES = (".msh", ".vtu", ".xdmf", ".inp")
DECK_FORCE = 800.0  # N, the actuator force of the paper's tests (Sec. 5) and of analyze


def _params(args):
    """The paper's design with --h / --b (m) replaced; invalid values raise ValueError."""
    changes = {k: getattr(args, k) for k in ("h", "b") if getattr(args, k) is not None}
    return dataclasses.replace(paper_design(), **changes)


def run_analyze(args) -> dict:
    if args.model == "beam":
        force = float(published()["loading"]["force_max_N"])
        return {**analyze_dbma_beam(_params(args), force=force, dim=args.dim), "dim": args.dim}
    return analyze_dbma(_params(args), dim=args.dim, size_factor=args.size_factor,
                        max_dofs=args.max_dofs)


def summarize_analyze(r: dict) -> str:
    freqs = ", ".join(f"{f:.1f}" for f in r["frequencies_hz"])
    x, y = (1e3 * v for v in r["max_von_mises_location"][:2])
    model = f"{r['dim']}-D " + ("beam model" if r.get("model") == "beam" else "FEM")
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
        *(f"note: {note}" for note in r.get("validity_notes", [])),
    ])


def run_frf(args) -> dict:
    return frf_study(damping=args.damping, dim=args.dim, size_factor=args.size_factor)


def summarize_frf(r: dict) -> str:
    o, p, b = r["output"], r["paper"], r["buckling"]
    lines = [
        f"DBMA dynamics, {r['dim']}-D FEM, {r['dofs']} DOFs, actuator rod "
        f"{r['actuator_stiffness']:.3g} N/m, modal damping {100 * r['damping']:.3g} %",
        f"output stiffness {o['k_out']:.4g} N/m, lateral {o['k_lateral']:.4g} N/m; parasitic "
        f"lateral {o['parasitic_lateral']:.3g} m/m, rotation {o['parasitic_rotation']:.3g} rad/m",
        f"static output / force {r['static_output_m_per_n']:.4g} m/N; resonance "
        f"{r['resonance_hz']:.1f} Hz (pads held: {r['working_frequency_pads_held_hz']:.1f} Hz; "
        f"paper {p['fn_measured_hz']:.4g} measured, {p['fn_fem_hz']:.4g} FEM)",
        f"-3 dB bandwidth {r['bandwidth_minus3db_hz']:.1f} Hz (paper: up to "
        f"{p['bandwidth_hz']:.0f} Hz), flat (+-3 dB) to {r['flat_bandwidth_hz']:.1f} Hz, "
        f"half-power width {r['half_power_bandwidth_hz']:.2f} Hz",
    ]
    lines += [f"  zeta {100 * s['damping']:.3g} %: resonance {s['resonance_hz']:.1f} Hz, peak x"
              f"{s['amplification_at_resonance']:.3g}, -3 dB bandwidth "
              f"{s['bandwidth_minus3db_hz']:.1f} Hz" for s in r.get("sensitivity", [])]
    lines.append(f"hinge buckling at {b['force_n']:.0f} N: factor {b['factor']:.3g} "
                 f"(critical actuator force {b['critical_force_n']:.4g} N)")
    return "\n".join(lines)


def run_mesh(args) -> dict:

    path = Path(args.out)
    if path.suffix not in MESH_SUFFIXES:
        raise ValueError(f"OUT = {args.out!r}: the extension must be one of {MESH_SUFFIXES}")
    if args.deck:
        return write_deck(path, _params(args), args.dim, args.size_factor, args.deck)
    mesh = mesh_dbma(_params(args), dim=args.dim, size_factor=args.size_factor)
    write_mesh(mesh, path, order=args.order)
    return {"path": str(path), "dim": args.dim, "order": args.order,
            "vertices": int(mesh.mesh.p.shape[1]), "elements": int(mesh.mesh.t.shape[1]),
            "groups": mesh.group_names}


def write_deck(path: Path, params, dim: int, size_factor: float, kind: str) -> dict:
    """The model ``analyze`` solves (quadratic elements) as a complete CalculiX deck: its
    supports and the paper's 800 N actuator force (static), or the modal supports and six
    modes (modal)."""
    if path.suffix != ".inp":
        raise ValueError(f"--deck writes a CalculiX deck: OUT = {str(path)!r} must end in .inp")
    model = build_model(params, None, dim, size_factor)
    lines = (deck_lines(model, static_supports(), actuator_loads(DECK_FORCE, dim))
             if kind == "static" else deck_lines(model, modal_supports(), n_modes=6))
    path.write_text("\n".join(lines) + "\n")
    return {"path": str(path), "dim": dim, "order": model.order, "deck": kind,
            "vertices": int(model.mesh.mesh.p.shape[1]),
            "elements": int(model.mesh.mesh.t.shape[1]), "groups": model.mesh.group_names}


def summarize_mesh(r: dict) -> str:
    what = f"CalculiX {r['deck']} deck" if r.get("deck") else "mesh"
    return (f"wrote {r['path']} ({what}): {r['dim']}-D, order {r['order']} "
            f"({'quadratic, as analyze solves' if r['order'] == 2 else 'linear'}), "
            f"{r['vertices']} vertices, {r['elements']} elements, groups {', '.join(r['groups'])}")



def register(subparsers):
    parser = subparsers.add_parser("dbma", help="double-row bow-type amplifier: FEM and mesh")
    commands = parser.add_subparsers(dest="dbma_command", required=True, metavar="ACTION")
    analyze = commands.add_parser("analyze", help="static and modal FEM beside the formulas")
    analyze.add_argument("--h", type=float, help="hinge offset h (m), default the paper's 2.6e-3")
    analyze.add_argument("--b", type=float, help="hinge thickness b (m), default 0.6e-3")
    analyze.add_argument("--dim", type=int, choices=(2, 3), default=3,
                         help="3: statics and modes on the 3-D mesh (default); 2: plane stress, "
                              "the report's statics (R differs by the out-of-plane stiffness)")
    analyze.add_argument("--size-factor", type=positive, default=1.0,
                         help="mesh size multiplier (default 1)")
    analyze.add_argument("--max-dofs", type=count, default=None,
                         help="refuse a mesh above this many unknowns (default: what half the "
                              "available memory affords)")
    add_model_options(analyze, "continuum: FEM (default); beam: the reduced beam model (its "
                               "statics in-plane; --dim 3: the spatial beam's modes, out of "
                               "plane too)")
    analyze.add_argument("--json", action="store_true", help="print one JSON object")
    analyze.set_defaults(run=run_analyze, summarize=summarize_analyze)
    frf = commands.add_parser("frf", help="output compliance, FRF from actuator force to "
                              "output, bandwidth, hinge buckling at 800 N")
    frf.add_argument("--damping", type=damping_ratio, default=None,
                     help="modal damping ratio (default 0.02, steel; data/dbma_paper.toml)")
    frf.add_argument("--dim", type=int, choices=(2, 3), default=2, help="model dimension")
    frf.add_argument("--size-factor", type=positive, default=1.0,
                     help="mesh size multiplier (default 1)")
    frf.add_argument("--json", action="store_true", help="print one JSON object")
    frf.set_defaults(run=run_frf, summarize=summarize_frf)
    mesh = commands.add_parser("mesh", help="write the default mesh that analyze solves")
    mesh.add_argument("out", help="output file: .msh, .vtu, .xdmf or .inp")
    mesh.add_argument("--h", type=float, help="hinge offset h (m), default the paper's 2.6e-3")
    mesh.add_argument("--b", type=float, help="hinge thickness b (m), default 0.6e-3")
    mesh.add_argument("--dim", type=int, choices=(2, 3), default=3, help="mesh dimension")
    mesh.add_argument("--size-factor", type=positive, default=1.0, help="mesh size multiplier")
    mesh.add_argument("--order", type=int, choices=(1, 2), default=2,
                      help="element order written (default 2: the quadratic elements analyze "
                           "solves; CalculiX reads them as C3D10 / CPS6)")
    mesh.add_argument("--deck", choices=("static", "modal"),
                      help="write a complete CalculiX deck (OUT.inp): the mesh, material, "
                           "supports and the 800 N actuator force (static) or six modes (modal)")
    mesh.add_argument("--json", action="store_true", help="print one JSON object")
    mesh.set_defaults(run=run_mesh, summarize=summarize_mesh)
