"""A mechanism's outline for manufacture: DXF (ezdxf) and STEP (gmsh's OpenCASCADE writer).

DXF: every boundary loop of the mechanism's one face as a closed LWPOLYLINE in millimetres,
straight edges as vertices and fillets and notches as true arcs (bulges), as wire-EDM and laser
shops take it; the outer loop first, then the holes. STEP: the 2-D face, or with ``dim`` 3 the
solid extruded by the depth, in metres (gmsh's OCC writer; the file's unit is declared)."""
import contextlib
import math
import os
from pathlib import Path
import sys

import numpy as np

from ...fem import gmsh_session
from .description import Mechanism, cross2
from .draw import draw

SUFFIXES = (".dxf", ".step", ".stp")


def _fused(gmsh, mechanism: Mechanism, dim: int) -> list:
    """Draw the mechanism and fuse it into one shape; returns its entities of ``dim``."""
    draw(gmsh, mechanism, dim)
    occ = gmsh.model.occ
    shapes = occ.getEntities(dim)
    if len(shapes) > 1:
        shapes, _ = occ.fuse(shapes[:1], shapes[1:])
    occ.synchronize()
    return shapes


def _bulge(gmsh, curve: int, start) -> float:
    """The DXF bulge of ``curve`` traversed from its end at ``start`` (m): tan(sweep / 4),
    > 0 counter-clockwise; 0 for a straight line."""
    if gmsh.model.getType(1, curve) not in ("Circle", "Ellipse"):
        return 0.0
    lo, hi = gmsh.model.getParametrizationBounds(1, curve)
    a, m, b = (np.asarray(gmsh.model.getValue(1, curve, [u]))[:2]
               for u in (lo[0], (lo[0] + hi[0]) / 2, hi[0]))
    if np.linalg.norm(b - start) < np.linalg.norm(a - start):
        a, b = b, a
    chord = b - a
    cross = cross2(chord, m - a)
    sagitta = abs(cross) / np.linalg.norm(chord)
    return sagitta / (np.linalg.norm(chord) / 2) * (1.0 if cross < 0 else -1.0)


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
                loop.append((float(xy[0]), float(xy[1]), _bulge(gmsh, curve, xy)))
                point = q if p == point else p
            out.append(loop)
        return sorted(out, key=lambda lp: -_extent(lp))


def _extent(loop) -> float:
    xy = np.array([p[:2] for p in loop])
    return float(np.prod(xy.max(axis=0) - xy.min(axis=0)))


def write_dxf(mechanism: Mechanism, path) -> Path:
    """The outline as closed polylines with arcs, in millimetres (ezdxf)."""
    import ezdxf
    from ezdxf import units

    doc = ezdxf.new("R2010")
    doc.units = units.MM
    msp = doc.modelspace()
    for loop in outline_loops(mechanism):
        msp.add_lwpolyline([(1e3 * x, 1e3 * y, 0.0, 0.0, b) for x, y, b in loop],
                           format="xyseb", close=True)
    doc.saveas(path)
    return Path(path)


@contextlib.contextmanager
def _quiet_stdout():
    """OpenCASCADE's STEP writer prints its statistics on file descriptor 1: keep stdout
    for the command's own output (--json)."""
    sys.stdout.flush()
    saved = os.dup(1)
    try:
        with open(os.devnull, "w") as null:
            os.dup2(null.fileno(), 1)
            yield
    finally:
        os.dup2(saved, 1)
        os.close(saved)


def write_step(mechanism: Mechanism, path, dim: int = 2) -> Path:
    """The face (``dim`` 2) or the extruded solid (3) as STEP, in metres."""
    with gmsh_session("step") as gmsh:
        _fused(gmsh, mechanism, dim)
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")
        with _quiet_stdout():
            gmsh.write(str(path))
    return Path(path)


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


def polyline_area(points) -> float:
    """Area enclosed by a closed polyline [(x, y, bulge)] (any unit^2), arcs included."""
    total = 0.0
    for (x0, y0, b), (x1, y1, _) in zip(points, points[1:] + points[:1]):
        total += (x0 * y1 - x1 * y0) / 2
        if b:
            theta = 4 * math.atan(b)
            chord = math.hypot(x1 - x0, y1 - y0)
            radius = chord / (2 * math.sin(abs(theta) / 2))
            total += math.copysign(radius ** 2 * (abs(theta) - math.sin(abs(theta))) / 2, theta)
    return total
