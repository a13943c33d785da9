"""A density design re-meshed as a body-fitted shape and solved by flexfem's own FEM
(plane stress, gmsh + scikit-fem): the springs' displacements beside the density model's,
its modes, its peak stress and the corner that peak sits at. Springs are added by
superposition (exact for the linear model): the shape's flexibility between the spring
points C and the springs' stiffnesses k give (I + C k) u = u_loads."""
import numpy as np

from ..fem import (Fixed, Force, Material, Model, PlaneStress, PointForce, Prescribed,
                   facets_where, gmsh_session, ground_spring, mesh_from_gmsh, solve_modes,
                   solve_nonlinear, solve_static)
from ..fem.hyperelastic import STRAIN_LIMIT, max_strain
from ..fem.newton import NonConvergenceError
from ..fem.static_result import mean_field
from .model_file import along_edge, edge_axis
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


def _near(xy, reach):
    """A facet test: its midpoint within ``reach`` (m) of a point of ``xy`` ((n, 2), m)."""
    def near(x):
        d = np.min(np.hypot(x[0][:, None] - xy[:, 0], x[1][:, None] - xy[:, 1]), axis=1)
        return d <= reach
    return near


def _reach(grid) -> float:
    """How far (m) from a region's grid nodes its facets lie: just over half the longer side
    of an element, so that an edge's facets between its nodes are all within reach."""
    return 0.51 * max(grid.dx, grid.dy)


def _facets(problem, mesh, region, reach, what, parallel: bool = False):
    """The boundary facets within ``reach`` (m) of ``region``'s grid nodes; with
    ``parallel``, where those nodes line an edge (one x or one y), only the facets along it
    (:func:`~.model_file.along_edge`)."""
    xy = problem.grid.nodes[region.nodes(problem.grid)]
    facets = facets_where(mesh.mesh, _near(xy, reach))
    axis = edge_axis(xy, reach)
    if parallel and axis is not None:
        p = mesh.mesh.p[:, mesh.mesh.facets[:, facets]]
        facets = facets[along_edge(p[:, 1] - p[:, 0], axis)]
    if facets.size == 0:
        raise ValueError(f"{what}: the shape does not reach it")
    return facets


def _supports(problem, mesh, reach, parallel: bool = False):
    """Boundary groups near each support's nodes, and their flexfem supports."""
    groups, supports = {}, []
    for k, s in enumerate(problem.supports):
        groups[f"support{k}"] = _facets(problem, mesh, s.where, reach, f"support[{k}]",
                                        parallel)
        fix = {a: 0.0 for a in s.fix}
        supports.append(Fixed(f"support{k}") if len(fix) == 2 else
                        Prescribed(f"support{k}", **fix))
    return mesh.with_groups(boundaries=groups), supports


def verify_mechanism(problem, outline: Outline, E: float | None = None, size=None,
                     springs: bool = True, case: int = 1) -> dict:
    """The body-fitted shape's displacement of every spring point along its DOF (m), with the
    problem's supports, loads of load case ``case`` (at their nodes) and, with ``springs``,
    its springs; ``E`` defaults to the problem's, ``size`` (m) to half an element."""
    g = problem.grid
    h = min(g.dx, g.dy)
    mesh = mesh_outline(outline, size or h / 2)
    mesh, supports = _supports(problem, mesh, _reach(g), True)
    E = problem.interpolation.E0 if E is None else E
    model = Model(mesh, Material("design", E, problem.nu, 1.0), PlaneStress(problem.thickness),
                  order=2)
    loads = [PointForce(tuple(g.nodes[n]), tuple(ld.force[a] / len(ld.where.nodes(g))
                                                  for a in (0, 1)))
             for ld in problem.case_loads(case) for n in ld.where.nodes(g)]
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


def shape_model(problem, outline: Outline, size=None):
    """(model, supports): the body-fitted shape meshed at ``size`` m (default half an
    element), quadratic plane stress with the problem's E, nu, thickness and mass density;
    boundary groups 'support<k>', 'load<k>' (every load case) and each spring's name: the
    facets within 0.51 of an element's longer side of their grid nodes (along an edge, only
    those along it)."""
    h, reach = min(problem.grid.dx, problem.grid.dy), _reach(problem.grid)
    mesh, supports = _supports(problem, mesh_outline(outline, size or h / 2), reach, True)
    groups = {name: _facets(problem, mesh, ld.where, reach, f"load[{name[4:]}]", True)
              for name, ld in problem.load_groups()}
    groups.update({s.name: _facets(problem, mesh, s.where, reach, f"spring {s.name!r}",
                                   True) for s in problem.springs})
    model = Model(mesh.with_groups(boundaries=groups),
                  Material("design", problem.interpolation.E0, problem.nu,
                           problem.mass_density), PlaneStress(problem.thickness), order=2)
    return model, supports


def verify_modes(problem, outline: Outline, hold=(), along: str = "output", n: int = 6,
                 size=None) -> dict:
    """The ``n`` lowest modes of the body-fitted shape (:func:`shape_model`) with the
    problem's supports and the springs named in ``hold`` held along their DOF (a rigid
    actuator), the others left out: ``frequencies_hz``, ``working_mode`` (1-based: the
    largest effective mass along spring ``along``'s DOF), ``fn_working`` (Hz) and
    ``effective_mass_fraction`` (n x 2)."""
    model, supports = shape_model(problem, outline, size)
    supports += [Prescribed(s.name, **{s.dof: 0.0}) for s in problem.springs if s.name in hold]
    modes = solve_modes(model, n, supports)
    k = int(np.argmax(modes.effective_mass[:, AXIS[problem.spring(along).dof]]))
    return {"frequencies_hz": [float(f) for f in modes.frequencies_hz], "working_mode": k + 1,
            "fn_working": float(modes.frequencies_hz[k]),
            "effective_mass_fraction": modes.effective_mass_fraction.tolist()}


def mirror_lines(problem) -> list:
    """The symmetry lines of a problem: (axis, value) of each edge support that holds only
    the DOF normal to its edge (0: x = value, 1: y = value), m."""
    g, lines = problem.grid, []
    for s in problem.supports:
        if s.where.kind == "edge":
            axis, at = {"left": (0, 0.0), "right": (0, g.lx), "bottom": (1, 0.0),
                        "top": (1, g.ly)}[s.where.value]
            if tuple(s.fix) == ("xy"[axis],):
                lines.append((axis, at))
    return lines


def interior_angles(outline: Outline, mirrors=()) -> tuple:
    """(vertices (n, 2), m; their interior angles in the solid, deg): above 180 a re-entrant
    corner. A vertex on a symmetry line of ``mirrors`` ((axis, value), m) gets the mirrored
    part's angle, twice its own."""
    from shapely.geometry.polygon import orient

    xy, angles = [], []
    for part in outline.parts:
        part = orient(part, 1.0)  # the solid on the left of every ring
        for ring in [part.exterior, *part.interiors]:
            p = np.asarray(ring.coords)[:-1]
            d_in, d_out = p - np.roll(p, 1, axis=0), np.roll(p, -1, axis=0) - p
            cross = d_in[:, 0] * d_out[:, 1] - d_in[:, 1] * d_out[:, 0]
            angle = 180.0 - np.degrees(np.arctan2(cross, np.sum(d_in * d_out, axis=1)))
            for axis, at in mirrors:
                angle = np.where(np.abs(p[:, axis] - at) <= 1e-9, 2 * angle, angle)
            xy.append(p), angles.append(angle)
    return np.vstack(xy), np.concatenate(angles)


def singularity_exponent(angle_deg: float) -> float:
    """1 - lambda of the symmetric (mode I) stress field at a corner of the solid of interior
    angle ``angle_deg``: sigma ~ r^-(1 - lambda), lambda the least root in (0, 1) of
    lambda sin(theta) + sin(lambda theta) = 0 (Williams 1952); 0 (no singularity) at 180 deg
    or less; 0.4555 at 270 deg."""
    from scipy.optimize import brentq

    theta = np.radians(angle_deg)
    if theta <= np.pi * (1 + 1e-9):
        return 0.0
    return 1.0 - brentq(lambda x: x * np.sin(theta) + np.sin(x * theta), 0.5 * np.pi / theta,
                        1.0 - 1e-12)


def verify_static(problem, outline: Outline, size=None) -> dict:
    """The body-fitted shape (:func:`shape_model`) under load case 1, each load's total force
    spread over its group, without the springs: ``displacements`` (each spring group's mean
    displacement along its DOF, m), ``peak_stress`` (Pa, the largest nodal von Mises
    stress, as flexfem's static results give it), ``peak_where`` (m), ``corner_angle`` (deg,
    the interior angle, mirrored at symmetry lines, of the outline's vertex nearest the peak
    within two mesh sizes; 180 where there is none) and its ``singularity_exponent``."""
    model, supports = shape_model(problem, outline, size)
    loads = [Force(name, tuple(ld.force)) for name, ld in problem.load_groups(1)]
    result = solve_static(model, supports, loads)
    where = np.asarray(result.max_von_mises_location, float)
    xy, angles = interior_angles(outline, mirror_lines(problem))
    d = np.hypot(*(xy - where).T)
    reach = 2 * (size or min(problem.grid.dx, problem.grid.dy) / 2)
    angle = float(angles[np.argmin(d)]) if d.min() <= reach else 180.0
    return {"displacements": {s.name: float(result.mean_displacement(s.name)[AXIS[s.dof]])
                              for s in problem.springs},
            "peak_stress": result.max_von_mises, "peak_where": where.tolist(),
            "corner_angle": angle, "singularity_exponent": singularity_exponent(angle)}


def verify_large(problem, outline: Outline, size=None) -> dict:
    """The body-fitted shape (:func:`shape_model`) under load case 1 with its springs (each
    on its group's mean displacement), solved with large displacements in
    ``problem.nonlinear.steps`` load steps (flexfem's continuum solver, St. Venant-Kirchhoff
    like the density model) and with small ones: ``large`` and ``small`` {spring: its
    group's mean displacement along its DOF, m}, ``load_factor`` (1, or the last one reached
    where the path ends at a limit point or Newton fails; ``large`` is then there),
    ``max_strain`` (the largest Green-Lagrange principal strain, -) and ``strain_valid``
    (below the solver's St. Venant-Kirchhoff validity limit)."""
    model, supports = shape_model(problem, outline, size)
    springs = [ground_spring(model, s.name, s.stiffness, s.dof) for s in problem.springs]
    if springs:
        model = model.with_stiffness(sum(springs[1:], springs[0]))
    loads = [Force(name, tuple(ld.force)) for name, ld in problem.load_groups(1)]
    last = {"lam": 0.0, "u": np.zeros(model.n_dofs)}

    def record(lam, u, _):
        last.update(lam=float(lam), u=u)
        return False

    try:
        solve_nonlinear(model, supports, loads, steps=problem.nonlinear.steps if
                        problem.nonlinear else 10, stop_when=record)
    except NonConvergenceError:
        pass
    small = solve_static(model, supports, loads)
    strain = max_strain(model, last["u"])
    return {"large": {s.name: float(mean_field(model, last["u"], s.name)[AXIS[s.dof]])
                      for s in problem.springs},
            "small": {s.name: float(small.mean_displacement(s.name)[AXIS[s.dof]])
                      for s in problem.springs},
            "load_factor": last["lam"], "max_strain": strain,
            "strain_valid": bool(strain <= STRAIN_LIMIT)}


def verify_compliances(problem, outline: Outline, size=None) -> list:
    """The body-fitted shape's compliance f_c.u_c (J) in each load case c, each load's force
    spread over its group (:func:`shape_model`): sum over the loads of F . (the group's mean
    displacement), the work of a uniform traction; without the springs."""
    model, supports = shape_model(problem, outline, size)
    out = []
    for case in range(1, problem.n_cases + 1):
        groups = problem.load_groups(case)
        result = solve_static(model, supports, [Force(n, tuple(ld.force)) for n, ld in groups])
        out.append(float(sum(np.dot(ld.force, result.mean_displacement(n)) for n, ld in groups)))
    return out
