"""gmsh physical groups arrive as named skfem boundaries and subdomains."""
import numpy as np
import pytest
import skfem
from meshes import beam_2d, beam_3d
from flexfem.fem import gmsh_session, mesh_from_gmsh, read_mesh


@pytest.mark.parametrize("build, cell", [
    (lambda: beam_2d(1.0, 0.1, 0.05), skfem.MeshTri),
    (lambda: beam_2d(1.0, 0.1, 0.05, quads=True), skfem.MeshQuad),
    (lambda: beam_3d(1.0, 0.1, 0.1, 0.05), skfem.MeshTet),
    (lambda: beam_3d(1.0, 0.1, 0.1, 0.05, hexes=True), skfem.MeshHex),
])
def test_groups_become_boundaries_and_subdomains(build, cell):
    mesh = build()
    assert isinstance(mesh.mesh, cell)
    p = mesh.mesh.p
    assert np.allclose(p[0, mesh.nodes("fixed")], 0.0)
    assert np.allclose(p[0, mesh.nodes("tip")], 1.0)
    assert len(mesh.elements("body")) == mesh.mesh.t.shape[1]
    # every facet at x = 0 is in the group, and nothing else
    at_root = mesh.mesh.facets_satisfying(lambda x: np.isclose(x[0], 0.0), boundaries_only=True)
    assert np.array_equal(np.sort(mesh.facets("fixed")), np.sort(at_root))


def test_hex_elements_are_valid():
    mesh = beam_3d(1.0, 0.1, 0.1, 0.05, hexes=True)
    basis = skfem.Basis(mesh.mesh, skfem.ElementHex1())
    assert np.isclose(basis.dx.sum(), 1.0 * 0.1 * 0.1)  # positive Jacobians add up to the volume


def test_unknown_group_lists_existing_names():
    mesh = beam_2d(1.0, 0.1, 0.05)
    with pytest.raises(ValueError, match=r"no boundary group 'output'.*'fixed', 'tip'"):
        mesh.facets("output")
    with pytest.raises(ValueError, match="subdomains: \\['body'\\]"):
        mesh.elements("arm")


def test_msh_file_round_trip(tmp_path):
    path = tmp_path / "beam.msh"
    with gmsh_session() as gmsh:
        s = gmsh.model.occ.addRectangle(0, 0, 0, 1.0, 0.1)
        gmsh.model.occ.synchronize()
        gmsh.model.addPhysicalGroup(2, [s], name="body")
        gmsh.model.addPhysicalGroup(1, [4], name="fixed")
        gmsh.option.setNumber("Mesh.MeshSizeMax", 0.05)
        gmsh.model.mesh.generate(2)
        direct = mesh_from_gmsh(gmsh)
        gmsh.write(str(path))
    again = read_mesh(path)
    assert np.allclose(again.mesh.p, direct.mesh.p)
    assert np.array_equal(again.mesh.t, direct.mesh.t)
    assert np.array_equal(again.facets("fixed"), direct.facets("fixed"))


def test_missing_file_and_empty_model():
    with pytest.raises(FileNotFoundError, match="does not exist"):
        read_mesh("/nonexistent/mesh.msh")
    with gmsh_session() as gmsh:
        gmsh.model.occ.addRectangle(0, 0, 0, 1.0, 0.1)
        gmsh.model.occ.synchronize()
        with pytest.raises(ValueError, match="no mesh"):
            mesh_from_gmsh(gmsh)


def _serendipity_box(dim, order2):
    """Transfinite recombined unit square (dim 2) or cube (dim 3), groups fixed (x = 0)/body;
    with ``order2`` set to gmsh's incomplete second order: 8-node quadrangles (type 16) and
    20-node hexahedra (type 17). Returns (FEMesh, gmsh element types of the cells)."""
    with gmsh_session() as gmsh:
        if dim == 2:
            e = gmsh.model.occ.addRectangle(0, 0, 0, 1.0, 0.5)
        else:
            e = gmsh.model.occ.addBox(0, 0, 0, 1.0, 0.5, 0.5)
        gmsh.model.occ.synchronize()
        gmsh.model.addPhysicalGroup(dim, [e], name="body")
        for _, tag in gmsh.model.getBoundary([(dim, e)], oriented=False):
            if np.isclose(gmsh.model.occ.getCenterOfMass(dim - 1, tag)[0], 0.0):
                gmsh.model.addPhysicalGroup(dim - 1, [tag], name="fixed")
        for _, tag in gmsh.model.getEntities(1):
            gmsh.model.mesh.setTransfiniteCurve(tag, 4)
        for _, tag in gmsh.model.getEntities(2):
            gmsh.model.mesh.setTransfiniteSurface(tag)
            gmsh.model.mesh.setRecombine(2, tag)
        if dim == 3:
            gmsh.model.mesh.setTransfiniteVolume(e)
        gmsh.model.mesh.generate(dim)
        if order2:
            gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)
            gmsh.model.mesh.setOrder(2)
        types = list(gmsh.model.mesh.getElementTypes(dim))
        return mesh_from_gmsh(gmsh), types


@pytest.mark.parametrize("dim, gmsh_type, cell", [(2, 16, skfem.MeshQuad), (3, 17, skfem.MeshHex)])
def test_serendipity_cells_are_read_by_their_corners(dim, gmsh_type, cell):
    quadratic, types = _serendipity_box(dim, order2=True)
    assert types == [gmsh_type]
    linear, _ = _serendipity_box(dim, order2=False)
    assert isinstance(quadratic.mesh, cell)
    # the same corners and cells as the first-order mesh of the same geometry
    assert np.allclose(quadratic.mesh.p, linear.mesh.p)
    assert np.array_equal(quadratic.mesh.t, linear.mesh.t)
    assert np.array_equal(quadratic.facets("fixed"), linear.facets("fixed"))
    # positive Jacobians: the cells add up to the area / volume (vertex order is skfem's)
    element = skfem.ElementQuad1() if dim == 2 else skfem.ElementHex1()
    assert np.isclose(skfem.Basis(quadratic.mesh, element).dx.sum(), 0.5 if dim == 2 else 0.25)
    assert np.allclose(quadratic.mesh.p[0, quadratic.nodes("fixed")], 0.0)
    assert len(quadratic.facets("fixed")) == (9 if dim == 3 else 3)  # 3 x 3 faces, 3 edges
