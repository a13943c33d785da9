"""The field files of ``flexfem analyze --out DIR``: VTU files for ParaView of the model that
was solved, with the model file's groups as cell data.

    static.vtu  the load case: displacement (m), von_mises (Pa), stress (Pa, 9 components)
    modes.vtu   with [analysis] modes: one point field per mode, "mode_1 (124.2 Hz)", ...
    stroke_path.vtu  with stroke_check: the large-deflection path's end state

The continuum's fields are :func:`flexfem.fem.export.result_fields` (the vertices of the
first-order mesh), written on the elements and on the boundary groups' facets
(:func:`flexfem.fem.export.meshio_mesh`: cell data ``group_id`` and one 0/1 array per group).
The beam model's are its beam lines (line cells: the beams, its notches' condensed pairs and
its rigid links, told apart by the cell data ``kind``), with the displacement and rotation
at the nodes, the beam stress |N|/A + |M| c/I per beam element (Pa) and one 0/1 point array
per group (a beam model's group is its nodes).
"""
from pathlib import Path

import meshio
import numpy as np

from ...fem.beam.face import BeamResult
from ...fem.beam.modal import BeamModes
from ...fem.beam.model import BeamModel
from ...fem.export import meshio_mesh, mode_field_name, result_fields
from ...fem.modal import Modes
from ...fem.model import Model
from ...fem.nonlinear_result import NonlinearResult
from ...fem.static_result import StaticResult

#: cell data ``kind`` of a beam model's line cells
BEAM_KINDS = {"beam": 0, "condensed pair": 1, "rigid link": 2}


def _pad3(vectors) -> np.ndarray:
    v = np.asarray(vectors, dtype=float)
    return np.hstack([v, np.zeros((v.shape[0], 3 - v.shape[1]))])


def continuum_mesh(model: Model, point: dict, element: dict) -> meshio.Mesh:
    """The continuum's elements and boundary facets with the groups as cell data,
    ``point`` data at the vertices and ``element`` data (one array per element) on the
    element block (NaN on the facets)."""
    m = meshio_mesh(model.mesh, order=1)
    cell_data = dict(m.cell_data)
    for name, values in element.items():
        cell_data[name] = [np.asarray(values, dtype=float)] + [
            np.full(len(block.data), np.nan) for block in m.cells[1:]]
    return meshio.Mesh(m.points, m.cells, point_data=point, cell_data=cell_data)


def beam_cells(model: BeamModel) -> list[tuple[str, np.ndarray, str]]:
    """[(kind, (n, 2) node pairs)] of the beam model's lines."""
    links = [(link.master, s) for link in model.rigid_links for s in link.slaves]
    blocks = [("beam", model.elements), ("condensed pair", model.pairs),
              ("rigid link", np.array(links, dtype=int).reshape(-1, 2))]
    return [(kind, np.asarray(c, dtype=int).reshape(-1, 2)) for kind, c in blocks if len(c)]


def beam_mesh(model: BeamModel, point: dict, stress=None) -> meshio.Mesh:
    """The beam model's lines (see the module's docstring) with ``point`` data at its nodes
    and the beam ``stress`` (Pa, one value per beam element) as cell data."""
    blocks = beam_cells(model)
    cells = [("line", c) for _, c in blocks]
    cell_data = {"kind": [np.full(len(c), BEAM_KINDS[k], dtype=np.int32) for k, c in blocks]}
    if stress is not None:
        cell_data["beam_stress"] = [np.asarray(stress, dtype=float) if k == "beam"
                                    else np.full(len(c), np.nan) for k, c in blocks]
    point = dict(point)
    for name, g in model.groups.items():
        member = np.zeros(model.n_nodes, dtype=np.int32)
        member[list(g.nodes)] = 1
        point[name if name not in point else f"group {name}"] = member
    return meshio.Mesh(_pad3(model.nodes), cells, point_data=point, cell_data=cell_data)


def static_mesh(model, static) -> meshio.Mesh | None:
    """The load case's mesh and fields, or None for a result this module does not know (the
    spatial beam model's out-of-plane statics)."""
    if isinstance(static, StaticResult):
        point, cell, _ = result_fields(static)
        return continuum_mesh(model, point, {k: v[0] for k, v in cell.items()})
    if isinstance(static, BeamResult) and static.dim == 2:  # the spatial one's: not here
        q = static.state.q
        return beam_mesh(model, {"displacement": _pad3(q[:, :2]), "rotation": q[:, 2]},
                         static.state.stress)
    return None


def path_end_mesh(model, path) -> meshio.Mesh | None:
    """The final step of a large-deflection solve of ``model`` (the continuum's
    NonlinearResult: displacement, von Mises and the Cauchy and second Piola-Kirchhoff
    stresses on the reference mesh; the beam model's path: as its static result), or None."""
    if isinstance(path, NonlinearResult):
        point, cell, _ = result_fields(path)
        return continuum_mesh(model, point, {k: v[0] for k, v in cell.items()})
    if hasattr(path, "step"):
        return static_mesh(model, path.step(-1))
    return None


def modes_mesh(model, modes) -> meshio.Mesh | None:
    """Every mode shape as a point field named by its frequency (mass-normalised,
    m/sqrt(kg)), or None for modes this module does not know."""
    if isinstance(modes, Modes):
        point, _, _ = result_fields(modes)
        return continuum_mesh(model, point, {})
    if isinstance(modes, BeamModes) and modes.model.dim == 2:
        point = {mode_field_name(k, f): _pad3(modes.shapes[k][:, :2])
                 for k, f in enumerate(modes.frequencies_hz)}
        return beam_mesh(model, point)
    return None


def write_vtu(mesh: meshio.Mesh, path: Path) -> None:
    """Write ``mesh`` as VTU at ``path`` (the caller renames it into place)."""
    meshio.write(path, mesh, file_format="vtu")
