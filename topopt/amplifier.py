"""A displacement amplifier designed in the DBMA's envelope (geometry/dbma: the paper's
design, its layout), as its quarter: the actuator's pad pushed along +x, the output face on
top pushed along +y, the symmetry lines x = 0 and y = 0 held normal to themselves; the
actuator's room (|y| below the DBMA's arm gap, inside the pads) kept void, the pad and the
output face solid. R = u_out / u_in of the quarter is the full part's output over the
actuator's elongation (the DBMA's R_fem)."""
import math

from .grid import Grid
from .interpolation import Interpolation
from .problem import (Constraint, Load, Optimizer, Passive, Problem, Response, Spring,
                      Support)
from .projection import Projection
from .regions import Region
from .robust import Robust, radius_for


def dbma_envelope(params=None, layout=None) -> dict:
    """The DBMA's quarter (m): ``width``, ``height``, ``pad`` ((x0, x1), (y0, y1)),
    ``output`` ((x0, x1), y), ``gap`` (the actuator's room, y), ``thickness``, ``E``, ``nu``,
    ``rho`` (kg/m^3)."""
    from ..geometry.dbma.drawing import DBMALayout, quarter_rects
    from ..geometry.dbma.params import paper_design

    p = params or paper_design()
    layout = layout or DBMALayout()
    member, pad, out = quarter_rects(p, layout)[:3]
    return {"width": member.x1, "height": member.y1, "pad": ((pad.x0, pad.x1), (0.0, pad.y1)),
            "output": ((0.0, out.x1), out.y1), "gap": layout.arm_gap, "thickness": p.d,
            "E": p.E, "nu": p.nu, "rho": p.rho}


def amplifier_problem(force: float, k_in_min: float, k_actuator: float, k_output: float,
                      element: float = 1e-3, volume: float = 0.3, iterations: int = 300,
                      radius: float = 3.0, envelope: dict | None = None,
                      fn_min: float | None = None, stress_max: float | None = None,
                      min_hinge: float | None = None, eta: float = 0.25,
                      own_stiffness: bool = False) -> Problem:
    """Maximise the output's displacement. ``force`` (N): the actuator's push on one pad
    (the quarter carries half); ``k_in_min`` (N/m): the least input stiffness (force over
    elongation, the DBMA's k_in), a limit on u_in; ``k_actuator``, ``k_output`` (N/m): the
    input and output springs of the full part; ``element`` (m): grid size; ``volume``: the
    solid fraction of the quarter; ``radius`` (elements): the density filter's; ``fn_min``
    (Hz): a least lowest eigenfrequency of the density model (its springs, the quarter's
    symmetric modes); ``stress_max`` (Pa): a limit on the p-norm (P = 8) of its stresses;
    ``min_hinge`` (m): the blueprint's minimum solid and void size by the robust formulation
    (thresholds 1 - ``eta``, 0.5, ``eta``; the filter's radius from topopt.robust.radius_for,
    ``radius`` then unused), on square elements of ``element``, the grid the whole elements
    that fit inside the envelope; ``own_stiffness``: bound the structure's own input stiffness
    too (the pad's force over its displacement without the springs, as the DBMA's k_in)."""
    env = envelope or dbma_envelope()
    robust = None
    if min_hinge is None:
        nelx, nely = round(env["width"] / element), round(env["height"] / element)
        dx, h = env["width"] / nelx, env["height"] / nely
    else:
        nelx, nely = (math.floor(env[k] / element + 1e-9) for k in ("width", "height"))
        dx = h = element
        robust = Robust(eta, min_hinge)
        radius = radius_for(min_hinge, element, eta)
    width, height = nelx * dx, nely * h
    # the output face: two elements, or with a minimum hinge one element more than it (so
    # that the face the load acts on is no thinner than a hinge)
    face = 2 * h if min_hinge is None else (math.ceil(min_hinge / h - 1e-9) + 1) * h
    (px0, px1), (_, py1) = env["pad"]
    px0, px1, py1 = round(px0 / dx) * dx, round(px1 / dx) * dx, round(py1 / h) * h
    (_, ox1), _ = env["output"]
    ox1, top = round(ox1 / dx) * dx, height
    f = force / 2
    return Problem(
        Grid(nelx, nely, width, height), Response("displacement", "output"),
        sense="max", nu=env["nu"], thickness=env["thickness"], mass_density=env["rho"],
        interpolation=Interpolation("simp", 3.0, env["E"], 1e-9 * env["E"]),
        filter_kind="density", radius=radius,
        supports=(Support(Region("edge", "left"), ("x",)),
                  Support(Region("edge", "bottom"), ("y",))),
        loads=(Load(Region("box", ((px0, 0.0), (px0, py1))), (f, 0.0)),),
        springs=(Spring("input", Region("box", ((px0, 0.0), (px0, py1))), "x", k_actuator),
                 Spring("output", Region("box", ((0.0, top), (ox1, top))), "y",
                        k_output / 2)),
        constraints=(Constraint(Response("volume"), upper=volume),
                     Constraint(Response("displacement", "input"), upper=f / k_in_min))
        + ((Constraint(Response("displacement", "input", springs=False),
                       upper=f / k_in_min),) if own_stiffness else ())
        + ((Constraint(Response("frequency"), lower=fn_min),) if fn_min else ())
        + ((Constraint(Response("stress"), upper=stress_max),) if stress_max else ()),
        passive=(Passive(Region("box", ((0.0, 0.0), (px0, env["gap"]))), "void"),
                 Passive(Region("box", ((px0, 0.0), (px1, py1))), "solid"),
                 Passive(Region("box", ((0.0, top - face), (ox1, top))), "solid")),
        optimizer=Optimizer("mma", 0.2, iterations, 0.01),
        projection=Projection(beta=1.0, beta_max=16.0, every=40), robust=robust)


def spring_free(problem) -> Problem:
    """The problem with its springs made negligible (1e-9 of their stiffness)."""
    from dataclasses import replace

    springs = tuple(replace(s, stiffness=1e-9 * s.stiffness) for s in problem.springs)
    return replace(problem, springs=springs, constraints=problem.constraints[:1])


def dbma_quarter(params=None, layout=None):
    """The DBMA's quarter x, y >= 0 as an Outline (m): its rectangles (geometry/dbma, leaf
    hinges with sharp corners) joined and cut at the symmetry lines."""
    from shapely.geometry import box
    from shapely.ops import unary_union

    from ..geometry.dbma.drawing import DBMALayout, quarter_rects
    from ..geometry.dbma.params import paper_design
    from .outline import Outline

    rects = quarter_rects(params or paper_design(), layout or DBMALayout())
    shape = unary_union([box(r.x0, r.y0, r.x1, r.y1) for r in rects])
    return Outline(shape.intersection(box(0.0, 0.0, rects[0].x1, rects[2].y1)), (), 0.0)


def shape_readings(problem, outline, size: float) -> dict:
    """The body-fitted shape (topopt.verify.shape_model) under the actuator's force alone:
    R = u_out / u_in (the groups' mean displacements, as the DBMA's R_fem), ``k_in`` (N/m:
    the pad's force over its motion, the full part's actuator force over its elongation);
    its modes with the pad held along x (a rigid actuator, as the DBMA's modal analysis),
    the quarter's symmetry making them the modes symmetric about x = 0 and y = 0; its peak
    von Mises stress (Pa, at the problem's force) at triangles of ``size`` and ``size / 2``
    m, with the place and corner of the finer one."""
    from .verify import verify_modes, verify_static

    coarse, fine = verify_static(problem, outline, size), verify_static(problem, outline,
                                                                        size / 2)
    u = coarse["displacements"]
    push = sum(ld.force[0] for ld in problem.case_loads(1))
    return {"R": u["output"] / u["input"], "k_in": push / u["input"],
            **verify_modes(problem, outline, hold=("input",), size=size),
            "peak_stress": coarse["peak_stress"], "peak_stress_fine": fine["peak_stress"],
            **{k: fine[k] for k in ("peak_where", "corner_angle", "singularity_exponent")}}


def verify_amplifier(result, threshold: float = 0.3, neck: float = 0.6e-3,
                     size: float | None = None) -> dict:
    """R = u_out / u_in of a finished amplifier: the density model's and the body-fitted
    shape's (the outline of ``density > threshold``, one-node hinges closed into necks of
    ``neck`` m, meshed at ``size`` m, default half an element), each under the actuator's
    force alone (as the DBMA's R_fem; the shape's by :func:`shape_readings`, with its
    ``k_in`` (N/m), modes (``fn_working``, Hz) and peak stress (``peak_stress``, Pa)) and
    with the springs (the shape's by verify_mechanism: point loads, springs by
    superposition); ``k_in_density`` (N/m); the outline and its number of parts."""
    from .model import Discrete
    from .outline import extract_outline, problem_anchors
    from .verify import mirror_lines, verify_mechanism

    problem = result.problem
    size = size or min(problem.grid.dx, problem.grid.dy) / 2
    d = Discrete(spring_free(problem))
    u = d.system.solve(problem.interpolation.modulus(result.density), d.force)[:, 0]
    free = {name: float(v @ u) for name, v in d.spring_vectors.items()}
    push = sum(ld.force[0] for ld in problem.case_loads(1))
    outline = extract_outline(result.density, problem.grid, problem_anchors(problem),
                              threshold=threshold, close=neck / (2 * (2 ** 0.5 - 1)),
                              mirrors=mirror_lines(problem))
    fitted = verify_mechanism(problem, outline, size=size)
    dens = result.displacements
    readings = shape_readings(problem, outline, size)
    return {"R_density": free["output"] / free["input"], "k_in_density": push / free["input"],
            "R_density_springs": dens["output"] / dens["input"],
            "R_fitted": readings.pop("R"),
            "R_fitted_springs": fitted["output"] / fitted["input"],
            "u_in_fitted_springs": fitted["input"], "parts": len(outline.parts),
            **readings, "outline": outline}
