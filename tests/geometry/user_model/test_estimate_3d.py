"""The mesh estimate of a 3-D geometry reads the sizes on its volumes' curves (through their
surfaces): a plate of 2 cm elements is estimated within a small factor of what gmsh makes,
not from its bounding box (which gave ~300 times too few)."""
from flexfem.fem import gmsh_session
from flexfem.fem.budget import NODES_PER_ELEMENT
from flexfem.geometry.user_model.estimate import estimate_geometry_mesh


def test_a_plate_is_estimated_from_its_element_size():
    with gmsh_session("plate") as gmsh:
        gmsh.model.occ.addBox(0, 0, 0, 1.0, 0.042, 1.0)
        gmsh.model.occ.synchronize()
        gmsh.model.mesh.setSize(gmsh.model.getEntities(0), 0.02)
        estimate = estimate_geometry_mesh(gmsh, 3, 2)
        gmsh.model.mesh.generate(3)
        tetrahedra = len(gmsh.model.mesh.getElements(3)[1][0])
    dofs = 3 * NODES_PER_ELEMENT[(3, 2)] * tetrahedra
    assert 0.7 < estimate["dofs"] / dofs < 3
