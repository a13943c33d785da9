"""A :class:`~flexfem.geometry.flexure_linkage.FlexureLayout` as a 3-D solid: the planar
drawing of :mod:`flexfem.geometry.flexure_drawing` extruded through the part's out-of-plane
thickness.

:func:`mesh_layout_solid` draws and sizes the layout exactly as the 2-D mesh does (structured
flexures, graded links, root fillets), extrudes every surface by ``thickness`` in ``layers``
structured layers (each triangular prism split into three tetrahedra: use order=2 in the
Model) and turns the 2-D groups into 3-D ones: each subdomain's surfaces become its volumes,
each boundary's curves ("fixed", the named edges) the faces swept by them. The mid-plane is
z = 0 (the part spans -thickness/2 <= z <= thickness/2). Lengths in m.
"""
import dataclasses
import math
import numbers

import numpy as np

from ..fem.gmsh_session import gmsh_session
from ..fem.mesh import mesh_from_gmsh
from .flexure_drawing import draw_layout
from .flexure_linkage import FlexureLayout


def check_solid_options(thickness, layers) -> None:
    """Raise ValueError for a thickness that is not a finite number > 0 (m) or fewer than
    one layer."""
    if not (isinstance(thickness, numbers.Real) and math.isfinite(thickness) and thickness > 0):
        raise ValueError(f"thickness = {thickness!r} m must be a finite number > 0")
    if not (isinstance(layers, (int, np.integer)) and not isinstance(layers, bool)
            and layers >= 1):
        raise ValueError(f"layers = {layers!r} must be an integer >= 1 (element layers "
                         "through the thickness)")


def _groups(gmsh) -> dict:
    """{(dim, name): [entity tags]} of the model's physical groups."""
    return {(d, gmsh.model.getPhysicalName(d, t)):
            [int(e) for e in gmsh.model.getEntitiesForPhysicalGroup(d, t)]
            for d, t in gmsh.model.getPhysicalGroups()}


def _extrude(gmsh, thickness: float, layers: int) -> dict:
    """Extrude every surface by ``thickness`` (m) along z in ``layers`` structured layers.
    Returns {surface: its volume}."""
    surfaces = gmsh.model.getEntities(2)
    out = gmsh.model.occ.extrude(surfaces, 0.0, 0.0, thickness, numElements=[layers])
    gmsh.model.occ.synchronize()
    volumes = [t for d, t in out if d == 3]
    if len(volumes) != len(surfaces):
        raise RuntimeError(f"extrusion gave {len(volumes)} volumes for {len(surfaces)} surfaces")
    volume_of = {}
    for (_, s), v in zip(surfaces, volumes):  # gmsh lists the volumes in the input's order
        a = gmsh.model.occ.getCenterOfMass(2, s)
        b = gmsh.model.occ.getCenterOfMass(3, v)
        if math.dist(a[:2], b[:2]) > 1e-6 * thickness:
            raise RuntimeError(f"volume {v} is not the extrusion of surface {s}")
        volume_of[s] = v
    return volume_of


def _swept_faces(gmsh, curves, thickness: float, tol: float) -> list:
    """The faces swept by ``curves`` (planar, z = 0): those whose bounding box is the
    curve's, stretched by ``thickness`` along z (m, to ``tol``; both boxes carry OCC's
    tolerance margin)."""
    boxes = {t: np.array(gmsh.model.getBoundingBox(2, t)) for _, t in gmsh.model.getEntities(2)}
    found = []
    for c in curves:
        want = np.array(gmsh.model.getBoundingBox(1, c))
        want[5] += thickness
        found += [t for t, box in boxes.items() if np.all(np.abs(box - want) <= tol)]
    return found


def draw_layout_solid(gmsh, layout: FlexureLayout, thickness: float, layers: int,
                      n_across: int = 3, aspect: float = 4.0, coarse: float | None = None,
                      root_fillet_radius: float = 0.0) -> dict:
    """Draw ``layout`` (:func:`~flexfem.geometry.flexure_drawing.draw_layout`, same
    arguments), extrude it by ``thickness`` (m) in ``layers`` layers and replace its 2-D
    physical groups by 3-D ones of the same names. Returns the mesh sizes (m) of
    draw_layout."""
    check_solid_options(thickness, layers)
    sizes = draw_layout(gmsh, layout, n_across, aspect, coarse, root_fillet_radius)
    groups = _groups(gmsh)
    gmsh.model.removePhysicalGroups()
    volume_of = _extrude(gmsh, thickness, layers)
    tol = 1e-3 * min(p.width for p in layout.parts)
    for (dim, name), tags in groups.items():
        if dim == 2:
            gmsh.model.addPhysicalGroup(3, [volume_of[t] for t in tags], name=name)
            continue
        faces = _swept_faces(gmsh, tags, thickness, tol)
        if len(faces) != len(tags):
            raise RuntimeError(f"group {name!r}: {len(faces)} faces swept by {len(tags)} curves")
        gmsh.model.addPhysicalGroup(2, faces, name=name)
    return sizes


def mesh_layout_solid(layout: FlexureLayout, thickness: float, layers: int = 2,
                      n_across: int = 3, aspect: float = 4.0, coarse: float | None = None,
                      name: str = "flexure_solid", root_fillet_radius: float = 0.0) -> tuple:
    """Mesh ``layout`` extruded by ``thickness`` (m) in ``layers`` layers of tetrahedra (use
    order=2 in the Model): the in-plane mesh of
    :func:`~flexfem.geometry.flexure_drawing.mesh_layout` with the same options. Returns
    (FEMesh with the mid-plane at z = 0, the sizes dict of mesh_layout plus "layer_size",
    m). Groups: mesh_layout's, as volumes and faces."""
    check_solid_options(thickness, layers)
    if not (isinstance(n_across, (int, np.integer)) and n_across >= 2):
        raise ValueError(f"n_across = {n_across!r} must be an integer >= 2 (elements across a "
                         "flexure)")
    with gmsh_session(name) as gmsh:
        sizes = draw_layout_solid(gmsh, layout, thickness, layers, n_across, aspect, coarse,
                                  root_fillet_radius)
        gmsh.option.setNumber("Mesh.Algorithm", 6)
        gmsh.model.mesh.generate(3)
        mesh = mesh_from_gmsh(gmsh)
    mesh = dataclasses.replace(mesh, mesh=mesh.mesh.translated((0.0, 0.0, -thickness / 2)))
    return mesh, {**sizes, "layer_size": thickness / layers}
