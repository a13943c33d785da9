"""A density design re-meshed as a body-fitted shape and solved by flexfem's own FEM
(plane stress, gmsh + scikit-fem): the springs' displacements beside the density model's.
Springs are added by superposition (exact for the linear model): the shape's flexibility
between the spring points C and the springs' stiffnesses k give (I + C k) u = u_loads."""
import numpy as np

from ..fem import (Fixed, Material, Model, PlaneStress, PointForce, Prescribed, facets_where,
                   gmsh_session, mesh_from_gmsh, solve_static)
from .outline import Outline

AXIS = {"x": 0, "y": 1}


def _add_ring(gmsh, coords, size) -> int:
    points = [gmsh.model.geo.addPoint(x, y, 0.0, size) for x, y in np.asarray(coords)[:-1]]
    lines = [gmsh.model.geo.addLine(a, b) for a, b in zip(points, points[1:] + points[:1])]
    return gmsh.model.geo.addCurveLoop(lines)


def mesh_outline(outline: Outline, size: float):
    """The FEMesh (linear triangles, ``size`` m) of the outline's solid."""
    with gmsh_session() as gmsh:
        surfaces = []
        for part in outline.parts:
            loops = [_add_ring(gmsh, part.exterior.coords, size)]
            loops += [_add_ring(gmsh, r.coords, size) for r in part.interiors]
            surfaces.append(gmsh.model.geo.addPlaneSurface(loops))
        gmsh.model.geo.synchronize()
        gmsh.model.addPhysicalGroup(2, surfaces, name="body")
        gmsh.option.setNumber("Mesh.MeshSizeMax", size)
        gmsh.model.mesh.generate(2)
        return mesh_from_gmsh(gmsh)


def _supports(problem, mesh, reach):
    """Boundary groups near each support's nodes, and their flexfem supports."""
    groups, supports = {}, []
    for k, s in enumerate(problem.supports):
        xy = problem.grid.nodes[s.where.nodes(problem.grid)]

        def near(x, xy=xy):
            d = np.min(np.hypot(x[0][:, None] - xy[:, 0], x[1][:, None] - xy[:, 1]), axis=1)
            return d <= reach

        facets = facets_where(mesh.mesh, near)
        if facets.size == 0:
            raise ValueError(f"support[{k}]: the shape does not reach it")
        groups[f"support{k}"] = facets
        fix = {a: 0.0 for a in s.fix}
        supports.append(Fixed(f"support{k}") if len(fix) == 2 else
                        Prescribed(f"support{k}", **fix))
    return mesh.with_groups(boundaries=groups), supports


def verify_mechanism(problem, outline: Outline, E: float | None = None, size=None,
                     springs: bool = True) -> dict:
    """The body-fitted shape's displacement of every spring point along its DOF (m), with the
    problem's supports, loads of load case 1 (at their nodes) and, with ``springs``, its
    springs; ``E`` defaults to the problem's, ``size`` (m) to half an element."""
    g = problem.grid
    h = min(g.dx, g.dy)
    mesh = mesh_outline(outline, size or h / 2)
    mesh, supports = _supports(problem, mesh, 0.51 * h)
    E = problem.interpolation.E0 if E is None else E
    model = Model(mesh, Material("design", E, problem.nu, 1.0), PlaneStress(problem.thickness),
                  order=2)
    loads = [PointForce(tuple(g.nodes[n]), tuple(ld.force[a] / len(ld.where.nodes(g))
                                                  for a in (0, 1)))
             for ld in problem.case_loads(1) for n in ld.where.nodes(g)]
    points = [g.nodes[s.where.nodes(g)].mean(axis=0) for s in problem.springs]
    vertices = [int(np.argmin(np.hypot(*(mesh.mesh.p - p[:, None])))) for p in points]

    def spring_u(result):
        return np.array([result.displacement[v, AXIS[s.dof]]
                         for v, s in zip(vertices, problem.springs)])

    u0 = spring_u(solve_static(model, supports, loads))
    if not springs:
        return {s.name: float(v) for s, v in zip(problem.springs, u0)}
    C = np.column_stack([spring_u(solve_static(model, supports, [PointForce(
        tuple(p), tuple(1.0 if a == AXIS[s.dof] else 0.0 for a in (0, 1)))]))
        for p, s in zip(points, problem.springs)])
    k = np.diag([s.stiffness for s in problem.springs])
    u = np.linalg.solve(np.eye(len(points)) + C @ k, u0) if points else u0
    return {s.name: float(v) for s, v in zip(problem.springs, u)}
