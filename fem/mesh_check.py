"""Mesh checks that catch silent wrong answers: inverted, overlapping and non-conforming
elements, and vertices that belong to no element. Each raises ValueError naming the elements
or vertices (at most ``_SHOWN`` of them) so that the mesh can be repaired.

Inverted and tangled cells are found geometrically, not by the sign of det J: the two
elements on an interior facet must lie on opposite sides of it, and no facet may belong to
three or more elements. The sign of det J alone says nothing: scikit-fem integrates with
|det J| and sorts triangle vertices, and a valid gmsh mesh of several surfaces has cells of both
turns (each surface meshed along its own normal). A hanging node is a boundary vertex inside
another boundary facet.
"""
from itertools import combinations

import numpy as np
import skfem

from .near_points import pairs_within

_SHOWN = 10   # elements or vertices named in a message
_TOL = 1e-9   # relative to an element's size: on a facet, inside it


def _name(indices) -> str:
    indices = np.asarray(indices)
    more = f" and {len(indices) - _SHOWN} more" if len(indices) > _SHOWN else ""
    return f"{np.asarray(indices[:_SHOWN]).tolist()}{more}"


def check_facet_sharing(mesh: skfem.Mesh) -> None:
    """Refuse facets shared by three or more elements and interior facets whose two elements
    lie on the same side (overlapping or folded elements)."""
    count = np.bincount(mesh.t2f.ravel(), minlength=mesh.facets.shape[1])
    crowded = np.flatnonzero(count > 2)
    if len(crowded):
        elements = np.flatnonzero(np.any(np.isin(mesh.t2f, crowded), axis=0))
        raise ValueError(f"the mesh overlaps: {len(crowded)} facets belong to 3 or more elements "
                         f"each (a conforming mesh has 2 on interior facets, 1 on the boundary): "
                         f"elements {_name(elements)}")
    interior = np.flatnonzero(mesh.f2t[1] >= 0)
    corners = mesh.p[:, mesh.facets[:, interior]]  # (dim, n_corners, n)
    origin = corners.mean(axis=1)
    if mesh.dim() == 2:
        edge = corners[:, 1] - corners[:, 0]
        normal = np.array([-edge[1], edge[0]])
    else:
        normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0], axis=0)
    centroid = mesh.p[:, mesh.t].mean(axis=1)
    sides = [np.sum(normal * (centroid[:, mesh.f2t[k, interior]] - origin), axis=0)
             for k in (0, 1)]
    same = np.flatnonzero(sides[0] * sides[1] > 0)
    if len(same):
        pairs = mesh.f2t[:, interior[same]].T
        raise ValueError(f"the mesh overlaps: {len(same)} pairs of elements sharing a facet lie "
                         f"on the same side of it (inverted, folded or tangled elements): "
                         f"elements {_name(np.unique(pairs))}, in pairs {_name(pairs.tolist())}; "
                         "remesh")


def _on_facet(points: np.ndarray, corners: np.ndarray) -> np.ndarray:
    """Whether each point ((dim, n)) lies inside the facet with ``corners`` ((dim, k, n)),
    away from its corners, within _TOL of the facet's size."""
    dim = points.shape[0]
    size = np.max(np.linalg.norm(corners - corners[:, :1], axis=0), axis=0)
    if dim == 2:
        a, b = corners[:, 0], corners[:, 1]
        s = np.sum((points - a) * (b - a), axis=0) / np.sum((b - a) ** 2, axis=0)
        off = np.abs((b - a)[0] * (points - a)[1] - (b - a)[1] * (points - a)[0]) / size
        return (off <= _TOL * size) & (s > _TOL) & (s < 1 - _TOL)
    inside = np.zeros(points.shape[1], dtype=bool)
    for i, j, k in combinations(range(corners.shape[1]), 3):
        a, e1, e2 = corners[:, i], corners[:, j] - corners[:, i], corners[:, k] - corners[:, i]
        n = np.cross(e1, e2, axis=0)
        area2 = np.linalg.norm(n, axis=0)
        off = np.abs(np.sum(n * (points - a), axis=0)) / np.maximum(area2, 1e-300)
        d = points - a
        # barycentric coordinates of the projection (Gram system of e1, e2)
        g11, g12, g22 = (np.sum(e1 * e1, 0), np.sum(e1 * e2, 0), np.sum(e2 * e2, 0))
        r1, r2 = np.sum(d * e1, 0), np.sum(d * e2, 0)
        det = g11 * g22 - g12 ** 2
        b1, b2 = (g22 * r1 - g12 * r2) / det, (g11 * r2 - g12 * r1) / det
        bary = np.stack([1 - b1 - b2, b1, b2])
        inside |= (off <= _TOL * size) & np.all(bary >= -_TOL, axis=0) & \
            (bary.max(axis=0) < 1 - _TOL)
    return inside


def check_hanging_nodes(mesh: skfem.Mesh) -> None:
    """Refuse non-conforming meshes: a vertex lying inside (not at a corner of) a boundary
    facet, as a hanging node on a coarse element's edge or face leaves it."""
    boundary = mesh.boundary_facets()
    if len(boundary) == 0:
        return
    facets = mesh.facets[:, boundary]
    vertices = np.unique(facets)
    corners = mesh.p[:, facets]  # (dim, k, n)
    centre = corners.mean(axis=1)
    radius = np.max(np.linalg.norm(corners - centre[:, None], axis=0), axis=0) * (1 + 1e-6)
    f_idx, v_idx = pairs_within(mesh.p[:, vertices], centre, radius)
    v_idx = vertices[v_idx]
    own = np.any(facets[:, f_idx] == v_idx, axis=0)
    f_idx, v_idx = f_idx[~own], v_idx[~own]
    hit = _on_facet(mesh.p[:, v_idx], corners[:, :, f_idx])
    if np.any(hit):
        elements = np.unique(mesh.f2t[0, boundary[f_idx[hit]]])
        raise ValueError(f"the mesh is not conforming: vertices {_name(np.unique(v_idx[hit]))} "
                         f"lie on an edge or face of elements {_name(elements)} without being "
                         "their vertices (hanging nodes); refine those elements or remesh")


def unused_vertices(mesh: skfem.Mesh) -> np.ndarray:
    """Indices of vertices that belong to no element."""
    used = np.zeros(mesh.p.shape[1], dtype=bool)
    used[mesh.t.ravel()] = True
    return np.flatnonzero(~used)


def check_unused_vertices(mesh: skfem.Mesh) -> None:
    unused = unused_vertices(mesh)
    if len(unused):
        raise ValueError(f"the mesh has {len(unused)} vertices that belong to no element: "
                         f"{_name(unused)}; they would be unconstrained DOFs. read_mesh drops "
                         "them; for a mesh built by hand use drop_unused_vertices")
