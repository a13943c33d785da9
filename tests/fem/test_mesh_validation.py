"""Meshes that would give silently wrong answers are refused, naming the elements; unused
vertices are dropped on import; a mesh reports its own element size."""
import meshio
import numpy as np
import pytest
import skfem

from meshes import beam_2d
from flexfem.fem import (FEMesh, Fixed, Force, Model, PlaneStress, facets_where, read_mesh,
                         solve_static, write_mesh)
from flexfem.fem.mesh import drop_unused_vertices


def two_squares():
    """[0, 2] x [0, 1] as four counter-clockwise triangles, in meshio's form."""
    p = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [2, 0], [2, 1]], dtype=float)
    t = np.array([[0, 1, 2], [0, 2, 3], [1, 4, 5], [1, 5, 2]])
    return p, t


def test_cells_of_either_turn_are_accepted(tmp_path, steel):
    """A cell listed clockwise among counter-clockwise ones is no error (a gmsh mesh of
    several surfaces has both turns, one per surface normal): scikit-fem integrates with
    |det J|, so the answer is the same as with every cell turned the same way."""
    p, t = two_squares()
    mixed = t.copy()
    mixed[2] = mixed[2, ::-1]
    meshio.write(tmp_path / "m.vtu", meshio.Mesh(p, [("triangle", mixed)]))
    assert read_mesh(tmp_path / "m.vtu").mesh.t.shape[1] == 4
    quads = skfem.MeshQuad.init_tensor(np.linspace(0, 2, 5), np.linspace(0, 1, 3))
    flipped = quads.t.copy()
    flipped[:, 4] = flipped[::-1, 4]
    u = []
    for cells in (quads.t, flipped):
        m = skfem.MeshQuad(quads.p, cells)
        femesh = FEMesh(m, {"left": facets_where(m, lambda x: np.isclose(x[0], 0.0)),
                            "right": facets_where(m, lambda x: np.isclose(x[0], 2.0))})
        model = Model(femesh, steel, PlaneStress(0.01), order=2)
        u.append(solve_static(model, [Fixed("left")], [Force("right", (0.0, -1e3))]).u)
    assert np.allclose(u[0], u[1], rtol=0, atol=1e-10 * np.abs(u[0]).max())


def test_an_inverted_quadrilateral_is_refused():
    mesh = skfem.MeshQuad.init_tensor(np.linspace(0, 1, 4), np.linspace(0, 1, 4))
    p = mesh.p.copy()
    inner = int(np.argmin(np.hypot(p[0] - 1 / 3, p[1] - 1 / 3)))
    p[:, inner] = [0.8, 0.8]  # through its cells' far sides
    with pytest.raises(ValueError, match="folded elements|the mesh overlaps"):
        FEMesh(skfem.MeshQuad(p, mesh.t))


def test_a_tangled_triangle_mesh_overlaps():
    # a vertex of the middle pushed across its neighbours' shared edge: sorted triangle
    # vertices hide the orientation, the sides of the shared facets do not
    mesh = skfem.MeshTri.init_tensor(np.linspace(0, 1, 4), np.linspace(0, 1, 4))
    p = mesh.p.copy()
    centre = int(np.argmin(np.hypot(p[0] - 1 / 3, p[1] - 1 / 3)))
    p[:, centre] = [0.75, 0.75]
    with pytest.raises(ValueError, match=r"the mesh overlaps: \d+ pairs of elements .*: elements \[\d+"):
        FEMesh(skfem.MeshTri(p, mesh.t))


def test_a_tangled_tetrahedral_mesh_overlaps():
    mesh = skfem.MeshTet.init_tensor(*[np.linspace(0, 1, 4)] * 3)
    p = mesh.p.copy()
    inner = int(np.argmin(np.linalg.norm(p - 1 / 3, axis=0)))
    p[:, inner] = 0.9  # pushed through the cells around it
    with pytest.raises(ValueError, match="the mesh overlaps"):
        FEMesh(skfem.MeshTet(p, mesh.t))


def test_a_facet_of_three_elements_overlaps():
    p = np.array([[0, 1, 0.5, 0.5, 0.3], [0, 0, 1, -1, 0.8]], dtype=float)
    t = np.array([[0, 1, 2], [0, 3, 1], [0, 1, 4]]).T
    with pytest.raises(ValueError, match=r"1 facets belong to 3 or more elements .*elements \[0, 1, 2\]"):
        FEMesh(skfem.MeshTri(p, t))


def test_a_hanging_node_in_2d_is_named():
    p = np.array([[0, 1, 1, 0, 2, 2, 1], [0, 0, 1, 1, 0, 1, 0.5]], dtype=float)
    t = np.array([[0, 1, 2], [0, 2, 3], [1, 4, 6], [4, 5, 6], [5, 2, 6]]).T
    with pytest.raises(ValueError, match=r"not conforming: vertices \[6\] lie on an edge or face "
                                         r"of elements \[0\]"):
        FEMesh(skfem.MeshTri(p, t))


def test_a_hanging_node_in_3d_is_found():
    """A box of tetrahedra 1 x 1 cells in y, z beside one of 2 x 2 cells, sharing the plane
    x = 1 and its corner vertices only."""
    left = skfem.MeshTet.init_tensor(np.linspace(0, 1, 2), *[np.linspace(0, 1, 2)] * 2)
    right = skfem.MeshTet.init_tensor(np.linspace(1, 2, 2), *[np.linspace(0, 1, 3)] * 2)
    p = np.hstack([left.p, right.p])
    t = np.hstack([left.t, right.t + left.p.shape[1]])
    unique, inverse = np.unique(np.round(p, 12), axis=1, return_inverse=True)
    with pytest.raises(ValueError, match=r"not conforming: vertices \[5, 7, 8, 9, 11\] .*\(hanging nodes\)"):
        FEMesh(skfem.MeshTet(unique, inverse.ravel()[t]))


def test_unused_vertices_are_dropped_on_import_and_named_otherwise(tmp_path):
    femesh = beam_2d(1.0, 0.1, 0.05)
    path = write_mesh(femesh, tmp_path / "beam.vtu")
    m = meshio.read(path)
    extra = np.vstack([m.points[:5], [[5.0, 5.0, 0.0]], m.points[5:]])  # a stray vertex 5
    shift = lambda c: np.where(c >= 5, c + 1, c)  # noqa: E731
    meshio.write(path, meshio.Mesh(extra, [(b.type, shift(b.data)) for b in m.cells],
                                   cell_data=m.cell_data))
    back = read_mesh(path)
    assert set(back.boundaries) == set(femesh.boundaries)
    assert set(back.subdomains) == set(femesh.subdomains)
    assert back.mesh.p.shape == femesh.mesh.p.shape
    for name in femesh.boundaries:  # the same facets, by their coordinates
        mid = lambda f: np.sort(f.mesh.p[:, f.mesh.facets[:, f.boundaries[name]]].mean(1), 1)  # noqa: E731
        assert np.allclose(mid(back), mid(femesh))
    with pytest.raises(ValueError, match=r"1 vertices that belong to no element: \[5\]"):
        FEMesh(skfem.MeshTri(extra[:, :2].T, shift(femesh.mesh.t)))
    fixed = drop_unused_vertices(skfem.MeshTri(extra[:, :2].T, shift(femesh.mesh.t)))
    assert fixed.mesh.p.shape[1] == femesh.mesh.p.shape[1]


def test_characteristic_size_is_the_mean_edge_length():
    n = 4
    mesh = FEMesh(skfem.MeshTri.init_tensor(*[np.linspace(0, 1, n + 1)] * 2))
    h = 1.0 / n
    straight, diagonal = 2 * n * (n + 1), n * n
    expected = (straight * h + diagonal * np.sqrt(2) * h) / (straight + diagonal)
    assert mesh.characteristic_size == pytest.approx(expected, rel=1e-12)
    assert mesh.edge_lengths.max() == pytest.approx(np.sqrt(2) * h, rel=1e-12)
    box = FEMesh(skfem.MeshHex.init_tensor(*[np.linspace(0, 2, 3)] * 3))
    assert box.characteristic_size == pytest.approx(1.0, rel=1e-12)  # hex edges only
    assert beam_2d(1.0, 0.1, 0.02).characteristic_size == pytest.approx(0.02, rel=0.25)
