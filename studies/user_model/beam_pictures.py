"""The beam model's pictures of ``flexfem analyze --model beam --out DIR``: its beam lines
over the mechanism's outline (a model of bodies and flexures; a drawing's beam model is shown
without one), deformed and coloured by the beam stress |N|/A + |M| c/I (MPa), and its modes.
Lengths in mm; each function returns (figure, caption). See :mod:`.pictures`.
"""
import math

import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.patches import Polygon

from .fields import beam_cells
from .pictures import DEFORMED_SHARE, axes, colours, nice_scale, scale_text

_LINE_STYLE = {"beam": ("#1f4e9c", 1.6), "condensed pair": ("#d97706", 2.2),
               "rigid link": ("#444444", 0.5)}
#: where the groups' labels sit from their nodes (points): groups at one place stay legible
_OFFSETS = [(0, 16), (-30, -16), (30, -16), (0, -24), (-40, 10), (40, 10)]


def _arc(a, b, bulge: float, depth: int = 3) -> list:
    """Points after ``a`` up to ``b`` along the arc of ``bulge`` (tan of a quarter of its
    angle; 0 a straight edge), halved ``depth`` times."""
    if bulge == 0 or depth == 0:
        return [tuple(b)]
    from ...geometry.outline_files import arc_midpoint

    m = arc_midpoint(a, b, bulge)
    half = math.tan(math.atan(bulge) / 2)
    return _arc(a, m, half, depth - 1) + _arc(m, b, half, depth - 1)


def outline_polygons(mechanism) -> list[np.ndarray]:
    """[(n, 2)] (m): the mechanism's boundary loops (the outer first), arcs as chords."""
    from ...geometry.mechanism.export import outline_loops

    out = []
    for loop in outline_loops(mechanism):
        points = [tuple(loop[0][:2])]
        for (x, y, bulge), nxt in zip(loop, loop[1:] + loop[:1]):
            points += _arc((x, y), nxt[:2], bulge)
        out.append(np.array(points))
    return out


def _draw_outline(ax, loops, alpha: float = 1.0) -> None:
    for i, loop in enumerate(loops):
        ax.add_patch(Polygon(loop * 1e3, closed=True, fc="#e4e4e4" if i == 0 else "white",
                             ec="#9a9a9a", lw=0.6, alpha=alpha, zorder=0))


def _segments(model, q=None, scale: float = 0.0) -> list[tuple[str, np.ndarray]]:
    """[(kind, (n, 2, 2) segments in mm)] of the beam lines, moved by scale * q."""
    xy = model.nodes + (scale * np.asarray(q)[:, :2] if q is not None else 0.0)
    return [(kind, xy[cells] * 1e3) for kind, cells in beam_cells(model)]


def _outline_note(loops) -> str:
    return (" over the mechanism's outline" if loops else
            " (no outline: the model file's geometry is a drawing)")


def beam_mechanism_figure(model, loops, source: str):
    """The beam lines over the outline, the groups' nodes labelled."""
    fig, ax = axes(f"{source}: the beam model{_outline_note(loops)}")
    _draw_outline(ax, loops)
    for kind, seg in _segments(model):
        colour, width = _LINE_STYLE[kind]
        ax.add_collection(LineCollection(seg, colors=colour, linewidths=width, label=kind))
    names = sorted(model.groups)
    for i, (name, colour) in enumerate(zip(names, colours(len(names)))):
        p = model.nodes[list(model.groups[name].nodes)] * 1e3
        ax.plot(p[:, 0], p[:, 1], "o", color=colour, markersize=6, markeredgecolor="black")
        ax.annotate(name, p.mean(axis=0), xytext=_OFFSETS[i % len(_OFFSETS)],
                    textcoords="offset points", fontsize=8, ha="center", va="center",
                    bbox=dict(boxstyle="round,pad=0.2", fc="white", ec=colour, alpha=0.9),
                    arrowprops=dict(arrowstyle="-", color=colour, lw=0.8))
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize="small")
    ax.autoscale_view()
    caption = ("The beam model: its beams (blue), the notches' condensed pairs (orange) and "
               f"the rigid bodies' links (grey){_outline_note(loops)}; each group is its "
               "node(s), labelled; lengths in mm.")
    return fig, caption


def _extent(model) -> float:
    """The beam model's size in mm (its nodes' bounding box diagonal)."""
    return float(np.linalg.norm(np.ptp(model.nodes, axis=0))) * 1e3 or 1.0


def _moved_lines(ax, model, q, scale, values, label, loops, cmap):
    """The outline (faint), the undeformed lines (dashed) and the moved ones, the beams
    coloured by ``values`` (one per beam element)."""
    _draw_outline(ax, loops, alpha=0.5)
    for kind, seg in _segments(model):
        ax.add_collection(LineCollection(seg, colors="#999999", linewidths=0.6,
                                         linestyles="--"))
    art = None
    for kind, seg in _segments(model, q, scale):
        colour, width = _LINE_STYLE[kind]
        if kind == "beam":
            art = LineCollection(seg, array=np.asarray(values), cmap=cmap, linewidths=2.4)
            ax.add_collection(art)
        else:
            ax.add_collection(LineCollection(seg, colors=colour, linewidths=width))
    if art is not None:
        ax.figure.colorbar(art, ax=ax, label=label, shrink=0.85)
    ax.autoscale_view()


def beam_deformed_figure(model, static, loops, source: str):
    """The deformed beam lines coloured by the beam stress (MPa), the peak marked."""
    q = static.state.q
    scale = nice_scale(float(np.linalg.norm(q[:, :2], axis=1).max()), _extent(model) / 1e3)
    stress = np.nan_to_num(np.asarray(static.state.stress, dtype=float)) / 1e6
    fig, ax = axes(f"{source}: beam model deformed, {scale_text(scale)}")
    _moved_lines(ax, model, q, scale, stress, "beam stress |N|/A + |M|c/I (MPa)", loops, "jet")
    e, xi, _ = static.state.max_stress_location
    a, b = model.elements[int(e)]
    at = ((1 - xi) * (model.nodes[a] + scale * q[a, :2]) + xi * (model.nodes[b] + scale * q[b, :2]))
    peak = float(static.max_von_mises) / 1e6
    ax.plot(*(at * 1e3), marker="*", markersize=14, color="white", markeredgecolor="black")
    ax.annotate(f"peak {peak:.4g} MPa", at * 1e3, xytext=(8, 8), textcoords="offset points",
                fontsize=8, bbox=dict(boxstyle="round,pad=0.2", fc="white", alpha=0.85))
    caption = (f"The beam model deformed under the model file's loads ({scale_text(scale)}; "
               "undeformed dashed), its beams coloured by the beam stress |N|/A + |M| c/I "
               f"(no stress concentration at the roots); the star marks its peak, {peak:.4g} "
               "MPa.")
    return fig, caption


def beam_mode_figure(model, modes, k: int, loops, source: str):
    """Mode ``k`` (0-based) of the beam model, its beams coloured by relative amplitude."""
    shape = np.asarray(modes.shapes[k])[:, :2]
    amplitude = np.linalg.norm(shape, axis=1)
    top = amplitude.max() or 1.0
    scale = DEFORMED_SHARE * _extent(model) / 1e3 / top
    per_element = amplitude[model.elements].mean(axis=1) / top
    f = float(modes.frequencies_hz[k])
    fig, ax = axes(f"{source}: beam model, mode {k + 1}, {f:.4g} Hz")
    _moved_lines(ax, model, shape, scale, per_element, "relative amplitude", loops, "viridis")
    caption = (f"The beam model's mode {k + 1} at {f:.4g} Hz, its largest displacement drawn "
               "a tenth of the mechanism's size (undeformed dashed), the beams coloured by "
               "their displacement's magnitude over its largest.")
    return fig, caption
