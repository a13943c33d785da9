"""The body-fitted check at the necks: the outline's necks (topopt/necks.py) with the peak
von Mises stress of the re-meshed shape in each, under load case 1 with the springs."""
import numpy as np

from ..fem import Force, solve_static, von_mises
from .necks import outline_necks, peak_in
from .verify import AXIS, mirror_lines, shape_model


def detect_width(problem, min_member: float = 0.0) -> float:
    """The width (m) below which a part of the outline counts as a neck: twice the hinge
    width asked for (the robust formulation's min_hinge, else the shape's min_member, else
    two elements)."""
    g = problem.grid
    if problem.robust is not None and problem.robust.min_size > 0:
        return 2.0 * problem.robust.min_size
    return 2.0 * (min_member if min_member > 0 else 2.0 * max(g.dx, g.dy))


def problem_necks(problem, outline, detect: float) -> list:
    """The outline's necks thinner than ``detect`` (m), its symmetry lines mirrored, each
    kept where its narrowest chord lies in the design domain; narrowest first."""
    g = problem.grid
    return outline_necks(outline, detect, mirror_lines(problem), (0.0, 0.0, g.lx, g.ly))


def shape_stress(problem, outline, size=None):
    """(nodal points (n, 2), m; nodal von Mises stress (n,), Pa) of the body-fitted shape
    (:func:`~.verify.shape_model`) under load case 1, each load's total force spread over
    its group, with the springs added by superposition: the unit force on each spring's
    group gives the flexibility C, then (I + C k) u = u_loads and the springs' forces
    -k u scale those unit solves' stresses."""
    model, supports = shape_model(problem, outline, size)
    loads = [Force(name, tuple(ld.force)) for name, ld in problem.load_groups(1)]
    base = solve_static(model, supports, loads)
    sigma = base.nodal_stress_full.copy()
    if problem.springs:
        unit = [solve_static(model, supports, [Force(s.name, tuple(
            1.0 if a == AXIS[s.dof] else 0.0 for a in (0, 1)))]) for s in problem.springs]

        def along(result):
            return np.array([result.mean_displacement(s.name)[AXIS[s.dof]]
                             for s in problem.springs])

        C = np.column_stack([along(r) for r in unit])
        k = np.diag([s.stiffness for s in problem.springs])
        u = np.linalg.solve(np.eye(len(unit)) + C @ k, along(base))
        for f, r in zip(-k @ u, unit):
            sigma += f * r.nodal_stress_full
    return model.mesh.mesh.p.T, von_mises(np.moveaxis(sigma, 0, -1))


def neck_report(problem, outline, detect: float, size=None) -> list:
    """[{width (m), where (m), peak_stress (Pa)}] of the outline's necks thinner than
    ``detect``, narrowest first; the stress the largest nodal von Mises stress
    (:func:`shape_stress`) within a mesh size of the neck."""
    necks = problem_necks(problem, outline, detect)
    if not necks:
        return []
    size = size or min(problem.grid.dx, problem.grid.dy) / 2
    points, vm = shape_stress(problem, outline, size)
    return [{"width": n.width, "where": [float(n.where[0]), float(n.where[1])],
             "peak_stress": peak_in(points, vm, n.region, size)} for n in necks]
