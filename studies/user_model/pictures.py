"""The pictures of ``flexfem analyze --out DIR`` (matplotlib, Agg), of the model that was solved.

The continuum: the mechanism with its groups labelled, the deformed shape coloured by the
nodal von Mises stress (MPa) with the peak marked, and the first modes coloured by their
relative amplitude. A 2-D model is drawn as it is; a 3-D one is projected onto the x-y plane
as seen from +z (its boundary faces that face along z, the upper ones drawn over the lower;
its groups' faces as their projected edges). The beam model: its beam lines over the
mechanism's outline (for a model of bodies and flexures), deformed and coloured by the beam
stress |N|/A + |M| c/I (MPa), and its modes. Every deformed shape is scaled so that its
largest displacement is a tenth of the mechanism's size, and the title says by how much.

Each function draws one figure and returns (figure, caption); the caller saves it.
"""
import math

import numpy as np
import skfem
from matplotlib.collections import LineCollection
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from ...fem.abaqus import oriented_corners
from ...fem.export import facet_cells
from ..report.figures import pyplot

#: the most modes drawn, one picture each
MAX_MODE_PICTURES = 4
#: a deformed shape's largest displacement, as a share of the mechanism's size
DEFORMED_SHARE = 0.1


def nice_scale(max_u: float, size: float) -> float:
    """A round factor (1, 2 or 5 x 10^k) near DEFORMED_SHARE * size / max_u; 0 for no
    displacement."""
    if not max_u > 0:
        return 0.0
    raw = DEFORMED_SHARE * size / max_u
    exponent = math.floor(math.log10(raw))
    mantissa = raw / 10**exponent
    step = 5 if mantissa >= 5 else 2 if mantissa >= 2 else 1
    return float(step * 10**exponent)


def scale_text(scale: float) -> str:
    """'displacement x 250' (the factor the picture multiplies the displacement by)."""
    if scale == 0:
        return "no displacement"
    return f"displacement x {scale:.4g}" if scale < 1e5 else f"displacement x {scale:.1e}"


def _triangles(cells: np.ndarray) -> np.ndarray:
    """(m, 3) triangles of triangles or quadrilaterals (each split in two)."""
    if cells.shape[1] == 3:
        return cells
    return np.vstack([cells[:, [0, 1, 2]], cells[:, [0, 2, 3]]])


def continuum_view(model) -> tuple[np.ndarray, np.ndarray]:
    """(xy (n, 2) of every vertex, triangles (m, 3) to draw, back to front)."""
    mesh = model.mesh.mesh
    xy = mesh.p[:2].T
    if model.dim == 2:
        cells = mesh.t.T
        if isinstance(mesh, skfem.MeshQuad):
            cells = oriented_corners(mesh)
        return xy, _triangles(cells)
    facets = mesh.facets[:, mesh.boundary_facets()].T
    if facets.shape[1] == 4:  # hexahedra: the faces' vertices in cycle order
        facets = facet_cells(model.mesh, mesh.boundary_facets())
    tri = _triangles(facets)
    p = mesh.p.T[tri]  # (m, 3, 3)
    normal = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    facing = np.abs(normal[:, 2]) > 0.3 * np.linalg.norm(normal, axis=1)
    tri, z = tri[facing], p[facing, :, 2].mean(axis=1)
    return xy, tri[np.argsort(z, kind="stable")]


def view_outline(tri: np.ndarray) -> np.ndarray:
    """(s, 2) vertex pairs of the edges that bound the drawn triangles (used once)."""
    edges = np.sort(np.vstack([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]]), axis=1)
    unique, counts = np.unique(edges, axis=0, return_counts=True)
    return unique[counts == 1]


def _size(xy: np.ndarray) -> float:
    return float(np.linalg.norm(xy.max(axis=0) - xy.min(axis=0))) or 1.0


def axes(title: str, width: float = 7.0):
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(width, 5.2))
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title(title, fontsize=10)
    return fig, ax


def _projection(model) -> str:
    return "" if model.dim == 2 else " (3-D: projected onto the x-y plane, seen from +z)"


def _group_segments(femesh, name: str) -> np.ndarray:
    """(s, 2, 3) segments of a boundary group's facets (their edges), m."""
    p = femesh.mesh.p.T
    f = femesh.mesh.facets[:, femesh.boundaries[name]].T
    cycle = [(i, (i + 1) % f.shape[1]) for i in range(f.shape[1])] if f.shape[1] > 2 else [(0, 1)]
    return np.concatenate([np.stack([p[f[:, a]], p[f[:, b]]], axis=1) for a, b in cycle])


def part_centres(seg: np.ndarray, gap: float) -> list[np.ndarray]:
    """The mean point of each part of the segments (s, 2, 2), parts closer than ``gap``
    joined: one label per body of a group (a ground in two blocks gets two; an outline that
    the flexures interrupt, one)."""
    points = seg.reshape(-1, 2)
    cells, index = np.unique(np.floor(points / gap).astype(np.int64), axis=0,
                             return_inverse=True)
    where = {tuple(c): i for i, c in enumerate(cells)}
    rows, cols = [], []
    for i, (cx, cy) in enumerate(cells):
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                j = where.get((cx + dx, cy + dy))
                if j is not None:
                    rows.append(i)
                    cols.append(j)
    ends = index.reshape(-1, 2)  # a segment joins the cells of its two ends
    rows, cols = rows + ends[:, 0].tolist(), cols + ends[:, 1].tolist()
    graph = coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(len(cells), len(cells)))
    _, part = connected_components(graph, directed=False)
    part = part[index.ravel()]
    return [points[part == k].mean(axis=0) for k in np.unique(part)]


def colours(n: int) -> list:
    cmap = pyplot().get_cmap("tab10")
    return [cmap(i % 10) for i in range(n)]


def _label(ax, xy, text: str, colour) -> None:
    ax.annotate(text, xy, fontsize=8, color="black", ha="center", va="center",
                bbox=dict(boxstyle="round,pad=0.2", fc="white", ec=colour, alpha=0.85))


def mechanism_figure(model, source: str):
    """The continuum's mesh (grey) with each boundary group drawn and labelled."""
    xy, tri = continuum_view(model)
    fig, ax = axes(f"{source}: the mechanism and its groups{_projection(model)}")
    ax.tripcolor(xy[:, 0] * 1e3, xy[:, 1] * 1e3, tri, np.zeros(len(tri)), cmap="Greys",
                 vmin=0, vmax=5, edgecolors="#bbbbbb", linewidth=0.15)
    names = sorted(model.mesh.boundaries)
    for name, colour in zip(names, colours(len(names))):
        seg = _group_segments(model.mesh, name)
        ax.add_collection(LineCollection(seg[:, :, :2] * 1e3, colors=[colour], linewidths=2.5,
                                         label=name))
        for centre in part_centres(seg[:, :, :2], 0.05 * _size(xy)):
            _label(ax, centre * 1e3, name, colour)
    if names:
        ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize="small",
                  title="groups")
    ax.autoscale_view()
    caption = ("The mechanism as meshed, its boundary groups (supports and loads name them) "
               f"in colour{_projection(model)}; lengths in mm.")
    return fig, caption


def _deformed(ax, xy, u, tri, values, scale, label, cmap="viridis"):
    """Draw the undeformed outline (grey) and the deformed triangles coloured by values."""
    outline = view_outline(tri)
    ax.add_collection(LineCollection(xy[outline] * 1e3, colors="#999999", linewidths=0.6,
                                     linestyles="--"))
    moved = (xy + scale * u) * 1e3
    art = ax.tripcolor(moved[:, 0], moved[:, 1], tri, values, shading="gouraud", cmap=cmap)
    ax.figure.colorbar(art, ax=ax, label=label, shrink=0.85)
    ax.autoscale_view()
    return moved


def deformed_figure(model, static, source: str):
    """The deformed continuum coloured by the nodal von Mises stress (MPa), the peak marked."""
    xy, tri = continuum_view(model)
    u = np.asarray(static.displacement)[:, :2]
    scale = nice_scale(float(np.linalg.norm(static.displacement, axis=1).max()), _size(xy))
    vm = np.asarray(static.von_mises_nodal) / 1e6
    fig, ax = axes(f"{source}: deformed shape, {scale_text(scale)}{_projection(model)}")
    moved = _deformed(ax, xy, u, tri, vm, scale, "von Mises stress (MPa)", cmap="jet")
    peak = int(np.argmax(vm))
    ax.plot(*moved[peak], marker="*", markersize=14, color="white", markeredgecolor="black")
    ax.annotate(f"peak {vm[peak]:.4g} MPa", moved[peak], xytext=(8, 8),
                textcoords="offset points", fontsize=8,
                bbox=dict(boxstyle="round,pad=0.2", fc="white", alpha=0.85))
    caption = (f"Deformed shape under the model file's loads ({scale_text(scale)}; the "
               "undeformed outline dashed), coloured by the nodal (recovered) von Mises "
               f"stress; the star marks its peak, {vm[peak]:.4g} MPa{_projection(model)}.")
    return fig, caption


def continuum_mode_figure(model, modes, k: int, source: str):
    """Mode ``k`` (0-based) of the continuum, coloured by its relative amplitude."""
    xy, tri = continuum_view(model)
    shape = np.asarray(modes.vertex_shape(k))
    amplitude = np.linalg.norm(shape, axis=1)
    scale = DEFORMED_SHARE * _size(xy) / amplitude.max() if amplitude.max() > 0 else 0.0
    f = float(modes.frequencies_hz[k])
    fig, ax = axes(f"{source}: mode {k + 1}, {f:.4g} Hz{_projection(model)}")
    _deformed(ax, xy, shape[:, :2], tri, amplitude / (amplitude.max() or 1.0), scale,
              "relative amplitude")
    caption = (f"Mode {k + 1} at {f:.4g} Hz, drawn with its largest displacement a tenth of "
               "the mechanism's size (the undeformed outline dashed), coloured by the "
               f"displacement's magnitude over its largest{_projection(model)}.")
    return fig, caption
