"""The reproduction report: report.md, index.html and summary.json from the sections' summaries.

The report answers first and justifies second: one table of the sources at a glance (what
was rebuilt, how many headline results agree, the difference furthest out of its tolerance
and its reason), a design summary of one screen per source document (:mod:`.summary`: one sentence, the headline comparisons with their verdicts and
reasons, the stroke limits, one figure), then the audit (every section: what was done and how
the models were built, its figures with captions, its comparisons and links to its full
tables).

A section summary is a dict with "comparisons" (rows of :class:`~.comparison.Comparison`),
"figures" ({"file", "caption"} entries), "tables" (CSV files inside the
section folder: linked, not printed), optional "paragraph" (what was done and what it means),
"key_tables" ({"title", "columns", "rows"}: small tables printed rounded), "notes" (list of
str), "lead" (the design summary's clause on what the document's results are),
"summary_figure" (the file of the one figure the design summary shows), "stroke_limits"
(:func:`.stroke.stroke_limits` entries) and, for a failed section, "error".
"""
import html
import json
from pathlib import Path

from ...data import load_toml
from ..engine.serialize import jsonable
from .format import difference_text, is_image, number, tolerance_text
from .summary import GLANCE_COLUMNS, glance_rows, html_block, markdown_block

VERDICT_CLASSES = {"agrees": "agrees", "within limit": "agrees", "differs": "differs",
                   "beyond limit": "differs", "calibrated": "calibrated"}
HEADLINE_COLUMNS = ["quantity", "flexfem", "reference", "source", "difference", "tolerance",
                    "verdict"]


def documents() -> dict:
    """{key: citation fields} of the source documents (data/sources.toml)."""
    return load_toml("sources.toml")


def citation(doc: dict) -> str:
    """'Authors, *Title*, venue, DOI ...' of a source document."""
    where = (f"doi:{doc['doi']}" if "doi" in doc else doc.get("hal") or doc.get("url", ""))
    return f"{doc['authors']}, *{doc['title']}*, {doc['venue']}, {where}"


def comparison_cells(row: dict) -> list[str]:
    """The headline columns of one comparison row, formatted."""
    unit = row.get("unit", "")
    return [row.get("quantity", ""), number(row.get("flexfem"), unit),
            number(row.get("reference"), unit), row.get("source", ""),
            difference_text(row), tolerance_text(row), row.get("verdict", "not judged")]


def headline_groups(report: dict) -> list[tuple[str, dict, list, list, list]]:
    """[(key, document, paragraphs, headline rows, calibrated rows)] per source document, in
    report order; sections without a document (the engine's own checks) are left out."""
    docs, groups = documents(), {}
    for s in report["sections"]:
        key = s.get("document")
        if not key or key not in docs:
            continue
        _, _, paragraphs, rows, calibrated = groups.setdefault(key, (key, docs[key], [], [], []))
        if s.get("paragraph"):
            paragraphs.append(s["paragraph"])
        for row in s.get("comparisons", []):
            if row.get("kind") == "calibrated":
                calibrated.append(row)
            elif row.get("headline") and row.get("kind") != "input":
                rows.append(row)
    return list(groups.values())


def _md_table(header, rows) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c).replace("|", "\\|") for c in row) + " |" for row in rows]
    return "\n".join(lines)


def _md_section(s: dict) -> list[str]:
    out = [f"### {s['title']}", ""]
    if "error" in s:
        return out + [f"**This section failed:** `{s['error']}`", ""]
    if s.get("paragraph"):
        out += [s["paragraph"], ""]
    out += [f"- {note}" for note in s.get("notes", [])] + [""]
    for fig in s.get("figures", []):
        link = f"{s['section']}/{fig['file']}"
        out += ([f"![{fig['caption']}]({link})", "", f"*{fig['caption']}*", ""] if is_image(fig["file"])
                else [f"Field file [{fig['file']}]({link}): {fig['caption']}", ""])
    if s.get("comparisons"):
        out += [_md_table(HEADLINE_COLUMNS, [comparison_cells(r) for r in s["comparisons"]]), ""]
    for table in s.get("key_tables", []):
        out += [f"**{table['title']}**", "",
                _md_table(table["columns"], [[number(c) for c in r] for r in table["rows"]]), ""]
    if s.get("tables"):
        out += ["Full tables: " + ", ".join(f"[{n}]({s['section']}/{n})" for n in s["tables"]), ""]
    return out


def run_line(report: dict) -> str:
    """flexfem and Python versions, CPUs, the run's size and its time, in one line."""
    env, settings = report["environment"], report["settings"]
    size = "quick" if settings.get("quick") else "full" if settings.get("full") else "default"
    return (f"flexfem {env['flexfem']}, Python {env['python']}, {env['cpus']} CPUs; {size} "
            f"run, {report['wall_time_s']:.0f} s.")


def render_markdown(report: dict) -> str:
    groups = headline_groups(report)
    out = ["# flexfem reproduction report", "", run_line(report), "", "## At a glance", "",
           _md_table(GLANCE_COLUMNS, glance_rows(groups, report)), "", "## Design summary", ""]
    for key, doc, _, rows, _ in groups:
        out += markdown_block(doc, citation(doc), report, key, rows, _md_table)
    out += ["## Audit", "", "How each result was obtained, section by section: the models, "
            "their figures, every comparison (calibrations shown apart) and the full tables.",
            ""]
    for s in report["sections"]:
        out += _md_section(s)
    return "\n".join(out)


def _html_table(header, rows, cls="") -> str:
    head = "".join(f"<th>{html.escape(str(h))}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in row) + "</tr>"
                   for row in rows)
    return (f'<div class="table"><table class="{cls}"><thead><tr>{head}</tr></thead>'
            f"<tbody>{body}</tbody></table></div>")


def _verdict_table(rows, cls="comparisons") -> str:
    cells = [comparison_cells(r) for r in rows]
    table = _html_table(HEADLINE_COLUMNS, cells, cls)
    for verdict, cls in VERDICT_CLASSES.items():
        table = table.replace(f"<td>{verdict}</td>", f"<td class='{cls}'>{verdict}</td>")
    return table


def _html_section(s: dict) -> list[str]:
    parts = [f"<h3 id='{s['section']}'>{html.escape(s['title'])}</h3>"]
    if "error" in s:
        return parts + [f"<p class='error'>This section failed: <code>{html.escape(s['error'])}</code></p>"]
    if s.get("paragraph"):
        parts.append(f"<p>{html.escape(s['paragraph'])}</p>")
    if s.get("notes"):
        parts.append("<ul>" + "".join(f"<li>{html.escape(n)}</li>" for n in s["notes"]) + "</ul>")
    for fig in s.get("figures", []):
        src, caption = f"{s['section']}/{html.escape(fig['file'])}", html.escape(fig["caption"])
        if is_image(fig["file"]):
            wide = " class='wide'" if fig.get("wide") else ""
            parts.append(f"<figure{wide}><img src='{src}' alt='{caption}'><figcaption>"
                         f"{caption}</figcaption></figure>")
        else:  # e.g. a VTU field for ParaView: a link, not an <img>
            parts.append(f"<p>Field file: <a href='{src}'>{html.escape(fig['file'])}</a>: {caption}</p>")
    if s.get("comparisons"):
        parts.append(_verdict_table(s["comparisons"]))
    for table in s.get("key_tables", []):
        parts.append(f"<h4>{html.escape(table['title'])}</h4>")
        parts.append(_html_table(table["columns"], [[number(c) for c in r] for r in table["rows"]]))
    if s.get("tables"):
        links = ", ".join(f"<a href='{s['section']}/{html.escape(n)}'>{html.escape(n)}</a>"
                          for n in s["tables"])
        parts.append(f"<p class='tables'>Full tables: {links}</p>")
    return parts


def _contents(groups, sections) -> str:
    """One line of links: the documents' screens, then the audit's sections."""
    docs = " · ".join(f"<a href='#doc-{key}'>{html.escape(doc['title'][:48])}...</a>"
                      for key, doc, *_ in groups)
    audit = " · ".join(f"<a href='#{s['section']}'>{html.escape(s['section'])}</a>"
                       for s in sections)
    return f"<nav><b>Summary:</b> {docs}<br><b>Audit:</b> {audit}</nav>"


def render_html(report: dict) -> str:
    groups = headline_groups(report)
    parts = ["<!DOCTYPE html><html><head><meta charset='utf-8'>",
             "<title>flexfem reproduction report</title>", f"<style>{STYLE}</style>",
             CHECK_SCRIPT, "</head><body>", "<h1>flexfem reproduction report</h1>",
             f"<p class='run'>{html.escape(run_line(report))}</p>",
             "<h2 id='glance'>At a glance</h2>",
             _html_table(GLANCE_COLUMNS, glance_rows(groups, report), "glance"),
             "<h2 id='summary'>Design summary</h2>"]
    for key, doc, _, rows, _ in groups:
        parts += html_block(key, doc, citation(doc).replace("*", ""), report, rows)
    parts += ["<h2 id='audit'>Audit</h2>", _contents(groups, report["sections"]),
              "<p class='run'>How each result was obtained, section by section: the models, "
              "their figures, every comparison (calibrations shown apart) and the full "
              "tables.</p>"]
    for s in report["sections"]:
        parts += _html_section(s)
    parts.append("</body></html>")
    return "\n".join(parts)


def write_report(out: Path, report: dict) -> None:
    """Write report.md, index.html and summary.json into ``out``."""
    report = jsonable(report)
    (out / "summary.json").write_text(json.dumps(report, indent=1))
    (out / "report.md").write_text(render_markdown(report))
    (out / "index.html").write_text(render_html(report))


STYLE = """
body{font-family:sans-serif;max-width:62em;margin:auto;padding:0 1em;line-height:1.35}
h1{font-size:1.6em;margin:.4em 0 .1em}h2{margin:.8em 0 .3em}h3{margin:.8em 0 .2em}
.table{max-width:100%;overflow-x:auto}
table{border-collapse:collapse;margin:.6em 0;width:100%}
td,th{border:1px solid #ccc;padding:2px 5px;font-size:85%;vertical-align:top;
      overflow-wrap:break-word}
td:first-child{width:34%}
table.headline td:first-child{width:22%}table.headline td:last-child{width:34%}
th{background:#f2f2f2;text-align:left}
td.agrees{color:#060}td.differs{color:#a00;font-weight:bold}td.calibrated{color:#555}
figure{margin:.8em 0}figure img{max-width:100%;max-height:28em}
figure.summary{margin:.3em 0}figure.summary img{max-height:15em}
figcaption{font-size:85%;color:#333}
.error{color:#b00}.citation{font-style:italic;font-size:85%;margin:.1em 0}
.lead{font-weight:bold;margin:.3em 0}.stroke{margin:.2em 0;font-size:92%}
.run,.tables{font-size:85%;color:#444}nav{font-size:85%;line-height:1.5}
section.doc{border-bottom:1px solid #ddd;padding-bottom:.4em}
@media print{@page{size:A4;margin:1cm}
  body{max-width:none;font-size:8pt;line-height:1.25}td,th{font-size:6.2pt;padding:0 2px}
  h1{font-size:14pt}h2{font-size:12pt}h3{font-size:9.5pt;margin:.5em 0 .15em}
  h4{font-size:8pt;margin:.3em 0}p,ul{margin:.25em 0}nav{display:none}
  figure{display:inline-block;width:49%;margin:.2em 0;vertical-align:top;
    page-break-inside:avoid}
  figure img{max-height:5cm}figcaption{font-size:6.5pt}
  figure.summary{display:block;width:auto}figure.summary img{max-height:5.5cm}
  figure.wide{display:block;width:auto}figure.wide img{max-height:10cm}
  table{margin:.3em 0}td,th{line-height:1.15}h2,h3{page-break-after:avoid}}
"""

# On load the page counts its images that decoded, its tables that have rows and the tables
# wider than the page, and writes them into <body data-...>: a headless browser's DOM dump
# then shows whether it rendered and whether anything runs off the page.
CHECK_SCRIPT = """<script>
window.addEventListener('load', function () {
  var imgs = Array.from(document.images);
  document.body.dataset.imagesTotal = imgs.length;
  document.body.dataset.imagesLoaded = imgs.filter(function (i) {
    return i.complete && i.naturalWidth > 0; }).length;
  var tables = Array.from(document.querySelectorAll('table'));
  document.body.dataset.tablesTotal = tables.length;
  document.body.dataset.tablesWithRows = tables.filter(function (t) {
    return t.tBodies.length && t.tBodies[0].rows.length > 0; }).length;
  var width = document.body.clientWidth;
  document.body.dataset.tablesOverflowing = tables.filter(function (t) {
    return t.getBoundingClientRect().width > width + 1; }).length;
});
</script>"""
