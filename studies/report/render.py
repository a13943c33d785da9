"""The reproduction report: report.md, index.html and summary.json from the sections' summaries.

A section summary is a dict with "comparisons" (rows {quantity, flexfem, published, rel_diff,
note}), "figures" and "tables" (file names inside the section folder), optional "notes"
(list of str) and, for a failed section, "error".
"""
import csv
import html
import json
from pathlib import Path

from ..engine.serialize import jsonable

MAX_TABLE_ROWS = 40


def _fmt(value) -> str:
    if isinstance(value, float):
        return f"{value:.4g}"
    if value is None:
        return "-"
    return str(value)


def _pct(value) -> str:
    return "-" if value is None or not isinstance(value, (int, float)) else f"{100 * value:+.1f} %"


def comparison_rows(report: dict) -> list[dict]:
    """All comparison rows of all sections, each tagged with its section."""
    return [{"section": s["section"], **row}
            for s in report["sections"] for row in s.get("comparisons", [])]


def _read_csv(path: Path) -> list[list[str]]:
    with path.open(newline="") as f:
        return list(csv.reader(f))


def _is_image(name: str) -> bool:
    return Path(name).suffix.lower() in (".png", ".jpg", ".jpeg", ".svg")


def _markdown_table(header, rows) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(_fmt(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def render_markdown(report: dict) -> str:
    env = report["environment"]
    out = ["# flexfem reproduction report", "",
           f"flexfem {env['flexfem']}, Python {env['python']}, {env['cpus']} CPUs, "
           f"settings {report['settings']}, total {report['wall_time_s']:.0f} s.", "",
           "## Summary: flexfem beside the published values", "",
           _markdown_table(["section", "quantity", "flexfem", "published", "difference", "note"],
                           [[r["section"], r.get("quantity"), r.get("flexfem"), r.get("published"),
                             _pct(r.get("rel_diff")), r.get("note", "")]
                            for r in comparison_rows(report)]), ""]
    for s in report["sections"]:
        out += [f"## {s['title']}", ""]
        if "error" in s:
            out += [f"**This section failed:** `{s['error']}`", ""]
            continue
        out += [f"- {note}" for note in s.get("notes", [])] + [""]
        for name in s.get("figures", []):
            link = f"[{name}]({s['section']}/{name})"
            out += [f"!{link}" if _is_image(name) else f"Field file {link}", ""]
        for name in s.get("tables", []):
            out += [f"Table [{name}]({s['section']}/{name})", ""]
    return "\n".join(out)


def _html_table(header, rows, cls="") -> str:
    head = "".join(f"<th>{html.escape(str(h))}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(_fmt(c))}</td>" for c in row) + "</tr>"
                   for row in rows)
    return f'<table class="{cls}"><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>'


# On load the page counts its images that decoded and its tables that have rows, and writes
# both into <body data-...>: a headless browser's DOM dump then shows whether it rendered.
_CHECK_SCRIPT = """<script>
window.addEventListener('load', function () {
  var imgs = Array.from(document.images);
  document.body.dataset.imagesTotal = imgs.length;
  document.body.dataset.imagesLoaded = imgs.filter(function (i) {
    return i.complete && i.naturalWidth > 0; }).length;
  var tables = Array.from(document.querySelectorAll('table'));
  document.body.dataset.tablesTotal = tables.length;
  document.body.dataset.tablesWithRows = tables.filter(function (t) {
    return t.tBodies.length && t.tBodies[0].rows.length > 0; }).length;
});
</script>"""


def render_html(report: dict, out: Path) -> str:
    env = report["environment"]
    parts = ["<!DOCTYPE html><html><head><meta charset='utf-8'><title>flexfem reproduction report</title>",
             "<style>body{font-family:sans-serif;max-width:70em;margin:auto}table{border-collapse:collapse;"
             "margin:1em 0}td,th{border:1px solid #ccc;padding:2px 6px;font-size:90%}"
             "img{max-width:100%}.error{color:#b00}</style>", _CHECK_SCRIPT, "</head><body>",
             "<h1>flexfem reproduction report</h1>",
             f"<p>flexfem {html.escape(env['flexfem'])}, Python {env['python']}, {env['cpus']} CPUs, "
             f"settings {html.escape(json.dumps(report['settings']))}, total "
             f"{report['wall_time_s']:.0f} s.</p>",
             "<h2>Summary: flexfem beside the published values</h2>",
             _html_table(["section", "quantity", "flexfem", "published", "difference", "note"],
                         [[r["section"], r.get("quantity"), r.get("flexfem"), r.get("published"),
                           _pct(r.get("rel_diff")), r.get("note", "")]
                          for r in comparison_rows(report)], "summary")]
    for s in report["sections"]:
        parts.append(f"<h2 id='{s['section']}'>{html.escape(s['title'])}</h2>")
        if "error" in s:
            parts.append(f"<p class='error'>This section failed: <code>{html.escape(s['error'])}</code></p>")
            continue
        parts += [f"<p>{html.escape(note)}</p>" for note in s.get("notes", [])]
        for name in s.get("figures", []):
            src = f"{s['section']}/{html.escape(name)}"
            if not _is_image(name):  # e.g. a VTU field for ParaView: a link, not an <img>
                parts.append(f"<p>Field file: <a href='{src}'>{html.escape(name)}</a></p>")
                continue
            parts.append(f"<figure><img src='{src}' alt='{html.escape(name)}'>"
                         f"<figcaption>{html.escape(name)}</figcaption></figure>")
        for name in s.get("tables", []):
            path = out / s["section"] / name
            if path.suffix != ".csv" or not path.exists():
                continue
            rows = _read_csv(path)
            if rows:
                parts.append(f"<h3><a href='{s['section']}/{html.escape(name)}'>{html.escape(name)}</a></h3>")
                parts.append(_html_table(rows[0], rows[1:MAX_TABLE_ROWS + 1]))
    parts.append("</body></html>")
    return "\n".join(parts)


def write_report(out: Path, report: dict) -> None:
    """Write report.md, index.html and summary.json into ``out``."""
    report = jsonable(report)
    (out / "summary.json").write_text(json.dumps(report, indent=1))
    (out / "report.md").write_text(render_markdown(report))
    (out / "index.html").write_text(render_html(report, out))
