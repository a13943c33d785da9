"""Small meshes for the FEM tests, built with gmsh and read back with their named groups."""
import numpy as np
from flexfem.fem import gmsh_session, mesh_from_gmsh


def _name_box_faces(gmsh, dim, entity, length):
    """Physical groups 'fixed' (x = 0) and 'tip' (x = length) and 'body'."""
    gmsh.model.addPhysicalGroup(dim, [entity], name="body")
    for _, tag in gmsh.model.getBoundary([(dim, entity)], oriented=False):
        x = gmsh.model.occ.getCenterOfMass(dim - 1, tag)[0]
        if np.isclose(x, 0.0):
            gmsh.model.addPhysicalGroup(dim - 1, [tag], name="fixed")
        elif np.isclose(x, length):
            gmsh.model.addPhysicalGroup(dim - 1, [tag], name="tip")


def beam_2d(length, height, size, quads=False):
    """Rectangle [0, length] x [0, height] (m), groups fixed/tip/body."""
    with gmsh_session() as gmsh:
        s = gmsh.model.occ.addRectangle(0, 0, 0, length, height)
        gmsh.model.occ.synchronize()
        _name_box_faces(gmsh, 2, s, length)
        gmsh.option.setNumber("Mesh.MeshSizeMax", size)
        if quads:
            gmsh.option.setNumber("Mesh.RecombineAll", 1)
            gmsh.option.setNumber("Mesh.Algorithm", 8)
        gmsh.model.mesh.generate(2)
        return mesh_from_gmsh(gmsh)


def beam_3d(length, height, width, size, hexes=False):
    """Box [0, length] x [0, height] x [0, width] (m), groups fixed/tip/body."""
    with gmsh_session() as gmsh:
        v = gmsh.model.occ.addBox(0, 0, 0, length, height, width)
        gmsh.model.occ.synchronize()
        _name_box_faces(gmsh, 3, v, length)
        if hexes:
            for (dim, tag) in gmsh.model.getEntities(1):
                lo = gmsh.model.getBoundingBox(dim, tag)
                extent = max(lo[3] - lo[0], lo[4] - lo[1], lo[5] - lo[2])
                gmsh.model.mesh.setTransfiniteCurve(tag, max(2, int(round(extent / size)) + 1))
            for (dim, tag) in gmsh.model.getEntities(2):
                gmsh.model.mesh.setTransfiniteSurface(tag)
                gmsh.model.mesh.setRecombine(dim, tag)
            gmsh.model.mesh.setTransfiniteVolume(v)
        else:
            gmsh.option.setNumber("Mesh.MeshSizeMax", size)
        gmsh.model.mesh.generate(3)
        return mesh_from_gmsh(gmsh)


def rod_3d(length, radius, around):
    """Round rod along x from 0 to ``length`` (m) of ``radius`` (m), ``around`` elements
    round its circle (gmsh's curvature-based size), groups fixed/tip/body."""
    with gmsh_session() as gmsh:
        v = gmsh.model.occ.addCylinder(0, 0, 0, length, 0, 0, radius)
        gmsh.model.occ.synchronize()
        _name_box_faces(gmsh, 3, v, length)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", around)
        gmsh.option.setNumber("Mesh.MeshSizeMax", radius)
        gmsh.model.mesh.generate(3)
        return mesh_from_gmsh(gmsh)
