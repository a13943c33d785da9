"""``flexfem linkage trace NAME`` and ``flexfem eightbar trace``: rigid-body straight-line paths."""
from flexfem.geometry.straight_line import CLASSIC_LINKAGES
from flexfem.studies.eightbar_path import eightbar_path_summary, trace_classic

LINKAGE_CHOICES = ["watt", "roberts", "chebyshev", "peaucellier", "modified_peaucellier"]


def _run_linkage_trace(args) -> dict:
    return trace_classic(args.name, n=args.points)


def _summarize_linkage_trace(result: dict) -> str:
    return (f"{result['linkage']}: travel {result['travel_m'] * 1e3:.3f} mm, max deviation "
            f"{result['max_deviation_m'] * 1e6:.4g} um = {result['deviation_pct']:.4g} % of travel")


def _run_eightbar_trace(args) -> dict:
    return eightbar_path_summary(n=args.points)


def _summarize_eightbar_trace(result: dict) -> str:
    return (f"eight-bar (rigid body): travel {result['travel_m'] * 1e3:.2f} mm, max deviation "
            f"{result['max_deviation_m'] * 1e6:.3g} um = {result['deviation_pct']:.3g} % of travel "
            f"(band {result['band_m'] * 1e6:.3g} um), size {result['width_m'] * 1e3:.0f} x "
            f"{result['height_m'] * 1e3:.0f} mm, overlapping links: "
            f"{result['overlapping_links'] or 'none'}")


def add_eightbar_commands(eb_sub) -> None:
    """Add ``trace`` to the ``eightbar`` sub-command parsers."""
    p = eb_sub.add_parser("trace", help="trace the rigid-body eight-bar's end-effector path")
    p.add_argument("--points", type=int, default=251, help="points along the travel")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(run=_run_eightbar_trace, summarize=_summarize_eightbar_trace)


def register(subparsers) -> None:
    lk = subparsers.add_parser("linkage", help="classic straight-line linkages (thesis Ch. 2)")
    lk_sub = lk.add_subparsers(dest="linkage_command", required=True)
    p = lk_sub.add_parser("trace", help="trace a straight-line linkage and report its deviation")
    p.add_argument("name", choices=sorted(set(LINKAGE_CHOICES) & set(CLASSIC_LINKAGES)))
    p.add_argument("--points", type=int, default=201, help="points along the input range")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(run=_run_linkage_trace, summarize=_summarize_linkage_trace)

    eb = subparsers.add_parser("eightbar", help="the symmetric rectilinear eight-bar (thesis Ch. 5)")
    eb_sub = eb.add_subparsers(dest="eightbar_command", required=True)
    add_eightbar_commands(eb_sub)
