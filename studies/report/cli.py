"""``flexfem reproduce``: the main job, every comparison with the source documents."""
import sys

from ..mechanisms import report_sections
from .reproduce import reproduce


def register(subparsers):
    p = subparsers.add_parser("reproduce", help="regenerate every comparison with the source documents")
    p.add_argument("--out", default="report", help="report folder (default: ./report)")
    size = p.add_mutually_exclusive_group()
    size.add_argument("--quick", action="store_true", help="smoke run, coarse meshes (< 2 min)")
    size.add_argument("--full", action="store_true", help="the finest meshes")
    p.add_argument("--resume", action="store_true", help="keep sections already finished in --out")
    p.add_argument("--section", action="append", choices=[s.folder for _, s in report_sections()],
                   help="run only this section (repeatable)")
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    p.set_defaults(run=_run, summarize=summarize)


def _run(args) -> dict:
    progress = (lambda line: print(line, file=sys.stderr)) if sys.stderr.isatty() else None
    report = reproduce(args.out, quick=args.quick, full=args.full, resume=args.resume,
                       sections=args.section, progress=progress)
    report["out"] = str(args.out)
    return report


def summarize(report: dict) -> str:
    lines = [f"{'section':<16} {'quantity':<44} {'flexfem':>11} {'published':>11} {'diff':>8}"]
    for s in report["sections"]:
        if "error" in s:
            lines.append(f"{s['section']:<16} FAILED: {s['error']}")
        for row in s.get("comparisons", []):
            flex, pub, rel = row.get("flexfem"), row.get("published"), row.get("rel_diff")
            lines.append(f"{s['section']:<16} {str(row.get('quantity'))[:44]:<44} "
                         f"{_num(flex):>11} {_num(pub):>11} "
                         f"{'' if rel is None else f'{100 * rel:+.1f}%':>8}")
    lines.append(f"report: {report['out']}/index.html ({report['wall_time_s']:.0f} s)")
    return "\n".join(lines)


def _num(value) -> str:
    return f"{value:.4g}" if isinstance(value, (int, float)) else str(value if value is not None else "-")
