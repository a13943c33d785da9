"""Mesh and field export for ParaView, gmsh and CalculiX: one table of formats, two entry
points.

    write_mesh(femesh, "part.msh")           # .msh (gmsh 2.2) .vtu .xdmf .inp, by extension
    write_mesh(femesh, "part.inp", order=2)  # quadratic CalculiX mesh, same nodes as flexfem P2
    write_result(static_result, "u.vtu")     # displacement, von Mises, stress at the vertices
    write_result(modes, "modes.xdmf")        # every mode shape

Fields are written at the mesh vertices on the first-order mesh: the quadratic (P2) fields are
sampled at the vertices (their mid-edge values are not written) and von Mises is the nodal
L2-projected value of :class:`~flexfem.fem.static.StaticResult`.
"""
from pathlib import Path

import meshio
import numpy as np
import skfem

from .abaqus import (
    abaqus_mesh,
    group_nodes,
    mid_edge_nodes,
    oriented_corners,
    write_inp,
)
from .mesh import FEMesh
from .modal import Modes
from .nonlinear_result import NonlinearResult
from .static_result import StaticResult, vertex_displacement
from .stress import nonlinear_stress

# skfem mesh type -> (meshio cell type of the element for order 1, 2; meshio facet cell type)
_MESHIO_CELLS = {
    skfem.MeshTri: (("triangle", "triangle6"), "line"),
    skfem.MeshQuad: (("quad", "quad8"), "line"),
    skfem.MeshTet: (("tetra", "tetra10"), "triangle"),
    skfem.MeshHex: (("hexahedron", "hexahedron20"), "quad"),
}


def cell_types(mesh: skfem.Mesh) -> tuple[tuple[str, str], str]:
    for mesh_type, value in _MESHIO_CELLS.items():
        if isinstance(mesh, mesh_type):
            return value
    raise ValueError(f"cannot export a {type(mesh).__name__}")


_CYCLE = {"line": [(0, 1)], "triangle": [(0, 1), (1, 2), (2, 0)],
          "quad": [(0, 1), (1, 2), (2, 3), (3, 0)]}
_QUADRATIC_FACET = {"line": "line3", "triangle": "triangle6", "quad": "quad8"}
# faces of a hexahedron in Abaqus/VTK vertex order, each a cycle
_HEX_FACES = np.array([[0, 1, 2, 3], [4, 7, 6, 5], [0, 4, 5, 1], [1, 5, 6, 2], [2, 6, 7, 3],
                       [3, 7, 4, 0]])


def facet_cells(femesh: FEMesh, facets: np.ndarray) -> np.ndarray:
    """(n, k) vertex indices of boundary facets in meshio (VTK) order: for hexahedra the
    face of the adjacent element whose vertices go round the face (skfem stores them sorted)."""
    mesh = femesh.mesh
    f = mesh.facets[:, facets].T
    if not isinstance(mesh, skfem.MeshHex):
        return f
    faces = oriented_corners(mesh)[mesh.f2t[0, facets]][:, _HEX_FACES]  # (n, 6, 4)
    same = np.all(np.sort(faces, axis=2) == np.sort(f, axis=1)[:, None, :], axis=2)
    return faces[np.arange(len(facets)), np.argmax(same, axis=1)]


def group_tags(femesh: FEMesh) -> dict[str, int]:
    """Integer tag (1, 2, ...) of each group, subdomains first; the gmsh physical tags and the
    ``group_id`` cell data of the exported files."""
    names = sorted(femesh.subdomains) + sorted(femesh.boundaries)
    return {name: i + 1 for i, name in enumerate(names)}


def meshio_mesh(femesh: FEMesh, order: int = 1) -> meshio.Mesh:
    """A meshio.Mesh of ``femesh``: one block of elements, one block of facets per boundary
    group; cell data ``group_id`` (the group's tag; for an element in several subdomains the
    first by name, 0 for none), one 0/1 array per group, cell sets and field data
    ``{name: [tag, dim]}``."""
    (linear, quadratic), facet_type = cell_types(femesh.mesh)
    am = abaqus_mesh(femesh, order)
    dim = femesh.dim
    points = am.points  # (n, 3): VTU and gmsh store 3-D points
    tags = group_tags(femesh)
    n_el = am.elements.shape[0]
    element_tag = np.zeros(n_el, dtype=np.int32)
    for name in sorted(femesh.subdomains, reverse=True):
        element_tag[femesh.subdomains[name]] = tags[name]
    cells = [(quadratic if order == 2 else linear, am.elements)]
    group_id = [element_tag]
    for name in sorted(femesh.boundaries):
        facets = facet_cells(femesh, femesh.boundaries[name])
        ftype = facet_type
        if order == 2:
            facets = np.hstack([facets, mid_edge_nodes(femesh.mesh, facets, _CYCLE[facet_type])])
            ftype = _QUADRATIC_FACET[facet_type]
        cells.append((ftype, facets))
        group_id.append(np.full(facets.shape[0], tags[name], dtype=np.int32))
    cell_data = {"group_id": group_id}
    cell_sets = {}
    for name, tag in tags.items():
        member = [np.zeros(len(g), dtype=np.int32) for g in group_id]
        if name in femesh.subdomains:
            member[0][femesh.subdomains[name]] = 1
        else:
            member[1 + sorted(femesh.boundaries).index(name)][:] = 1
        cell_data[name] = member
        cell_sets[name] = [np.flatnonzero(m) for m in member]
    field_data = {name: np.array([tag, dim if name in femesh.subdomains else dim - 1])
                  for name, tag in tags.items()}
    return meshio.Mesh(points, cells, cell_data=cell_data, cell_sets=cell_sets,
                       field_data=field_data)


def _write_msh(femesh: FEMesh, path: Path, order: int) -> None:
    m = meshio_mesh(femesh, order)
    tags = m.cell_data["group_id"]
    m = meshio.Mesh(m.points, m.cells, field_data=m.field_data,
                    cell_data={"gmsh:physical": tags, "gmsh:geometrical": tags})
    meshio.write(path, m, file_format="gmsh22", binary=False)


def _write_vtu(femesh: FEMesh, path: Path, order: int) -> None:
    m = meshio_mesh(femesh, order)
    meshio.write(path, meshio.Mesh(m.points, m.cells, cell_data=m.cell_data,
                                   field_data=m.field_data), file_format="vtu")


def _write_xdmf(femesh: FEMesh, path: Path, order: int) -> None:
    """XDMF holds the element block only (meshio cannot read back XDMF's mixed topology of
    quadratic cells): subdomains as cell data, boundary groups as 0/1 point data on the nodes
    of their facets."""
    m = meshio_mesh(femesh, order)
    cell_data = {name: [data[0]] for name, data in m.cell_data.items()
                 if name not in femesh.boundaries}
    point_data = {}
    for name in femesh.boundaries:
        member = np.zeros(len(m.points), dtype=np.int32)
        member[group_nodes(femesh, name, order)] = 1
        point_data[name] = member
    meshio.xdmf.write(path, meshio.Mesh(m.points, m.cells[:1], point_data=point_data,
                                        cell_data=cell_data), data_format="XML")


def _write_inp(femesh: FEMesh, path: Path, order: int) -> None:
    write_inp(femesh, path, order)


MESH_FORMATS = {".msh": _write_msh, ".vtu": _write_vtu, ".xdmf": _write_xdmf, ".inp": _write_inp}
RESULT_FORMATS = (".vtu", ".xdmf")


def _format(path: Path, known) -> str:
    suffix = path.suffix.lower()
    if suffix not in known:
        raise ValueError(f"unknown file extension {suffix!r} of {path}; known: {', '.join(known)}")
    return suffix


def write_mesh(femesh: FEMesh, path, order: int = 1) -> Path:
    """Write ``femesh`` with its groups to ``path``, the format chosen by the extension:
    ``.msh`` (gmsh 2.2 ASCII, groups as physical tags named in ``$PhysicalNames``), ``.vtu``
    (elements and boundary facets, cell data ``group_id`` and one 0/1 array per group),
    ``.xdmf`` (elements only; subdomains as cell data, boundary groups as 0/1 point data), ``.inp`` (CalculiX/Abaqus,
    NSET and ELSET per group). ``order=2`` writes quadratic elements (mid-edge nodes at
    scikit-fem's P2 DOF locations). Coordinates in m."""
    if order not in (1, 2):
        raise ValueError(f"order = {order} must be 1 or 2")
    path = Path(path)
    MESH_FORMATS[_format(path, MESH_FORMATS)](femesh, path, order)
    return path


def pad3(vectors: np.ndarray) -> np.ndarray:
    """(n, 2) -> (n, 3) with a zero z column, for ParaView's vector glyphs and warps."""
    return np.hstack([vectors, np.zeros((vectors.shape[0], 3 - vectors.shape[1]))])


def mode_field_name(k: int, frequency_hz: float) -> str:
    """Name of the field of mode ``k`` (0-based), e.g. 'mode_1 (81.6269 Hz)': ParaView lists it
    with its frequency."""
    return f"mode_{k + 1} ({frequency_hz:.6g} Hz)"


def _tensor9(tensors: np.ndarray) -> np.ndarray:
    """(n, 3, 3) -> (n, 9) row-major: ParaView's tensor layout (XX XY XZ YX ... ZZ)."""
    return np.ascontiguousarray(tensors.reshape(len(tensors), 9))


def result_fields(result_or_modes) -> tuple[dict, dict, dict]:
    """(point_data, cell_data, field_data) of a StaticResult, NonlinearResult (final step) or
    Modes at the mesh vertices: ``displacement`` (m), ``von_mises`` (Pa, nodal),
    ``von_mises_element_max`` (Pa, per element), ``stress`` (Pa, the nodal L2-projected Cauchy
    tensor, 9 components; a NonlinearResult has ``stress_cauchy`` and
    ``stress_second_piola_kirchhoff`` instead, on the reference mesh); or one field per mode,
    named by :func:`mode_field_name` (mass-normalised, m/sqrt(kg)).
    meshio's VTU writer drops field data, so each mode's frequency is in its field's name."""

    r = result_or_modes
    if isinstance(r, StaticResult):
        point = {"displacement": pad3(r.displacement), "von_mises": r.von_mises_nodal}
        if r.nodal_stress_full is not None:
            point["stress"] = _tensor9(r.nodal_stress_full)
        return point, {"von_mises_element_max": [r.von_mises_element_max]}, {}
    if isinstance(r, NonlinearResult):
        point = {"displacement": pad3(vertex_displacement(r.model, r.u[-1])),
                 "von_mises": r.von_mises_nodal}
        for name, value in nonlinear_stress(r, full=True).items():
            point[f"stress_{name}"] = _tensor9(value)
        return point, {"von_mises_element_max": [r.von_mises_element_max]}, {}
    if isinstance(r, Modes):
        point = {mode_field_name(k, f): pad3(r.vertex_shape(k))
                 for k, f in enumerate(r.frequencies_hz)}
        return point, {}, {}
    raise ValueError(f"write_result needs a StaticResult, NonlinearResult or Modes, not "
                     f"{type(r).__name__}")


def write_result(result_or_modes, path) -> Path:
    """Write a StaticResult or NonlinearResult (displacement, von Mises, stress tensors) or
    Modes (every mode shape) to ``.vtu`` or ``.xdmf`` for ParaView, on the first-order mesh
    (fields at the vertices; see :func:`result_fields`)."""
    path = Path(path)
    suffix = _format(path, RESULT_FORMATS)
    point, cell, field = result_fields(result_or_modes)
    femesh = result_or_modes.model.mesh
    (linear, _), _ = cell_types(femesh.mesh)
    m = meshio.Mesh(pad3(femesh.mesh.p.T), [(linear, oriented_corners(femesh.mesh))],
                    point_data=point, cell_data=cell, field_data=field)
    if suffix == ".xdmf":
        meshio.xdmf.write(path, m, data_format="XML")
    else:
        meshio.write(path, m, file_format="vtu")
    return path
