"""The outline as STEP, through the package's one STEP writer (geometry/outline_files.py, in
millimetres), as ``flexfem export`` writes a model file's: one planar face per part, its holes
cut."""
from pathlib import Path

from ..fem import gmsh_session
from ..geometry.outline_files import write_step as _write_step
from .outline import Outline


def write_step(outline: Outline, path) -> Path:
    """Write the outline's faces to ``path`` (.step or .stp), in millimetres."""
    return _write_step(outline.faces, path)


def step_area(path) -> float:
    """The total face area (m^2) of a STEP file, re-imported by OpenCASCADE."""
    with gmsh_session("topopt-step-read") as gmsh:
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")
        shapes = gmsh.model.occ.importShapes(str(path))
        gmsh.model.occ.synchronize()
        return float(sum(gmsh.model.occ.getMass(d, t) for d, t in shapes if d == 2))
