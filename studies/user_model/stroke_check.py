"""The stroke limits checked by a large-deflection solve ([analysis] stroke_check = true).

A linear solve's limits (stroke.py) assume that force, outputs and stress grow in proportion
to the stroke. A bridge amplifier's leaves, a guide's leaves pulled taut, a pivot turned far
do not. The check follows the large-deflection path of the model whose stress sized the
limits (the continuum, or the beam model where it stands in for a singular peak) under the
file's single force, scaled by load control in :data:`STEPS` steps to the force the linear
stiffness gives at :data:`REACH` times the largest linear limit (again, up to twice, to a
larger force where a stiffening path falls short of it). At the linear yield stroke the path
is compared with the linear solve: where its force, the mean displacement of the other
groups (the outputs), its peak stress or one of the file's [outputs] departs by more than
:data:`DEPARTURE` (check["departed"] names which), the limits
come from the path (fem/fatigue.py's yield_stroke_curve and fatigue_stroke_curve: the stroke
where the path's peak stress reaches the allowable, linear between its steps) and
stroke_limit_basis says "nonlinear path"; otherwise the linear limits stand. The path is
taken in the load's direction only: a fatigue cycle's other half is assumed to mirror it.
"""
import numpy as np

from ...fem import Force, solve_nonlinear, solve_static
from ...fem.fatigue import fatigue_stroke_curve, yield_stroke_curve
from .observe import observed, observed_path, output_values
from .outputs import single_force

DEPARTURE = 0.05  # relative departure from linear beyond which the path sizes the limits
REACH = 1.5       # the path goes to this many times the largest linear limit
STEPS = 6         # load steps of the path
LINEAR = "linear (within 5 % of the large-deflection solve)"
UNCHECKED = ("linear (not checked by a large-deflection solve: [analysis] stroke_check = "
             "true checks it)")


def _along(u, direction) -> float:
    u = np.asarray(u, float)
    return float(u @ direction[:u.size])


def _peak(path, k: int) -> float:
    """The peak von Mises stress (Pa) of step ``k``: the continuum's nodal one, the beam's."""
    return float(np.max(path.stress_at_step(k)[0]))


def stroke_path(fe, supports, group, direction, force, others, steps=STEPS,
                spec=None) -> dict:
    """The large-deflection path of ``fe`` under ``force`` (N) on ``group`` along
    ``direction``, by load control: per step its stroke (m), force (N), peak von Mises
    stress (Pa), the mean displacement (m) of each group of ``others`` and, given the model
    file ``spec``, its [outputs] ("outputs": {name: [value per step]}, None at the start)."""
    path = solve_nonlinear(fe, supports, [Force(group, tuple(force * direction))],
                           steps=steps)
    n = len(path.load_factors)
    outputs = {}
    if spec is not None and spec.outputs:
        along = observed_path(spec, path, [group, *others])["outputs_path"]
        outputs = {"outputs": {k: [None, *v] for k, v in along.items()}}
    return {**outputs, "result": path, "strokes": [_along(path.mean_displacement(group, k), direction) for k in range(n)],
            "forces": [float(f) * force for f in path.load_factors],
            "peak_stress": [_peak(path, k) for k in range(n)],
            "others": {g: [path.mean_displacement(g, k).tolist() for k in range(n)]
                       for g in others}}


def _linear(fe, supports, group, direction, others, spec=None) -> dict:
    """Per newton along ``direction``: stroke (m/N), peak stress (Pa/N), others (m/N) and,
    given ``spec``, the observations of its [outputs] (m/N, rad/N)."""
    unit = solve_static(fe, supports, [Force(group, tuple(direction))])
    out = {"stroke": _along(unit.mean_displacement(group), direction),
           "stress": float(unit.max_von_mises),
           "others": {g: np.asarray(unit.mean_displacement(g)) for g in others}}
    if spec is not None and spec.outputs:
        out["observations"] = observed(spec, unit, [group, *others])["observations"]
    return out


def _output_departures(spec, path: dict, linear: dict, at: float) -> dict:
    """{output: relative departure} of the [outputs] on the path at the stroke ``at`` (m)
    from their linear values there (the unit solve's observations scaled to that stroke);
    an output that is zero or not defined in the linear solve is left out."""
    if spec is None or "outputs" not in path or "observations" not in linear:
        return {}
    scale = at / linear["stroke"]
    scaled = {g: {c: v * scale for c, v in o.items()} for g, o in
              linear["observations"].items()}
    expected = output_values(spec, scaled)[0]
    s = np.asarray(path["strokes"][1:])
    out = {}
    for name, values in path["outputs"].items():
        lin, along = expected.get(name), values[1:]
        if lin is None or lin == 0 or any(v is None for v in along):
            continue
        out[name] = float(np.interp(at, s, along)) / lin - 1.0
    return out


def _departures(path: dict, linear: dict, at: float) -> dict:
    """The relative departures of the path from linear at the stroke ``at`` (m)."""
    s = np.asarray(path["strokes"])
    force = float(np.interp(at, s, path["forces"]))
    per_newton = at / linear["stroke"]
    moved = {g: np.array([np.interp(at, s, np.asarray(v)[:, i]) for i in range(len(v[0]))])
             for g, v in path["others"].items()}
    scale = max([np.linalg.norm(u) for u in linear["others"].values()], default=0.0)
    output = max([float(np.linalg.norm(moved[g] - per_newton * u)) / (per_newton * scale)
                  for g, u in linear["others"].items()] or [0.0]) if scale > 0 else 0.0
    return {"force": force / per_newton - 1.0, "output": float(output),
            "stress": float(np.interp(at, s, path["peak_stress"]))
            / (per_newton * linear["stress"]) - 1.0}


def checked_path(fe, supports, group, direction, top, others, spec=None) -> tuple[dict, dict]:
    """(path, linear): the path out to the stroke ``top`` (m) at least (two more tries with
    a larger force where it stiffens and falls short)."""
    linear = _linear(fe, supports, group, direction, others, spec)
    force = top / linear["stroke"]
    for _ in range(3):
        path = stroke_path(fe, supports, group, direction, force, others, spec=spec)
        if path["strokes"][-1] >= 0.999 * top:
            break
        force *= top / max(path["strokes"][-1], 1e-3 * top)
    return path, linear


def stroke_check(spec, limits: dict, fe, supports, kept: dict | None = None) -> dict:
    """The keys stroke_limit_basis and stroke_check (and, from the path, stroke_limit_yield
    and stroke_limit_fatigue) for ``limits`` (stroke.py's) of the model ``fe`` that sized
    them; {} where there is no linear limit to check. ``kept``: a dict that receives
    "stroke_path" = (fe, the path's solve result) for the field files."""
    load = single_force(spec)
    a, m = spec.analysis, spec.material
    strokes = [v for v in (limits.get("stroke_limit_yield"),
                           (limits.get("stroke_limit_fatigue") or 0.0) + abs(a.mean_stroke)
                           if limits.get("stroke_limit_fatigue") is not None else None)
               if v is not None and v > 0]
    if load is None or not strokes:
        return {}
    direction = np.asarray(limits["stroke_direction"], float)
    others = [g for g in limits.get("groups", []) if g != load.group]
    try:
        path, linear = checked_path(fe, supports, load.group, direction,
                                    REACH * max(strokes), others, spec)
    except ValueError as error:  # NonConvergenceError among them
        return {"stroke_limit_basis": f"linear (the large-deflection check failed: {error})"}
    if kept is not None:
        kept["stroke_path"] = (fe, path["result"])
    at = limits.get("stroke_limit_yield") or max(strokes)
    departed = _departures(path, linear, at)
    outputs = _output_departures(spec, path, linear, at)
    check = {"model": "beam" if type(fe).__name__.startswith("Beam") else "continuum",
             **{k: v for k, v in path.items() if k not in ("others", "result")}, "at_stroke": at,
             "departure": departed, "output_departure": outputs,
             "departed": [k for k, v in {**departed, **{f"outputs.{n}": v for n, v in
                                                         outputs.items()}}.items()
                          if abs(v) > DEPARTURE],
             "linear_limits": {
                 k: limits.get(k) for k in ("stroke_limit_yield", "stroke_limit_fatigue")}}
    if not check["departed"]:
        return {"stroke_limit_basis": LINEAR, "stroke_check": check}
    s, peak = path["strokes"][1:], path["peak_stress"][1:]
    out = {"stroke_limit_basis": "nonlinear path", "stroke_check": check}
    if limits.get("stroke_limit_yield") is not None:
        limit, reached = yield_stroke_curve(s, peak, m.yield_strength, a.safety_factor)
        out["stroke_limit_yield"] = limit
        check["force_at_limit"] = float(np.interp(limit, path["strokes"], path["forces"]))
        check["yield_reached"] = reached  # False: the limit is beyond the path's end
    if limits.get("stroke_limit_fatigue") is not None:
        amplitude, reached = fatigue_stroke_curve(s, peak, m, 0.0, a.mean_stroke, a.fatigue,
                                                  a.safety_factor)
        out["stroke_limit_fatigue"], check["fatigue_reached"] = amplitude, reached
    return out
