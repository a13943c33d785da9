"""A spatial mechanism's solid for manufacture: its bodies and flexures (as the continuum
draws them, geometry/spatial/continuum.py) fused by OpenCASCADE into one solid and written
as STEP in millimetres through the package's one STEP writer
(geometry/outline_files.write_session_step). ``flexfem export FILE.toml OUT.step`` on a
spatial file writes it; its volume is :func:`~.mass.mechanism_volume`."""
from pathlib import Path

from ...fem import gmsh_session
from ..outline_files import write_session_step
from .continuum import body_shapes, flexure_shapes
from .description import SpatialMechanism


def _fused(gmsh, mechanism: SpatialMechanism) -> list:
    occ = gmsh.model.occ
    shapes = [dt for b in mechanism.bodies for dt in body_shapes(occ, b)]
    shapes += [dt for tags in flexure_shapes(occ, mechanism) for dt in tags]
    try:
        shapes, _ = occ.fuse(shapes[:1], shapes[1:])
    except Exception as error:  # gmsh raises plain Exception with OCC's message
        raise ValueError(f"{mechanism.source}: gmsh cannot fuse the bodies and flexures "
                         f"({error}); look for a degenerate shape") from None
    occ.synchronize()
    return shapes


def write_spatial_step(mechanism: SpatialMechanism, path) -> Path:
    """The fused solid of ``mechanism`` as STEP (.step or .stp, millimetres)."""
    path = Path(path)
    if path.suffix.lower() not in (".step", ".stp"):
        raise ValueError(f"{path}: a spatial mechanism is exported as its solid: use .step "
                         "(a DXF is a planar outline)")
    with gmsh_session("spatial step") as gmsh:
        _fused(gmsh, mechanism)
        return write_session_step(gmsh, path)


def solid_volume(mechanism: SpatialMechanism) -> float:
    """The fused solid's volume (m^3) from the OpenCASCADE model (checks of an export)."""
    with gmsh_session("spatial volume") as gmsh:
        return sum(gmsh.model.occ.getMass(*dt) for dt in _fused(gmsh, mechanism))
