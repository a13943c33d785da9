"""The outline as STEP (gmsh's OpenCASCADE writer, in metres), as ``flexfem export`` writes a
model file's: one planar face per part, its holes cut."""
from pathlib import Path

import numpy as np

from ..fem import gmsh_session
from ..geometry.mechanism.export import _quiet_stdout
from .outline import Outline


def _occ_loop(occ, coords) -> int:
    points = [occ.addPoint(x, y, 0.0) for x, y in np.asarray(coords)[:-1]]
    lines = [occ.addLine(a, b) for a, b in zip(points, points[1:] + points[:1])]
    return occ.addCurveLoop(lines)


def write_step(outline: Outline, path) -> Path:
    """Write the outline's faces (m) to ``path`` (.step or .stp)."""
    with gmsh_session("topopt-step") as gmsh:
        occ = gmsh.model.occ
        for part in outline.parts:
            loops = [_occ_loop(occ, part.exterior.coords)]
            loops += [_occ_loop(occ, r.coords) for r in part.interiors]
            occ.addPlaneSurface(loops)
        occ.synchronize()
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")
        with _quiet_stdout():
            gmsh.write(str(path))
    return Path(path)


def step_area(path) -> float:
    """The total face area (m^2) of a STEP file, re-imported by OpenCASCADE."""
    with gmsh_session("topopt-step-read") as gmsh:
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")
        shapes = gmsh.model.occ.importShapes(str(path))
        gmsh.model.occ.synchronize()
        return float(sum(gmsh.model.occ.getMass(d, t) for d, t in shapes if d == 2))
