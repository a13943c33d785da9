"""The design summary: one screen per source document.

Per document: one sentence saying what was reproduced and how well (the ``lead`` of its first
section that gives one, and the count of its headline verdicts), the headline table (at most
MAX_ROWS rows; every row carries its note, so that a "differs" or "beyond limit" gives its
reason in the row), the stroke limits of its mechanism (a section's ``stroke_limits``) and at
most one figure (the first section's ``summary_figure``, a file of its own figures). How the
models were built stays in the audit.
"""
import html
import math

from .format import difference_text, is_image, number, tolerance_text
from .stroke import stroke_sentence

MAX_ROWS = 6
SUMMARY_COLUMNS = ["quantity", "flexfem", "reference (where)", "difference or margin",
                   "verdict", "why / note"]
GOOD = ("agrees", "within limit")
BAD = ("differs", "beyond limit")


def summary_cells(row: dict) -> list[str]:
    """The design summary's columns of one headline row."""
    unit = row.get("unit", "")
    verdict = row.get("verdict", "not judged")
    tolerance = tolerance_text(row)
    if verdict in ("agrees", "differs") and tolerance != "-":
        verdict = f"{verdict} ({tolerance})"
    note = row.get("note", "") or ("(no reason given)" if row.get("verdict") in BAD else "-")
    return [row.get("quantity", ""), number(row.get("flexfem"), unit),
            f"{number(row.get('reference'), unit)} ({row.get('source', '')})",
            difference_text(row), verdict, note]


GLANCE_COLUMNS = ["source", "what was rebuilt", "headline results", "largest difference",
                  "its reason"]


def _short_source(doc: dict) -> str:
    """'G. Liu et al., Micromachines 11(3), 312, 2020'."""
    authors = doc.get("authors", "").split(", ")
    who = authors[0] + (" et al." if len(authors) > 1 else "")
    return f"{doc['title']} ({who}, {doc.get('venue', '')})"


def glance_rows(groups, report: dict) -> list[list[str]]:
    """One row per source document, before the per-document screens: what was rebuilt (its
    ``lead``), how many headline results agree or meet their limit, and the difference
    furthest out of its own tolerance (a differing or beyond-limit row first) with its note."""
    out = []
    for key, doc, _, rows, _ in groups:
        sections = doc_sections(report, key)
        lead = next((s["lead"] for s in sections if s.get("lead")), "-")
        judged = [r for r in rows if r.get("verdict") in GOOD + BAD]
        good = sum(r.get("verdict") in GOOD for r in judged)
        valued = [r for r in judged if isinstance(r.get("difference"), (int, float))
                  and math.isfinite(r["difference"]) and (r.get("tolerance") or r.get("limit"))]
        # a differing (or beyond-limit) row first, then the furthest out of its tolerance (a
        # limit row: its relative distance from the limit)
        worst = max(valued, key=lambda r: (r["verdict"] in BAD, abs(r["difference"]) / (
            1.0 if r.get("limit") else r["tolerance"])), default=None)
        largest = f"{worst['quantity']}: {difference_text(worst)}" if worst else "-"
        reason = (worst.get("note") or "-") if worst else "-"
        out.append([_short_source(doc), lead, f"{good} of {len(judged)} agree or meet their "
                    "limit", largest, reason])
    return out


def doc_sections(report: dict, key: str) -> list[dict]:
    """The sections of the report that reproduce document ``key``, in report order."""
    return [s for s in report["sections"] if s.get("document") == key and "error" not in s]


def sentence(sections: list, rows: list) -> str:
    """What was reproduced (the first section's ``lead``) and how well (the verdicts)."""
    lead = next((s["lead"] for s in sections if s.get("lead")), "flexfem's results")
    good = sum(r.get("verdict") in GOOD for r in rows)
    bad = sum(r.get("verdict") in BAD for r in rows)
    how = f"{good} of {len(rows)} headline results agree with the source or meet its limit"
    if bad:
        how += f"; {bad} differ{'s' if bad == 1 else ''}, each with its reason in its row"
    return f"{lead}: {how}."


def stroke_lines(sections: list) -> list[str]:
    """One line of the strokes the document's sections size (their ``stroke_limits``)."""
    limits = [limit for s in sections for limit in s.get("stroke_limits", [])]
    return [stroke_sentence(limits)] if limits else []


def summary_figure(sections: list):
    """(section folder, figure entry) of the first ``summary_figure`` named, or None."""
    for s in sections:
        name = s.get("summary_figure")
        for fig in s.get("figures", []):
            if name and fig["file"] == name and is_image(fig["file"]):
                return s["section"], fig
    return None


def html_block(key: str, doc: dict, citation: str, report: dict, rows: list) -> list[str]:
    """The HTML of one document's screen."""
    sections = doc_sections(report, key)
    head = "".join(f"<th>{html.escape(h)}</th>" for h in SUMMARY_COLUMNS)
    body = ""
    for row in rows:
        cells = summary_cells(row)
        verdict = row.get("verdict", "")
        cls = "differs" if verdict in BAD else "agrees" if verdict in GOOD else ""
        body += "<tr>" + "".join(
            f"<td class='{cls}'>{html.escape(c)}</td>" if i == 4 else f"<td>{html.escape(c)}</td>"
            for i, c in enumerate(cells)) + "</tr>"
    parts = [f"<section class='doc'><h3 id='doc-{key}'>{html.escape(doc['title'])}</h3>",
             f"<p class='citation'>{html.escape(citation.replace(doc['title'] + ', ', ''))}</p>",
             f"<p class='lead'>{html.escape(sentence(sections, rows))}</p>",
             f"<div class='table'><table class='headline'><thead><tr>{head}</tr></thead>"
             f"<tbody>{body}</tbody></table></div>"]
    parts += [f"<p class='stroke'>{html.escape(line)}</p>" for line in stroke_lines(sections)]
    figure = summary_figure(sections)
    if figure:
        folder, fig = figure
        caption = html.escape(fig["caption"])
        parts.append(f"<figure class='summary'><img src='{folder}/{html.escape(fig['file'])}' "
                     f"alt='{caption}'><figcaption>{caption}</figcaption></figure>")
    return parts + ["</section>"]


def markdown_block(doc: dict, citation: str, report: dict, key: str, rows: list,
                   table) -> list[str]:
    """The Markdown of one document's screen (``table``: the Markdown table writer)."""
    sections = doc_sections(report, key)
    out = [f"### {doc['title']}", "", citation, "", sentence(sections, rows), "",
           table(SUMMARY_COLUMNS, [summary_cells(r) for r in rows]), ""]
    out += [line + "\n" for line in stroke_lines(sections)]
    figure = summary_figure(sections)
    if figure:
        folder, fig = figure
        out += [f"![{fig['caption']}]({folder}/{fig['file']})", "", f"*{fig['caption']}*", ""]
    return out
