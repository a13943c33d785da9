"""``flexfem optimize dbma``: FEM-decided search of the DBMA hinge dimensions (SI units)."""
from ..lazy import Lazy

# imported when the search runs (its options: when it is the command, studies/cli.py)
OptimizeSpec = Lazy(".optimize_spec:OptimizeSpec", __package__)
run_search = Lazy(".optimize_output:run", __package__)
summarize_search = Lazy(".optimize_output:summarize", __package__)

HELP = ("maximise the DBMA's amplification ratio over b, h, l under frequency, stress and "
        "output-stiffness constraints (analytical seed, 2-D FEM decides)")

# option -> OptimizeSpec field
SPEC_OPTIONS = {
    "--b-min": "b_min", "--b-max": "b_max", "--h-min": "h_min", "--h-max": "h_max",
    "--l-min": "l_min", "--l-max": "l_max", "--min-frequency": "min_frequency_hz",
    "--safety-factor": "safety_factor", "--stroke": "stroke_m",
    "--min-output-stiffness": "min_output_stiffness",
}
UNITS = {"min_frequency_hz": "Hz", "safety_factor": "-", "min_output_stiffness": "N/m"}


def add_arguments(parser) -> None:
    defaults = OptimizeSpec()
    for option, name in SPEC_OPTIONS.items():
        unit = UNITS.get(name, "m")
        parser.add_argument(option, dest=name, type=float, default=getattr(defaults, name),
                            help=f"{name} ({unit}, default {getattr(defaults, name):g})")
    parser.add_argument("--max-evaluations", type=int, default=defaults.max_evaluations,
                        help=f"FEM evaluations of the search (default {defaults.max_evaluations})")
    parser.add_argument("--out", default="dbma_optimize",
                        help="folder for the evaluation store, optimize_history.csv and .png "
                             "(default ./dbma_optimize; a re-run reuses the stored evaluations)")
    parser.add_argument("--quick", action="store_true",
                        help="smoke run: at most 12 FEM evaluations, 256 screened designs")
    parser.add_argument("--screen", choices=("closed-form", "beam"), default="closed-form",
                        help="screening model of the Sobol sample: the closed forms (default) "
                             "or the generated beam model (~0.2 s a design); the FEM decides")
    parser.add_argument("--json", action="store_true", help="print the result as one JSON object")


def run(args) -> dict:
    values = {name: getattr(args, name) for name in SPEC_OPTIONS.values()}
    spec = OptimizeSpec(**values, max_evaluations=args.max_evaluations)
    return run_search(spec, args.out, quick=args.quick, screen=args.screen)


def summarize(result: dict) -> str:
    files = ", ".join(result.get("tables", []) + result.get("figures", []))
    return summarize_search(result) + (f"\nresults in {result['out']}: {files}" if "out" in result else "")
