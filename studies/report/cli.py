"""``flexfem reproduce``: the main job, every comparison with the source documents."""
from collections import Counter
import sys

from ..mechanisms import report_sections


def register(subparsers):
    p = subparsers.add_parser("reproduce", help="regenerate every comparison with the source documents")
    p.add_argument("--out", default="report", help="report folder (default: ./report)")
    size = p.add_mutually_exclusive_group()
    size.add_argument("--quick", action="store_true", help="smoke run, coarse meshes (a few minutes on two cores)")
    size.add_argument("--full", action="store_true", help="the finest meshes")
    p.add_argument("--resume", action="store_true", help="keep sections already finished in --out")
    p.add_argument("--section", action="append", choices=[s.folder for _, s in report_sections()],
                   help="run only this section (repeatable)")
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    p.set_defaults(run=_run, summarize=summarize)


def _run(args) -> dict:
    from .reproduce import reproduce  # every section's studies: imported when the report runs

    progress = (lambda line: print(line, file=sys.stderr)) if sys.stderr.isatty() else None
    report = reproduce(args.out, quick=args.quick, full=args.full, resume=args.resume,
                       sections=args.section, progress=progress)
    report["out"] = str(args.out)
    return report


def summarize(report: dict) -> str:
    """The design summary in the terminal: per source document its headline comparisons with
    their verdicts, then each section's count of comparisons by verdict; failures named."""
    from .render import comparison_cells, headline_groups

    lines = []
    for _, doc, _, rows, _ in headline_groups(report):
        lines += ["", doc["title"]]
        lines += [f"  {cells[0][:52]:<52} {cells[1]:>12} {cells[2]:>12} {cells[4]:>9}  {cells[6]}"
                  for cells in map(comparison_cells, rows)]
    lines.append("")
    for s in report["sections"]:
        if "error" in s:
            lines.append(f"{s['section']:<18} FAILED: {s['error']}")
            continue
        verdicts = Counter(row.get("verdict", "not judged") for row in s.get("comparisons", []))
        counts = ", ".join(f"{n} {v}" for v, n in sorted(verdicts.items())) or "no comparisons"
        lines.append(f"{s['section']:<18} {counts} ({s['wall_time_s']:.0f} s)")
    lines.append(f"report: {report['out']}/index.html ({report['wall_time_s']:.0f} s)")
    return "\n".join(lines).lstrip("\n")
