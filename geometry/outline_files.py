"""Closed planar outlines as files for manufacture: DXF (ezdxf) and STEP (gmsh's OpenCASCADE
writer), both in millimetres (UNIT), the one pair of writers of the package.

A loop is [(x, y, bulge)] (m), closed (its last point joins its first); ``bulge`` is DXF's:
tan(sweep / 4) of the arc from this point to the next, > 0 counter-clockwise, 0 a straight
edge. A face is [outer loop, hole loop, ...]. The DXF holds each loop as a closed LWPOLYLINE
with its bulges (true arcs); the STEP each face as a planar face bounded by lines and circle
arcs, or the solid extruded from it by ``depth`` (m). The mechanism's export
(geometry/mechanism/export.py), the spatial mechanism's solid (geometry/spatial/export.py)
and the topology optimiser's outline (topopt/) all write through here."""
import contextlib
import math
import os
from pathlib import Path
import sys

import numpy as np

from ..fem import gmsh_session

UNIT = "mm"  # the length unit both files declare (DXF $INSUNITS, STEP's SI_UNIT(.MILLI.))
_PER_METRE = 1000.0


def write_dxf(loops, path) -> int:
    """Each loop (m) as a closed LWPOLYLINE in millimetres, arcs as bulges, the header's
    extents ($EXTMIN, $EXTMAX) those of the drawing (a viewer's "zoom extents"); returns the
    number of polylines written. OSError naming ``path`` where it cannot be written."""
    import ezdxf
    from ezdxf import bbox

    doc = ezdxf.new("R2010")
    doc.units = ezdxf.units.MM
    msp = doc.modelspace()
    for loop in loops:
        msp.add_lwpolyline([(_PER_METRE * x, _PER_METRE * y, 0.0, 0.0, b) for x, y, b in loop],
                           format="xyseb", close=True)
    box = bbox.extents(msp)
    if box.has_data:  # both: ezdxf copies the layout's on saving, unless its minimum is 0
        msp.reset_extents(box.extmin, box.extmax)
        doc.header["$EXTMIN"], doc.header["$EXTMAX"] = box.extmin, box.extmax
    try:
        doc.saveas(path)
    except OSError as error:
        raise OSError(f"{path}: the DXF file could not be written "
                      f"({error.strerror or error})") from None
    return len(loops)


def write_step(faces, path, depth: float | None = None) -> Path:
    """The faces (m) as planar STEP faces, or (``depth``, m) the solids extruded from them
    along z; the file declares millimetres and OpenCASCADE scales the metres to them."""
    with gmsh_session("step") as gmsh:
        occ = gmsh.model.occ
        surfaces = [(2, occ.addPlaneSurface([_curve_loop(occ, loop) for loop in face]))
                    for face in faces]
        if depth is not None:
            occ.extrude(surfaces, 0.0, 0.0, depth)
        return write_session_step(gmsh, path)


def write_session_step(gmsh, path) -> Path:
    """The shapes of the open gmsh session (drawn in metres) as STEP in millimetres: the
    writer :func:`write_step` and the spatial mechanism's solid
    (geometry/spatial/export.py) share."""
    gmsh.model.occ.synchronize()
    gmsh.option.setString("Geometry.OCCTargetUnit", "M")  # the model's unit: metres
    try:
        with _quiet_stdout():
            gmsh.write(str(path))
    except Exception as error:  # gmsh raises a bare Exception with its last error
        raise OSError(f"{path}: the STEP file could not be written ({error})") from None
    return Path(path)


def arc_midpoint(a, b, bulge: float) -> tuple:
    """The middle of the arc of ``bulge`` from point ``a`` to ``b`` (m): off the chord's
    middle by the sagitta bulge * chord / 2, to the right for a counter-clockwise arc."""
    (x0, y0), (x1, y1) = a, b
    half = bulge / 2
    return ((x0 + x1) / 2 + half * (y1 - y0), (y0 + y1) / 2 - half * (x1 - x0))


def polyline_area(points) -> float:
    """Area enclosed by a closed polyline [(x, y, bulge)] (any unit^2), arcs included; > 0
    counter-clockwise."""
    total = 0.0
    for (x0, y0, b), (x1, y1, _) in zip(points, points[1:] + points[:1]):
        total += (x0 * y1 - x1 * y0) / 2
        if b:
            theta = 4 * math.atan(b)
            chord = math.hypot(x1 - x0, y1 - y0)
            radius = chord / (2 * math.sin(abs(theta) / 2))
            total += math.copysign(radius ** 2 * (abs(theta) - math.sin(abs(theta))) / 2, theta)
    return total


def _curve_loop(occ, loop) -> int:
    """One closed loop [(x, y, bulge)] (m) as an OpenCASCADE curve loop of lines and arcs."""
    points = [occ.addPoint(x, y, 0.0) for x, y, _ in loop]
    curves = []
    for i, (x, y, bulge) in enumerate(loop):
        j = (i + 1) % len(loop)
        if bulge:
            mx, my = arc_midpoint((x, y), loop[j][:2], bulge)
            middle = occ.addPoint(mx, my, 0.0)
            curves.append(occ.addCircleArc(points[i], middle, points[j], center=False))
            occ.remove([(0, middle)])
        else:
            curves.append(occ.addLine(points[i], points[j]))
    return occ.addCurveLoop(curves)


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


def loop_of(coords) -> list:
    """A loop of straight edges [(x, y, 0.0)] from a ring's coordinates (m), the closing
    repeat of the first point (shapely's) dropped."""
    xy = np.asarray(coords, dtype=float)[:, :2]
    if len(xy) > 1 and np.array_equal(xy[0], xy[-1]):
        xy = xy[:-1]
    return [(float(x), float(y), 0.0) for x, y in xy]
