"""``flexfem optimize dbma``: FEM-decided search of the DBMA hinge dimensions (SI units)."""
from .dbma_optimize import OptimizeSpec

# option -> OptimizeSpec field
SPEC_OPTIONS = {
    "--b-min": "b_min", "--b-max": "b_max", "--h-min": "h_min", "--h-max": "h_max",
    "--l-min": "l_min", "--l-max": "l_max", "--min-frequency": "min_frequency_hz",
    "--safety-factor": "safety_factor", "--stroke": "stroke_m",
    "--min-output-stiffness": "min_output_stiffness",
}
UNITS = {"min_frequency_hz": "Hz", "safety_factor": "-", "min_output_stiffness": "N/m"}


def register(subparsers):
    p = subparsers.add_parser("optimize", help="design search: hinge dimensions maximising R")
    mechanisms = p.add_subparsers(dest="mechanism", required=True, metavar="MECHANISM")
    d = mechanisms.add_parser(
        "dbma", help="maximise the DBMA's amplification ratio over b, h, l under frequency, "
                     "stress and output-stiffness constraints (analytical seed, 2-D FEM decides)")
    defaults = OptimizeSpec()
    for option, name in SPEC_OPTIONS.items():
        unit = UNITS.get(name, "m")
        d.add_argument(option, dest=name, type=float, default=getattr(defaults, name),
                       help=f"{name} ({unit}, default {getattr(defaults, name):g})")
    d.add_argument("--max-evaluations", type=int, default=defaults.max_evaluations,
                   help=f"FEM evaluations of the search (default {defaults.max_evaluations})")
    d.add_argument("--out", default="dbma_optimize",
                   help="folder for the evaluation store, optimize_history.csv and .png "
                        "(default ./dbma_optimize; a re-run reuses the stored evaluations)")
    d.add_argument("--quick", action="store_true",
                   help="smoke run: at most 12 FEM evaluations, 256 screened designs")
    d.add_argument("--json", action="store_true", help="print the result as one JSON object")
    d.set_defaults(run=run_optimize, summarize=summarize_optimize)


def run_optimize(args) -> dict:
    from .dbma_optimize import run
    values = {name: getattr(args, name) for name in SPEC_OPTIONS.values()}
    spec = OptimizeSpec(**values, max_evaluations=args.max_evaluations)
    return run(spec, args.out, quick=args.quick)


def summarize_optimize(result: dict) -> str:
    from .dbma_optimize_output import summarize
    files = ", ".join(result.get("tables", []) + result.get("figures", []))
    return summarize(result) + (f"\nresults in {result['out']}: {files}" if "out" in result else "")
