"""``flexfem analyze MODEL.toml --out DIR``: the numbers, the field files and the pictures of
the analysis in one folder, with a page that puts them together.

    DIR/summary.json   the --json object (written first, so the numbers are kept whatever
                       follows; written again at the end with "files")
    DIR/static.vtu     the load case's fields (:mod:`.fields`), DIR/modes.vtu the modes
    DIR/*.png          the pictures (:mod:`.pictures`, :mod:`.beam_pictures`)
    DIR/index.html     the human summary's numbers and the pictures, in the report's style

Every file is written under a temporary name in DIR and renamed into place, so an interrupted
run leaves the previous file or the new one, never half of one.
"""
import html
import json
import os
import tempfile
from pathlib import Path

from ...fem.beam.model import BeamModel
from ..engine.serialize import jsonable
from ..out_folder import prepare_out
from ..report.figures import DPI, pyplot
from ..report.render import CHECK_SCRIPT, STYLE
from . import beam_pictures, fields, pictures


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


_UMASK = _umask()


def _atomic(out: Path, name: str, write) -> Path:
    """Call ``write(temporary path)``, then rename the file to ``out / name`` (with the
    permissions a new file gets)."""
    fd, tmp = tempfile.mkstemp(dir=out, prefix=f".{name}.", suffix=".part")
    os.close(fd)
    try:
        write(Path(tmp))
        os.chmod(tmp, 0o666 & ~_UMASK)
        os.replace(tmp, out / name)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return out / name


def _text(out: Path, name: str, text: str) -> Path:
    return _atomic(out, name, lambda p: p.write_text(text, encoding="utf-8"))


def _figure(out: Path, name: str, drawn) -> dict:
    fig, caption = drawn
    try:
        _atomic(out, name, lambda p: fig.savefig(p, format="png", dpi=DPI, bbox_inches="tight"))
    finally:
        pyplot().close(fig)
    return {"file": name, "caption": caption}


def _field_files(out: Path, model, kept: dict) -> list[dict]:
    """The VTU files of the load case and the modes: [{"file", "caption"}]."""
    written = []
    static = fields.static_mesh(model, kept.get("static"))
    what = ("displacement (m), rotation (rad) and the beam stress |N|/A + |M| c/I (Pa, per "
            "beam element) on the beam lines" if isinstance(model, BeamModel) else
            "displacement (m), von_mises (Pa, nodal), stress (Pa, the 9 components of the "
            "Cauchy tensor) and von_mises_element_max (Pa), with the groups as cell data")
    if static is not None:
        _atomic(out, "static.vtu", lambda p: fields.write_vtu(static, p))
        written.append({"file": "static.vtu", "caption": f"The load case: {what}."})
    modes = fields.modes_mesh(model, kept["modes"]) if "modes" in kept else None
    if modes is not None:
        _atomic(out, "modes.vtu", lambda p: fields.write_vtu(modes, p))
        written.append({"file": "modes.vtu", "caption": "The mode shapes, one point field "
                        "each named by its frequency (mass-normalised, m/sqrt(kg))."})
    model_s, path = kept.get("stroke_path", (None, None))
    end = fields.path_end_mesh(model_s, path) if path is not None else None
    if end is not None:
        _atomic(out, "stroke_path.vtu", lambda p: fields.write_vtu(end, p))
        kind = "beam model" if isinstance(model_s, BeamModel) else "continuum"
        written.append({"file": "stroke_path.vtu", "caption": "The stroke check's "
                        f"large-deflection path at its end (the {kind}): the same fields "
                        "as static.vtu (the continuum: the Cauchy and second Piola-Kirchhoff "
                        "stresses on the reference mesh)."})
    return written


def _n_modes(modes) -> int:
    return min(pictures.MAX_MODE_PICTURES, len(modes.frequencies_hz)) if modes is not None else 0


def _figures(out: Path, spec, model, kept: dict) -> list[dict]:
    """The pictures of the model that was solved: [{"file", "caption"}]."""
    name, static, modes = Path(spec.source).name, kept.get("static"), kept.get("modes")
    if not isinstance(model, BeamModel):
        figs = [_figure(out, "mechanism.png", pictures.mechanism_figure(model, name)),
                _figure(out, "deformed.png", pictures.deformed_figure(model, static, name))]
        return figs + [_figure(out, f"mode_{k + 1}.png",
                               pictures.continuum_mode_figure(model, modes, k, name))
                       for k in range(_n_modes(modes))]
    loops = (beam_pictures.outline_polygons(spec.mechanism) if spec.mechanism is not None
             else [])
    figs = [_figure(out, "beam_model.png", beam_pictures.beam_mechanism_figure(model, loops,
                                                                               name))]
    if fields.static_mesh(model, static) is not None:
        figs.append(_figure(out, "deformed.png",
                            beam_pictures.beam_deformed_figure(model, static, loops, name)))
    if not hasattr(modes, "shapes"):
        modes = None
    return figs + [_figure(out, f"mode_{k + 1}.png",
                           beam_pictures.beam_mode_figure(model, modes, k, loops, name))
                   for k in range(_n_modes(modes))]


def write_outputs(path, spec, result: dict, kept: dict, summary: str) -> list[str]:
    """Write summary.json, the field files, the pictures and index.html into the folder
    ``path`` (see the module's docstring); returns the files written, as paths under it."""
    out = prepare_out(path)
    names = ["summary.json"]
    _text(out, "summary.json", json.dumps(jsonable(result), indent=1))
    model = kept["model"]
    vtus = _field_files(out, model, kept)
    figs = _figures(out, spec, model, kept)
    names += [v["file"] for v in vtus] + [f["file"] for f in figs] + ["index.html"]
    files = [str(out / n) for n in names]
    kind = "beam model" if isinstance(model, BeamModel) else "continuum"
    _text(out, "index.html", render_page(result, summary, figs, vtus, kind,
                                         not_drawn(result, model, kept)))
    _text(out, "summary.json", json.dumps(jsonable({**result, "files": files}), indent=1))
    return files


def not_drawn(result: dict, model, kept: dict) -> list[str]:
    """One line for each solve of the analysis that has no picture or field file: a load
    case this module cannot draw (the spatial beam model's) and the stroke check's
    large-deflection path (its numbers are in summary.json)."""
    notes = []
    if kept.get("static") is not None and fields.static_mesh(model, kept["static"]) is None:
        notes.append("The load case of this model is not drawn (no field file or picture: "
                     "its numbers are in summary.json).")
    modes = kept.get("modes")
    if result.get("frequencies_hz") and (modes is None or fields.modes_mesh(model, modes) is None):
        notes.append("The mode shapes of this model are not drawn (the spatial beam model "
                     "keeps only its frequencies, in summary.json).")
    check = result.get("stroke_check")
    if check and check.get("strokes") and "stroke_path" not in kept:
        notes.append(f"The stroke check's large-deflection path (the {check['model']} model, "
                     f"to {check['strokes'][-1] * 1e3:.4g} mm) is not drawn: its strokes, "
                     "forces and peak stresses per step are in summary.json, stroke_check.")
    return notes


def _rows(summary: str) -> tuple[str, list[tuple[str, str]]]:
    """(the run line, [(quantity, value)]) of the human summary: each line split at its
    first ': ' (a line without one is a quantity alone; an indented line adds to the row
    above)."""
    lines = summary.splitlines()
    rows = []
    for line in lines[1:]:
        if line.startswith(" ") and rows:
            rows[-1] = (rows[-1][0], f"{rows[-1][1]}; {line.strip()}".lstrip("; "))
            continue
        quantity, sep, value = line.partition(": ")
        rows.append((quantity, value) if sep else (line, ""))
    return (lines[0] if lines else ""), rows


def render_page(result: dict, summary: str, figs: list[dict], vtus: list[dict],
                kind: str = "continuum", notes=()) -> str:
    """index.html: the human summary's numbers as a table, the pictures with their captions,
    links to the field files and to summary.json (relative links: the folder can be moved),
    and ``notes``: what the analysis solved but the page does not draw."""
    run, rows = _rows(summary)
    title = f"flexfem analyze {Path(result['model']).name}: {kind}, {result.get('dim', 2)}-D"
    body = "".join(f"<tr><td>{html.escape(q)}</td><td>{html.escape(v)}</td></tr>"
                   for q, v in rows)
    parts = ["<!DOCTYPE html><html><head><meta charset='utf-8'>",
             f"<title>{html.escape(title)}</title>", f"<style>{STYLE}</style>", CHECK_SCRIPT,
             "</head><body>", f"<h1>{html.escape(title)}</h1>",
             f"<p class='run'>{html.escape(run)}</p>", "<h2 id='numbers'>Numbers</h2>",
             "<div class='table'><table class='numbers'><thead><tr><th>quantity</th>"
             f"<th>value</th></tr></thead><tbody>{body}</tbody></table></div>",
             "<p class='tables'>Every number, in SI units: <a href='summary.json'>summary.json"
             "</a> (the same object as <code>flexfem analyze --json</code>).</p>",
             "<h2 id='pictures'>Pictures</h2>"]
    for fig in figs:
        src, caption = html.escape(fig["file"]), html.escape(fig["caption"])
        parts.append(f"<figure><img src='{src}' alt='{caption}'><figcaption>{caption}"
                     "</figcaption></figure>")
    if vtus:
        parts.append("<h2 id='fields'>Field files</h2><p>Open them in ParaView (File, Open; "
                     "Warp By Vector on <code>displacement</code> or a mode shows the "
                     "deformation).</p><ul>")
        parts += [f"<li><a href='{html.escape(v['file'])}'>{html.escape(v['file'])}</a>: "
                  f"{html.escape(v['caption'])}</li>" for v in vtus]
        parts.append("</ul>")
    parts += [f"<p class='not-drawn'>{html.escape(n)}</p>" for n in notes]
    parts.append("</body></html>")
    return "\n".join(parts)

