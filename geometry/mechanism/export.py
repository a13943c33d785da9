"""A mechanism's outline for manufacture, through the package's one DXF and STEP writers
(geometry/outline_files.py), both in millimetres.

The boundary loops of the mechanism's one face, the outer loop first, then the holes:
straight edges as vertices, fillets and circular notches as true arcs (bulges), an elliptical
notch as ELLIPSE_ARCS circular arcs, as wire-EDM and laser shops take it. DXF: each loop a
closed LWPOLYLINE. STEP: the 2-D face, or with ``dim`` 3 the solid extruded by the depth."""
from pathlib import Path

import numpy as np

from ...fem import gmsh_session
from ..outline_files import write_dxf as _write_dxf, write_step as _write_step
from .description import Mechanism, cross2
from .draw import draw

SUFFIXES = (".dxf", ".step", ".stp")
ELLIPSE_ARCS = 32  # circular arcs an elliptical notch's side is written as (DXF has none)


def _fused(gmsh, mechanism: Mechanism, dim: int) -> list:
    """Draw the mechanism and fuse it into one shape; returns its entities of ``dim``."""
    draw(gmsh, mechanism, dim)
    occ = gmsh.model.occ
    shapes = occ.getEntities(dim)
    if len(shapes) > 1:
        shapes, _ = occ.fuse(shapes[:1], shapes[1:])
    occ.synchronize()
    return shapes


def _bulge(a, m, b) -> float:
    """The DXF bulge tan(sweep / 4) of the circle through ``a``, ``m``, ``b`` (m) from a to
    b, > 0 counter-clockwise."""
    chord = b - a
    cross = cross2(chord, m - a)
    sagitta = abs(cross) / np.linalg.norm(chord)
    return sagitta / (np.linalg.norm(chord) / 2) * (1.0 if cross < 0 else -1.0)


def _segments(gmsh, curve: int, start) -> list:
    """[(x, y, bulge)] of ``curve`` traversed from its end at ``start`` (m): one straight
    edge, one arc for a circle's (OpenCASCADE may call it an ellipse), ELLIPSE_ARCS arcs for
    a true ellipse's."""
    kind = gmsh.model.getType(1, curve)
    if kind not in ("Circle", "Ellipse"):
        return [(float(start[0]), float(start[1]), 0.0)]
    lo, hi = gmsh.model.getParametrizationBounds(1, curve)
    curvature = np.abs(gmsh.model.getCurvature(1, curve, np.linspace(lo[0], hi[0], 9).tolist()))
    n = 1 if np.ptp(curvature) <= 1e-9 * curvature.max() else ELLIPSE_ARCS  # a circle's arc
    u = np.linspace(lo[0], hi[0], 2 * n + 1)
    xy = np.asarray(gmsh.model.getValue(1, curve, u.tolist())).reshape(-1, 3)[:, :2]
    if np.linalg.norm(xy[-1] - start) < np.linalg.norm(xy[0] - start):
        xy = xy[::-1]
    return [(float(xy[2 * k][0]), float(xy[2 * k][1]),
             _bulge(xy[2 * k], xy[2 * k + 1], xy[2 * k + 2])) for k in range(n)]


def _ends(gmsh, curve: int) -> list:
    return [abs(t) for _, t in gmsh.model.getBoundary([(1, curve)], combined=False,
                                                      recursive=False)]


def outline_loops(mechanism: Mechanism) -> list:
    """[[(x, y, bulge)]] (m): the boundary loops of the mechanism's face, the outer first."""
    with gmsh_session("outline") as gmsh:
        (face,) = _fused(gmsh, mechanism, 2)
        _, loops = gmsh.model.occ.getCurveLoops(face[1])
        out = []
        for curves in loops:
            curves = [abs(int(c)) for c in curves]
            ends = [_ends(gmsh, c) for c in curves]
            point = next(p for p in ends[0] if p not in ends[1 % len(ends)]) \
                if len(ends) > 1 else ends[0][0]
            loop = []
            for curve, (p, q) in zip(curves, ends):
                xy = np.asarray(gmsh.model.getValue(0, point, []))[:2]
                loop += _segments(gmsh, curve, xy)
                point = q if p == point else p
            out.append(loop)
        return sorted(out, key=lambda lp: -_extent(lp))


def _extent(loop) -> float:
    xy = np.array([p[:2] for p in loop])
    return float(np.prod(xy.max(axis=0) - xy.min(axis=0)))


def write_dxf(mechanism: Mechanism, path) -> Path:
    """The outline as closed polylines with arcs, in millimetres."""
    _write_dxf(outline_loops(mechanism), path)
    return Path(path)


def write_step(mechanism: Mechanism, path, dim: int = 2) -> Path:
    """The face (``dim`` 2) or the solid extruded by the depth (3) as STEP, in millimetres."""
    return _write_step([outline_loops(mechanism)], path,
                       mechanism.depth if dim == 3 else None)


def export(mechanism: Mechanism, path, dim: int = 2) -> Path:
    """Write ``path`` by its suffix: .dxf (the 2-D outline) or .step/.stp."""
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in SUFFIXES:
        raise ValueError(f"{path}: unknown export type {path.suffix!r}; use .dxf or .step")
    if suffix == ".dxf":
        if dim != 2:
            raise ValueError(f"{path}: a DXF is the 2-D outline; use .step for the solid")
        return write_dxf(mechanism, path)
    return write_step(mechanism, path, dim)


def area(mechanism: Mechanism) -> float:
    """The mechanism's face area (m^2), from the OpenCASCADE model (checks of an export)."""
    with gmsh_session("area") as gmsh:
        return sum(gmsh.model.occ.getMass(*dt) for dt in _fused(gmsh, mechanism, 2))
