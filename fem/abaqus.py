"""Abaqus ``.inp`` meshes that CalculiX reads: nodes, elements, NSETs and ELSETs per group.

meshio's Abaqus writer breaks CalculiX's input rules (numbers over 20 characters, several
lines after ``*HEADING``, element names such as ``C3D10MH``), so flexfem writes its own.

Quadratic meshes (``order=2``) take their nodes from scikit-fem's P2/Q2 DOF locations: node
``k + 1`` is scalar DOF ``k`` of the quadratic basis flexfem solves with (vertices first, then
one mid-edge node per edge), so a CalculiX model and a flexfem model of ``order=2`` share their
nodes. For quadrilaterals and hexahedra the face and centre nodes of scikit-fem's 9-node Q2 and
27-node hexahedron are dropped: CalculiX knows only the 8-node CPS8 and the 20-node C3D20
(serendipity), a different element on the same nodes.
"""
import re
from dataclasses import dataclass

import numpy as np
import skfem

from .mesh import FEMesh
from .model import scalar_element

# (skfem mesh type, order) -> (CalculiX element, corner pairs of its mid-edge nodes, 0-based)
_TRI_EDGES = [(0, 1), (1, 2), (2, 0)]
_QUAD_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0)]
_TET_EDGES = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]
_HEX_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
              (0, 4), (1, 5), (2, 6), (3, 7)]
ELEMENT_TYPES = {
    (skfem.MeshTri, 1): ("CPS3", []), (skfem.MeshTri, 2): ("CPS6", _TRI_EDGES),
    (skfem.MeshQuad, 1): ("CPS4", []), (skfem.MeshQuad, 2): ("CPS8", _QUAD_EDGES),
    (skfem.MeshTet, 1): ("C3D4", []), (skfem.MeshTet, 2): ("C3D10", _TET_EDGES),
    (skfem.MeshHex, 1): ("C3D8", []), (skfem.MeshHex, 2): ("C3D20", _HEX_EDGES),
}
# skfem's hexahedron vertex order -> Abaqus/gmsh/VTK order (inverse of mesh._HEX_FROM_GMSH)
_HEX_TO_ABAQUS = np.argsort([0, 4, 3, 1, 7, 5, 2, 6])
_NUMBER = "%.12e"  # at most 19 characters: CalculiX reads 20 per field
_PER_LINE = 16       # Abaqus data lines: at most 16 entries, continuation by a trailing comma


@dataclass(frozen=True, eq=False)
class AbaqusMesh:
    """A mesh in CalculiX's terms. points : (n_nodes, 3) coordinates (m) of node ``k + 1``;
    elements : (n_elements, n_nodes_per_element) 0-based node indices in CalculiX order;
    element_type : e.g. 'C3D10'; node_sets / element_sets : {name: 0-based indices}."""

    points: np.ndarray
    elements: np.ndarray
    element_type: str
    node_sets: dict
    element_sets: dict


def element_type(femesh: FEMesh, order: int) -> tuple[str, list]:
    """CalculiX element name and the corner pairs of its mid-edge nodes."""
    scalar_element(femesh.mesh, order)  # validates the order
    for (mesh_type, o), value in ELEMENT_TYPES.items():
        if isinstance(femesh.mesh, mesh_type) and o == order:
            return value
    raise ValueError(f"no CalculiX element for a {type(femesh.mesh).__name__} of order {order}")


def edge_nodes(mesh: skfem.Mesh) -> np.ndarray:
    """(2, n_edges) sorted vertex pairs of the mesh edges (facets in 2-D), in the order of
    scikit-fem's edge DOFs: the quadratic node of edge ``e`` is scalar DOF ``n_vertices + e``."""
    return np.sort(mesh.edges if mesh.dim() == 3 else mesh.facets, axis=0)


def oriented_corners(mesh: skfem.Mesh) -> np.ndarray:
    """(n_elements, n_corners) vertex indices in Abaqus order with positive Jacobian
    (scikit-fem sorts simplex vertices, which may invert them; CalculiX rejects inverted
    elements)."""
    t = mesh.t.T.copy()
    if isinstance(mesh, skfem.MeshHex):
        t = t[:, _HEX_TO_ABAQUS]
    p = mesh.p.T
    if mesh.dim() == 2:
        a, b = p[t[:, 1]] - p[t[:, 0]], p[t[:, -1]] - p[t[:, 0]]
        flip = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0] < 0
        t[flip] = t[flip][:, ::-1]
    else:
        far = 3 if isinstance(mesh, skfem.MeshTet) else 4
        a, b, c = (p[t[:, i]] - p[t[:, 0]] for i in (1, 3 if far == 4 else 2, far))
        flip = np.einsum("ij,ij->i", np.cross(a, b), c) < 0
        if far == 3:
            t[flip] = t[flip][:, [1, 0, 2, 3]]
        else:  # swap the bottom face (1-2-3-4) with the top one (5-6-7-8)
            t[flip] = t[flip][:, [4, 5, 6, 7, 0, 1, 2, 3]]
    return t


def mid_edge_nodes(mesh: skfem.Mesh, corners: np.ndarray, pairs) -> np.ndarray:
    """(n_cells, len(pairs)) node index of the mid-edge node between each corner pair."""
    n = mesh.p.shape[1]
    keys = edge_nodes(mesh)
    keys = keys[0].astype(np.int64) * n + keys[1]
    order = np.argsort(keys)
    a = np.stack([corners[:, i] for i, _ in pairs], axis=1).astype(np.int64)
    b = np.stack([corners[:, j] for _, j in pairs], axis=1).astype(np.int64)
    wanted = np.minimum(a, b) * n + np.maximum(a, b)
    edge = order[np.searchsorted(keys, wanted, sorter=order)]
    return n + edge


def abaqus_mesh(femesh: FEMesh, order: int = 1) -> AbaqusMesh:
    """The CalculiX view of ``femesh`` with linear (``order=1``) or quadratic elements: nodes,
    connectivity, one NSET per group (the nodes of its facets or elements) and one ELSET per
    subdomain."""
    mesh = femesh.mesh
    name, pairs = element_type(femesh, order)
    corners = oriented_corners(mesh)
    if order == 1:
        points, elements = mesh.p.T, corners
    else:
        n_nodes = mesh.p.shape[1] + edge_nodes(mesh).shape[1]
        curved = femesh.cell_mesh(2)  # the edge nodes on their curved surfaces, if any
        points = skfem.Basis(curved, scalar_element(curved, 2), intorder=1).doflocs[:, :n_nodes].T
        elements = np.hstack([corners, mid_edge_nodes(mesh, corners, pairs)])
    points = np.hstack([points, np.zeros((points.shape[0], 3 - points.shape[1]))])
    node_sets = {g: group_nodes(femesh, g, order) for g in femesh.group_names}
    return AbaqusMesh(points, elements, name, node_sets, dict(femesh.subdomains))


def group_nodes(femesh: FEMesh, group: str, order: int = 1) -> np.ndarray:
    """0-based node indices (in :func:`abaqus_mesh` numbering) of a boundary group or subdomain:
    the vertices, and for ``order=2`` also the mid-edge nodes, of its facets or elements."""
    if order == 1:
        return femesh.nodes(group)
    mesh = femesh.mesh
    basis = skfem.Basis(mesh, scalar_element(mesh, 2), intorder=1)
    if group in femesh.boundaries:
        dofs = basis.get_dofs(facets=femesh.facets(group)).all()
    else:
        dofs = basis.get_dofs(elements=femesh.elements(group)).all()
    n_nodes = mesh.p.shape[1] + edge_nodes(mesh).shape[1]
    return np.unique(dofs[dofs < n_nodes])


def set_name(group: str) -> str:
    """An Abaqus/CalculiX set name for a group: letters, digits and '_', starting with a letter."""
    name = re.sub(r"[^A-Za-z0-9_]", "_", group)
    return name if name[:1].isalpha() else f"G_{name}"


def _data_lines(values, per_line: int = _PER_LINE) -> list[str]:
    """Comma-separated data lines of at most ``per_line`` entries, continued by a trailing comma."""
    values = [str(v) for v in values]
    chunks = [values[i:i + per_line] for i in range(0, len(values), per_line)]
    return [", ".join(c) + ("," if i < len(chunks) - 1 else "") for i, c in enumerate(chunks)]


def inp_lines(am: AbaqusMesh, heading: str = "flexfem mesh") -> list[str]:
    """The mesh part of a CalculiX deck: *HEADING (one line), *NODE, *ELEMENT (ELSET=EALL),
    *NSET per group and NALL, *ELSET per subdomain."""
    lines = ["*HEADING", heading.splitlines()[0][:80] if heading else "flexfem", "*NODE"]
    ids = np.arange(1, am.points.shape[0] + 1)
    x, y, z = (np.char.mod(_NUMBER, am.points[:, i]) for i in range(3))
    lines += [f"{i}, {a}, {b}, {c}" for i, a, b, c in zip(ids, x, y, z)]
    lines.append(f"*ELEMENT, TYPE={am.element_type}, ELSET=EALL")
    conn = am.elements + 1
    for e, row in enumerate(conn, start=1):
        lines += _data_lines([e, *row.tolist()])
    lines += ["*NSET, NSET=NALL, GENERATE", f"1, {am.points.shape[0]}, 1"]
    for group, nodes in am.node_sets.items():
        lines.append(f"*NSET, NSET={set_name(group)}")
        lines += _data_lines((np.asarray(nodes) + 1).tolist())
    for group, elements in am.element_sets.items():
        lines.append(f"*ELSET, ELSET={set_name(group)}")
        lines += _data_lines((np.asarray(elements) + 1).tolist())
    return lines


def write_inp(femesh: FEMesh, path, order: int = 1) -> AbaqusMesh:
    """Write ``femesh`` to a CalculiX-readable Abaqus ``.inp`` file (mesh and sets only)."""
    am = abaqus_mesh(femesh, order)
    with open(path, "w") as f:
        f.write("\n".join(inp_lines(am)) + "\n")
    return am
