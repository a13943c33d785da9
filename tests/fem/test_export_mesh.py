"""Mesh export: .msh/.vtu/.xdmf/.inp round trips keep nodes, elements and group membership."""
import re

import meshio
import numpy as np
import pytest
import skfem
from meshes import beam_2d, beam_3d
from flexfem.fem import read_mesh
from flexfem.fem.abaqus import (
    abaqus_mesh,
    edge_nodes,
    element_type,
    oriented_corners,
    write_inp,
)
from flexfem.fem.export import MESH_FORMATS, group_tags, write_mesh


@pytest.fixture(scope="module")
def tri():
    return beam_2d(1.0, 0.2, 0.1)


@pytest.fixture(scope="module")
def tet():
    return beam_3d(1.0, 0.2, 0.2, 0.1)


@pytest.fixture(scope="module")
def hexes():
    return beam_3d(1.0, 0.2, 0.2, 0.1, hexes=True)


@pytest.fixture(scope="module")
def quads():
    return beam_2d(1.0, 0.2, 0.1, quads=True)


def _same_groups(a, b):
    """Group membership compared by vertex coordinates (indices may be renumbered)."""
    for name in b.boundaries:
        pa = np.unique(np.round(a.mesh.p[:, a.nodes(name)].T, 12), axis=0)
        pb = np.unique(np.round(b.mesh.p[:, b.nodes(name)].T, 12), axis=0)
        assert np.array_equal(pa, pb), name
    for name in b.subdomains:
        assert len(a.subdomains[name]) == len(b.subdomains[name]), name


@pytest.mark.parametrize("order", [1, 2])
@pytest.mark.parametrize("which", ["tri", "tet", "hexes", "quads"])
def test_msh_round_trip_through_read_mesh(which, order, tmp_path, request):
    femesh = request.getfixturevalue(which)
    path = write_mesh(femesh, tmp_path / "m.msh", order=order)
    if order == 2 and which in ("hexes", "quads"):
        # flexfem.fem.read_mesh does not know gmsh's 8-node quad / 20-node hexahedron (types 16,
        # 17): read with meshio and check the quadratic cells are there
        m = meshio.read(path)
        assert m.cells[0].type == ("quad8" if which == "quads" else "hexahedron20")
        assert len(m.cells[0].data) == femesh.mesh.t.shape[1]
        return
    back = read_mesh(path)
    assert back.mesh.p.shape[1] == femesh.mesh.p.shape[1]
    assert back.mesh.t.shape == femesh.mesh.t.shape
    assert sorted(back.group_names) == sorted(femesh.group_names)
    for name in femesh.boundaries:
        assert len(back.boundaries[name]) == len(femesh.boundaries[name])
    _same_groups(back, femesh)


@pytest.mark.parametrize("order", [1, 2])
@pytest.mark.parametrize("which", ["tri", "tet", "hexes"])
def test_vtu_round_trip_keeps_group_arrays(which, order, tmp_path, request):
    femesh = request.getfixturevalue(which)
    m = meshio.read(write_mesh(femesh, tmp_path / "m.vtu", order=order))
    n_nodes = abaqus_mesh(femesh, order).points.shape[0]
    assert len(m.points) == n_nodes
    assert len(m.cells[0].data) == femesh.mesh.t.shape[1]
    tags = group_tags(femesh)
    # meshio's VTU reader merges consecutive blocks of one cell type: stack the facet blocks
    facets = np.vstack([b.data for b in m.cells[1:]])
    group_id = np.concatenate(m.cell_data["group_id"][1:])
    start = 0
    for name in sorted(femesh.boundaries):
        rows = slice(start, start + len(femesh.boundaries[name]))
        start = rows.stop
        assert np.all(group_id[rows] == tags[name])
        member = np.concatenate(m.cell_data[name][1:])
        assert np.array_equal(np.flatnonzero(member), np.arange(rows.start, rows.stop))
        assert not np.any(m.cell_data[name][0])
        # the facet block's nodes are the group's nodes
        assert np.array_equal(np.unique(facets[rows]), abaqus_mesh(femesh, order).node_sets[name])
    assert start == len(facets)
    for name, elements in femesh.subdomains.items():
        assert np.array_equal(np.flatnonzero(m.cell_data[name][0]), np.sort(elements))


def test_xdmf_round_trip_keeps_groups(tet, tmp_path):
    m = meshio.read(write_mesh(tet, tmp_path / "m.xdmf", order=2))
    am = abaqus_mesh(tet, 2)
    assert len(m.points) == am.points.shape[0] and m.cells[0].type == "tetra10"
    assert len(m.cells[0].data) == tet.mesh.t.shape[1]
    for name in tet.boundaries:
        assert np.array_equal(np.flatnonzero(m.point_data[name]), am.node_sets[name])
    assert np.all(m.cell_data["body"][0] == 1)


def test_unknown_extension_lists_known_formats(tri, tmp_path):
    with pytest.raises(ValueError, match=r"\.stl.*\.msh.*\.vtu.*\.xdmf.*\.inp"):
        write_mesh(tri, tmp_path / "m.stl")
    assert set(MESH_FORMATS) == {".msh", ".vtu", ".xdmf", ".inp"}
    with pytest.raises(ValueError, match="order = 3"):
        write_mesh(tri, tmp_path / "m.vtu", order=3)


@pytest.mark.parametrize("which", ["tri", "tet", "hexes", "quads"])
def test_quadratic_nodes_are_the_p2_dof_locations_at_edge_midpoints(which, request):
    femesh = request.getfixturevalue(which)
    am = abaqus_mesh(femesh, 2)
    mesh = femesh.mesh
    corners = am.elements[:, :mesh.t.shape[0]]
    _, pairs = element_type(femesh, 2)
    for k, (i, j) in enumerate(pairs):
        mid = 0.5 * (am.points[corners[:, i]] + am.points[corners[:, j]])
        assert np.allclose(am.points[am.elements[:, mesh.t.shape[0] + k]], mid, atol=1e-14)
    # node k is scalar DOF k of the quadratic basis (vertices, then one node per edge)
    element = {skfem.MeshTri: skfem.ElementTriP2, skfem.MeshTet: skfem.ElementTetP2,
               skfem.MeshHex: skfem.ElementHex2, skfem.MeshQuad: skfem.ElementQuad2}
    e = next(v for t, v in element.items() if isinstance(mesh, t))()
    doflocs = skfem.Basis(mesh, e, intorder=1).doflocs.T
    n = mesh.p.shape[1] + edge_nodes(mesh).shape[1]
    assert np.allclose(am.points[:, :mesh.dim()], doflocs[:n])


@pytest.mark.parametrize("which", ["tri", "tet", "hexes", "quads"])
def test_elements_have_positive_jacobian_in_abaqus_order(which, request):
    mesh = request.getfixturevalue(which).mesh
    t = oriented_corners(mesh)
    p = np.vstack([mesh.p, np.zeros((3 - mesh.dim(), mesh.p.shape[1]))]).T
    if mesh.dim() == 2:
        a, b = p[t[:, 1]] - p[t[:, 0]], p[t[:, -1]] - p[t[:, 0]]
        assert np.all(np.cross(a, b)[:, 2] > 0)
    else:
        far = 3 if t.shape[1] == 4 else 4
        a, b, c = (p[t[:, i]] - p[t[:, 0]] for i in (1, 2 if far == 3 else 3, far))
        assert np.all(np.einsum("ij,ij->i", np.cross(a, b), c) > 0)


def test_inp_follows_calculix_input_rules(tet, tmp_path):
    path = tmp_path / "m.inp"
    am = write_inp(tet, path, order=2)
    text = path.read_text()
    lines = text.splitlines()
    # one text line after *HEADING, then a keyword
    assert lines[0] == "*HEADING" and lines[2].startswith("*")
    # every number field at most 20 characters
    fields = [f.strip() for line in lines if not line.startswith("*") for f in line.split(",")]
    assert max(len(f) for f in fields) <= 20
    assert "TYPE=C3D10," in text and "C3D10MH" not in text
    # at most 16 entries per data line (Abaqus rule), continuation by a trailing comma
    assert max(len(line.rstrip(",").split(",")) for line in lines if not line.startswith("*")) <= 16
    # NSET members parse back to the group nodes
    nsets = re.findall(r"\*NSET, NSET=(\w+)\n((?:[\d, ]+\n)+)", text)
    parsed = {name: np.array(re.findall(r"\d+", body), dtype=int) - 1 for name, body in nsets}
    for name in tet.boundaries:
        assert np.array_equal(parsed[name], am.node_sets[name])
    assert "*ELSET, ELSET=body" in text


def test_inp_c3d20_elements_continue_over_two_lines(hexes, tmp_path):
    path = tmp_path / "h.inp"
    write_inp(hexes, path, order=2)
    text = path.read_text()
    body = text.split("*ELEMENT, TYPE=C3D20, ELSET=EALL\n")[1].split("*")[0].splitlines()
    assert len(body) == 2 * hexes.mesh.t.shape[1]
    assert all(line.endswith(",") for line in body[::2])
    assert all(len(a.split(",")) - 1 + len(b.split(",")) == 21 for a, b in zip(body[::2], body[1::2]))
