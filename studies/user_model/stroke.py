"""The stroke limits of a model file's loaded group: how far it may move before the peak
stress reaches yield, and the amplitude it may cycle with for the material's fatigue life
(fem/fatigue.py), along its single force load ([analysis] safety_factor, mean_stroke and
fatigue set them). Lengths in m.

The stress they are sized by: a linear solve's peak von Mises stress over the stroke it comes
with. At a filleted root or a notch that peak converges under refinement; at a sharp
re-entrant corner (a leaf with square roots meeting its body) it is singular: it grows as the
mesh is refined and converges to nothing. A model of bodies and flexures knows where its sharp
corners are: where the continuum's peak sits within a thickness of one, the limits are sized
by the beam model's nominal stress (|N|/A + |M| c/I at the root) instead, and the output says
so. A drawing (.geo, STEP, mesh) does not: its peak is used as it is, with the advice to check
it with ``flexfem converge --metric max_von_mises``.
"""
import numpy as np

from ...fem.fatigue import fatigue_stroke, yield_stroke
from ...geometry.mechanism.description import Leaf
from .outputs import single_force


def _along(u, direction) -> float:
    """The component of displacement ``u`` (2 or 3 components) along ``direction``."""
    u = np.asarray(u, float)
    return float(u @ direction[:u.size])


def sharp_root_near(mechanism, point, reach: float = 1.0):
    """The index of the leaf with square roots whose root corner lies within ``reach`` x its
    thickness of ``point`` (m), or None."""
    for i, f in enumerate(mechanism.flexures):
        if not isinstance(f, Leaf) or f.fillet > 0:
            continue
        for _, corner, _, _, _ in mechanism.roots(i):
            if np.linalg.norm(np.asarray(point[:2]) - corner) <= reach * f.thickness:
                return i
    return None


def stroke_limits(spec, result: dict, nominal=None) -> dict:
    """The stroke-limit keys of ``result`` (analyze_model's dict) for its single force load:
    stroke_limit_yield (m), stroke_limit_fatigue (m, amplitude about mean_stroke; None without
    fatigue data), fatigue_cycles, fatigue_criterion, fatigue_source, stroke_group,
    stroke_direction (unit vector), stroke_limit_where (m), stroke_stress_basis, and
    stress_per_stroke (Pa/m); {} without a single force load. ``nominal``: a callable giving
    the beam model's result, used where the continuum's peak is at a sharp root."""
    load = single_force(spec)
    if load is None:
        return {}
    direction = np.asarray(load.vector, float) / np.linalg.norm(load.vector)
    stroke = _along(result["mean_displacement"][load.group], direction)
    stress, where = result["max_von_mises"], result["max_von_mises_location"]
    basis = "peak von Mises stress of the continuum"
    if result.get("solver") == "beam":
        basis = "nominal beam stress |N|/A + |M| c/I (no stress concentration)"
    elif spec.mechanism is not None:
        leaf = sharp_root_near(spec.mechanism, where)
        try:
            beam = nominal() if leaf is not None and nominal is not None else None
        except ValueError as error:  # the beam model cannot stand in: say so, size by nothing
            return {"stroke_group": load.group, "stroke_stress_basis": "none: the continuum's "
                    f"peak sits at the square root of flexure {leaf + 1} (singular) and the "
                    f"beam model cannot give the nominal stress ({error})",
                    "stroke_limit_yield": None, "stroke_limit_fatigue": None}
        if beam is not None:
            stroke = _along(beam["mean_displacement"][load.group], direction)
            stress, where = beam["max_von_mises"], beam["max_von_mises_location"]
            basis = (f"nominal beam stress: the continuum's peak sits at the square root of "
                     f"flexure {leaf + 1}, a singular corner (it grows under refinement); give "
                     "the leaf a fillet to size the stroke by the fillet's stress")
        else:
            basis += " (at a fillet or notch: converges under refinement)"
    else:
        basis += (" (not checked for a singular corner: see flexfem converge --metric "
                  "max_von_mises)")
    if not (stroke > 0 and stress > 0):
        return {}
    per_stroke = stress / stroke
    a, m = spec.analysis, spec.material
    missing = {"stroke_limit_yield": yield_needs(m),
               "stroke_limit_fatigue": fatigue_needs(m, a.fatigue, a.mean_stroke)}
    missing = {k: v for k, v in missing.items() if v is not None}
    out = {"stroke_group": load.group, "stroke_direction": direction.tolist(),
           "stress_per_stroke": per_stroke, "stroke_stress_basis": basis,
           "stroke_limit_where": [float(v) for v in where],
           "stroke_limit_yield": (None if "stroke_limit_yield" in missing else
                                  yield_stroke(per_stroke, m.yield_strength, a.safety_factor)),
           "stroke_limit_fatigue": (None if "stroke_limit_fatigue" in missing else
                                    fatigue_stroke(per_stroke, m, a.mean_stroke, a.fatigue,
                                                   a.safety_factor)),
           "fatigue_cycles": m.fatigue_cycles, "fatigue_criterion": a.fatigue,
           "fatigue_source": m.fatigue_source, "safety_factor": a.safety_factor,
           "mean_stroke": a.mean_stroke}
    if missing:
        out["not_available"] = missing
    return out


def yield_needs(material) -> str | None:
    """Why the yield-limited stroke cannot be given ("needs yield_strength"), None if it can."""
    return None if np.isfinite(material.yield_strength) else "needs yield_strength"


def fatigue_needs(material, criterion: str, mean_stroke: float) -> str | None:
    """Why the fatigue-limited stroke cannot be given, None if it can: no fatigue data, or a
    mean stroke without the static strength its line is drawn to (Goodman: ultimate_strength,
    Soderberg: yield_strength; a compressive face is also held to yield_strength)."""
    if material.fatigue_strength is None:
        return "needs fatigue_strength and fatigue_cycles"
    if mean_stroke:
        static = "ultimate_strength" if criterion == "goodman" else "yield_strength"
        lacking = [k for k in dict.fromkeys((static, "yield_strength"))
                   if not np.isfinite(getattr(material, k))]
        if lacking:
            return (f"needs {' and '.join(lacking)} (the {criterion} line of a mean stroke)")
    return None
