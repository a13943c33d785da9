"""Meshes with named groups: gmsh physical groups become skfem boundaries and subdomains.

Nodes, elements and groups are read from the gmsh API directly (not through pygmsh or
meshio's tag parsing, see DESIGN.md), and boundaries are matched to skfem facets by their
sorted vertex indices, vectorised.
"""
from dataclasses import dataclass, field
from itertools import combinations
from pathlib import Path

import meshio
import numpy as np
import skfem
import skfem.io.meshio

from .gmsh_session import gmsh_session
from .mesh_check import (check_facet_sharing, check_hanging_nodes, check_unused_vertices,
                         unused_vertices)

# gmsh element type -> (skfem mesh class, number of corner nodes). Higher-order types (9 and
# 11: 6/10-node simplices; 10 and 16: 9/8-node quadrangles; 12 and 17: 27/20-node hexahedra)
# list their corners first and are read by them.
_GMSH_CELLS = {
    2: (skfem.MeshTri, 3), 9: (skfem.MeshTri, 3),
    3: (skfem.MeshQuad, 4), 10: (skfem.MeshQuad, 4), 16: (skfem.MeshQuad, 4),
    4: (skfem.MeshTet, 4), 11: (skfem.MeshTet, 4),
    5: (skfem.MeshHex, 8), 12: (skfem.MeshHex, 8), 17: (skfem.MeshHex, 8),
}
# gmsh facet (boundary element) type -> number of corner nodes: lines (1, 8), triangles (2, 9),
# quadrangles (3, 10, 16)
_GMSH_FACET_CORNERS = {1: 2, 8: 2, 2: 3, 9: 3, 3: 4, 10: 4, 16: 4}
# gmsh's (= VTK's) hexahedron vertex order -> skfem's (skfem.io.meshio.HEX_MAPPING)
_HEX_FROM_GMSH = [0, 4, 3, 1, 7, 5, 2, 6]


@dataclass(frozen=True, eq=False)
class FEMesh:
    """A first-order skfem mesh with named boundaries (facet indices) and subdomains
    (element indices). Coordinates in metres. Refused with ValueError: no elements, non-finite
    coordinates, vertices in no element, degenerate, folded, inverted or overlapping elements,
    and non-conforming meshes (hanging nodes); see :mod:`~flexfem.fem.mesh_check`.

    ``edge_nodes`` (optional, (dim, n_edges) m, tetrahedral meshes): where a quadratic
    element's node on each edge of ``mesh.edges`` lies, for cells curved onto a round
    surface (:meth:`cell_mesh`); None: every edge straight, its node at the midpoint."""

    mesh: skfem.Mesh
    boundaries: dict = field(default_factory=dict)
    subdomains: dict = field(default_factory=dict)
    edge_nodes: np.ndarray | None = None

    def __post_init__(self):
        if self.mesh.t.shape[1] == 0:
            raise ValueError("the mesh has no elements")
        if not np.all(np.isfinite(self.mesh.p)):
            raise ValueError(f"the mesh has {np.sum(~np.all(np.isfinite(self.mesh.p), axis=0))} "
                             "vertices with non-finite coordinates; fix the geometry")
        _check_cells(self.mesh)
        check_unused_vertices(self.mesh)
        check_facet_sharing(self.mesh)
        check_hanging_nodes(self.mesh)
        if self.edge_nodes is not None:
            expected = (3, self.mesh.edges.shape[1]) if isinstance(self.mesh, skfem.MeshTet) else None
            if np.shape(self.edge_nodes) != expected:
                raise ValueError(f"edge_nodes of shape {np.shape(self.edge_nodes)}: a tetrahedral "
                                 f"mesh's curved edges take one node per edge, {expected}")

    def cell_mesh(self, order: int) -> skfem.Mesh:
        """The mesh the cells of ``order`` are mapped on: with :attr:`edge_nodes` and order 2,
        skfem's quadratic (isoparametric) MeshTet2 through them; else :attr:`mesh`."""
        if self.edge_nodes is None or order != 2:
            return self.mesh
        return skfem.MeshTet2(np.hstack([self.mesh.p, self.edge_nodes]), self.mesh.t)

    @property
    def dim(self) -> int:
        return self.mesh.dim()

    @property
    def edge_lengths(self) -> np.ndarray:
        """(n_edges,) length (m) of every element edge, each counted once."""
        edges = self.mesh.facets if self.dim == 2 else self.mesh.edges
        return np.linalg.norm(self.mesh.p[:, edges[1]] - self.mesh.p[:, edges[0]], axis=0)

    @property
    def characteristic_size(self) -> float:
        """The mesh's own element size h (m): the mean edge length (``edge_lengths.max()``
        is the largest)."""
        return float(self.edge_lengths.mean())

    @property
    def group_names(self) -> list[str]:
        return sorted(self.boundaries) + sorted(self.subdomains)

    def facets(self, name: str) -> np.ndarray:
        """Facet indices of boundary group ``name``."""
        if name in self.subdomains:
            raise ValueError(f"{name!r} is a subdomain, not a boundary group; loads on a boundary "
                             f"need one of the boundary groups {sorted(self.boundaries)} (for a "
                             "load on the volume use BodyForce)")
        if name not in self.boundaries:
            raise ValueError(f"no boundary group {name!r}; boundary groups: {sorted(self.boundaries)}"
                             f", subdomains: {sorted(self.subdomains)}")
        return self.boundaries[name]

    def elements(self, name: str) -> np.ndarray:
        """Element indices of subdomain ``name``."""
        if name not in self.subdomains:
            raise ValueError(f"no subdomain {name!r}; subdomains: {sorted(self.subdomains)}"
                             f", boundary groups: {sorted(self.boundaries)}")
        return self.subdomains[name]

    def nodes(self, name: str) -> np.ndarray:
        """Vertex indices of the boundary group or subdomain ``name``."""
        if name in self.boundaries:
            return np.unique(self.mesh.facets[:, self.boundaries[name]])
        return np.unique(self.mesh.t[:, self.elements(name)])

    def with_groups(self, boundaries=None, subdomains=None) -> "FEMesh":
        """A copy with extra groups added (e.g. built with :func:`facets_where`)."""
        return FEMesh(self.mesh, {**self.boundaries, **(boundaries or {})},
                      {**self.subdomains, **(subdomains or {})}, self.edge_nodes)


def facets_where(mesh: skfem.Mesh, condition) -> np.ndarray:
    """Boundary facet indices whose midpoint satisfies ``condition(x)`` (x: (dim, n) array, m)."""
    return mesh.facets_satisfying(condition, boundaries_only=True)


def corner_jacobians(mesh: skfem.Mesh) -> np.ndarray:
    """(n_elements, n_corners) determinant of the reference-to-physical map at each element's
    corners (constant per simplex; m^dim per unit reference measure)."""
    ref = np.asarray(mesh.elem().doflocs, dtype=float)  # (n_corners, dim), coordinates 0 or 1
    dim = ref.shape[1]
    simplex = isinstance(mesh, (skfem.MeshTri, skfem.MeshTet))
    dets = []
    for c in range(1 if simplex else len(ref)):
        # the (multi)linear map's Jacobian at a corner is made of its edges to the corners that
        # differ from it in one reference coordinate
        columns = []
        for k in range(dim):
            target = ref[c].copy()
            target[k] = 1.0 - target[k]
            n = int(np.flatnonzero(np.all(ref == target, axis=1))[0])
            columns.append((mesh.p[:, mesh.t[n]] - mesh.p[:, mesh.t[c]]) * (target[k] - ref[c, k]))
        dets.append(np.linalg.det(np.stack(columns, axis=-1).transpose(1, 0, 2)))
    return np.stack(dets, axis=1)


def _check_cells(mesh: skfem.Mesh) -> None:
    """Reject degenerate cells (zero area or volume) and, for quadrilaterals and hexahedra,
    cells whose map folds over (Jacobian changing sign inside: non-convex, twisted or
    self-intersecting). A cell's turn alone is fine: scikit-fem sorts simplex vertices and
    integrates with |det J|; cells inverted into their neighbours are refused by
    :func:`~flexfem.fem.mesh_check.check_facet_sharing`."""
    det = corner_jacobians(mesh)
    # relative to each element's own size, so that strongly graded meshes pass
    diameter = np.max([np.linalg.norm(mesh.p[:, mesh.t[i]] - mesh.p[:, mesh.t[j]], axis=0)
                       for i, j in combinations(range(mesh.t.shape[0]), 2)], axis=0)
    degenerate = np.any(np.abs(det) <= 1e-10 * diameter[:, None] ** mesh.dim(), axis=1)
    if np.any(degenerate):
        raise ValueError(f"the mesh has {int(np.sum(degenerate))} degenerate (zero-area/volume) "
                         f"elements, e.g. element {int(np.flatnonzero(degenerate)[0])}; remesh")
    folded = np.any(np.sign(det) != np.sign(det[:, :1]), axis=1)
    if np.any(folded):
        raise ValueError(f"the mesh has {int(np.sum(folded))} folded elements (Jacobian changes "
                         f"sign: non-convex or self-intersecting), e.g. element "
                         f"{int(np.flatnonzero(folded)[0])}; check the vertex order or remesh")


def _facet_keys(facet_nodes: np.ndarray, n_vertices: int) -> np.ndarray:
    """One int64 key per facet from its three smallest sorted vertex indices."""
    s = np.sort(facet_nodes, axis=0)[:3].astype(np.int64)
    if s.shape[0] == 2:
        return s[0] * n_vertices + s[1]
    return (s[0] * n_vertices + s[1]) * n_vertices + s[2]


def _match_facets(mesh: skfem.Mesh, facet_nodes: np.ndarray, name: str) -> np.ndarray:
    n = mesh.p.shape[1]
    all_keys = _facet_keys(mesh.facets, n)
    order = np.argsort(all_keys)
    keys = _facet_keys(facet_nodes, n)
    pos = np.searchsorted(all_keys, keys, sorter=order)
    pos = np.clip(pos, 0, len(order) - 1)
    found = order[pos]
    if not np.all(all_keys[found] == keys):
        raise ValueError(f"boundary group {name!r} has elements that are not facets of the mesh")
    return np.unique(found)


def mesh_from_gmsh(gmsh) -> FEMesh:
    """Read the current gmsh model's mesh (call inside :func:`gmsh_session` after
    ``gmsh.model.mesh.generate``).

    The highest-dimensional elements form the mesh; physical groups of that dimension become
    subdomains, those one dimension lower become boundaries. Higher-order gmsh elements are
    read by their corner nodes (quadratic fields come from the basis, on straight-sided cells).
    """
    dim = gmsh.model.getDimension()
    types, elem_tags, elem_nodes = gmsh.model.mesh.getElements(dim)
    if len(types) == 0:
        raise ValueError("the gmsh model has no mesh; call gmsh.model.mesh.generate(dim) first")
    if len(set(types)) != 1 or types[0] not in _GMSH_CELLS:
        raise ValueError(f"unsupported or mixed gmsh element types {list(types)}; "
                         "use triangles, quadrangles, tetrahedra or hexahedra only")
    mesh_type, n_corner = _GMSH_CELLS[types[0]]
    n_per = len(elem_nodes[0]) // len(elem_tags[0])
    conn = np.asarray(elem_nodes[0], dtype=np.int64).reshape(-1, n_per)[:, :n_corner]

    node_tags, coords, _ = gmsh.model.mesh.getNodes()
    coords = np.asarray(coords).reshape(-1, 3)
    used = np.unique(conn)
    tag_to_index = np.full(int(max(node_tags.max(), used.max())) + 1, -1, dtype=np.int64)
    tag_to_index[used] = np.arange(len(used))
    coord_of_tag = np.zeros((tag_to_index.size, 3))
    coord_of_tag[node_tags] = coords
    p = coord_of_tag[used, :dim].T.copy()
    t = tag_to_index[conn].T.copy()
    if mesh_type is skfem.MeshHex:
        t = t[_HEX_FROM_GMSH]
    mesh = mesh_type(p, t)

    element_index = np.full(int(np.max(elem_tags[0])) + 1, -1, dtype=np.int64)
    element_index[np.asarray(elem_tags[0], dtype=np.int64)] = np.arange(len(elem_tags[0]))

    boundaries, subdomains = {}, {}
    for gdim, tag in gmsh.model.getPhysicalGroups():
        name = gmsh.model.getPhysicalName(gdim, tag) or f"group{tag}"
        if gdim == dim:
            tags = [np.asarray(gmsh.model.mesh.getElements(dim, e)[1][0], dtype=np.int64)
                    for e in gmsh.model.getEntitiesForPhysicalGroup(gdim, tag)]
            subdomains[name] = np.unique(element_index[np.concatenate(tags)])
        elif gdim == dim - 1:
            nodes = []
            for entity in gmsh.model.getEntitiesForPhysicalGroup(gdim, tag):
                ftypes, _, fnodes = gmsh.model.mesh.getElements(gdim, entity)
                for ftype, fn in zip(ftypes, fnodes):
                    if int(ftype) not in _GMSH_FACET_CORNERS:
                        raise ValueError(f"boundary group {name!r}: unsupported gmsh facet "
                                         f"element type {int(ftype)}")
                    n_corner_f = _GMSH_FACET_CORNERS[int(ftype)]
                    n_per_f = gmsh.model.mesh.getElementProperties(int(ftype))[3]
                    nodes.append(np.asarray(fn, dtype=np.int64).reshape(-1, n_per_f)[:, :n_corner_f])
            if nodes:
                facet_nodes = tag_to_index[np.concatenate(nodes)].T
                boundaries[name] = _match_facets(mesh, facet_nodes, name)
    return FEMesh(mesh, boundaries, subdomains)


def read_mesh(path) -> FEMesh:
    """Read a mesh file with its physical groups: ``.msh`` through gmsh, other formats
    (e.g. ``.vtu``, ``.xdmf``) through meshio, using their cell sets as groups (or, in a
    ``.vtu`` from :func:`~flexfem.fem.export.write_mesh`, its 0/1 group arrays). Vertices in
    no element are dropped."""
    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"mesh file {path} does not exist")
    if path.suffix == ".msh":
        with gmsh_session() as gmsh:
            gmsh.open(str(path))
            return mesh_from_gmsh(gmsh)
    m = meshio.read(path)
    if not m.cell_sets:  # write_mesh's .vtu: one 0/1 cell-data array per group
        m.cell_sets = {name: [np.flatnonzero(a) for a in arrays]
                       for name, arrays in m.cell_data.items()
                       if name != "group_id" and not name.startswith("gmsh:")
                       and all(np.issubdtype(np.asarray(a).dtype, np.integer) and
                               np.all((np.asarray(a) == 0) | (np.asarray(a) == 1)) for a in arrays)}
    mesh = skfem.io.meshio.from_meshio(m)  # cell sets become groups
    return drop_unused_vertices(mesh, {k: np.asarray(v) for k, v in (mesh.boundaries or {}).items()},
                                {k: np.asarray(v) for k, v in (mesh.subdomains or {}).items()})


def drop_unused_vertices(mesh: skfem.Mesh, boundaries=None, subdomains=None) -> FEMesh:
    """A FEMesh of ``mesh`` without the vertices that belong to no element (meshio keeps
    them), vertices renumbered in their order and boundary groups (facet indices) matched
    anew."""
    boundaries, subdomains = dict(boundaries or {}), dict(subdomains or {})
    unused = unused_vertices(mesh)
    if len(unused) == 0:
        return FEMesh(mesh, boundaries, subdomains)
    keep = np.setdiff1d(np.arange(mesh.p.shape[1]), unused)
    new_index = np.full(mesh.p.shape[1], -1, dtype=np.int64)
    new_index[keep] = np.arange(len(keep))
    t = new_index[mesh.t]
    if isinstance(mesh, skfem.MeshHex):  # skfem's own vertex order is kept as it is
        new = type(mesh)(mesh.p[:, keep], t, validate=False)
    else:
        new = type(mesh)(mesh.p[:, keep], t)
    groups = {name: _match_facets(new, new_index[mesh.facets[:, facets]], name)
              for name, facets in boundaries.items()}
    return FEMesh(new, groups, subdomains)
