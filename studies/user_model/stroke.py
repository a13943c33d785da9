"""The stroke limits of a model file's loaded group: how far it may move before the peak
stress reaches yield, and the amplitude it may cycle with for the material's fatigue life
(fem/fatigue.py), along its single force load ([analysis] safety_factor, mean_stroke and
fatigue set them). Lengths in m.

The stress they are sized by: a linear solve's peak von Mises stress over the stroke it comes
with. At a filleted root or a notch that peak converges under refinement; at a sharp
re-entrant corner (a leaf with square roots meeting its body, two leaves fused where they
cross, a 45-degree chamfer) it is singular: it grows as the mesh is refined and converges to
nothing. Such a corner is found from the mesh itself (corners.py: the outline's interior
angle at the peak above 180 deg, with no fillet spreading it), and from a model's declared
square roots. Where the continuum's peak sits at one, the limits of a model of bodies and
flexures are sized by the beam model's nominal stress (|N|/A + |M| c/I) instead, and the
output says so; a drawing's are sized by the singular peak, and stroke_stress_singular and
stroke_stress_basis say that they shrink as the mesh is refined. A 3-D drawing's corners are
not checked: check its peak with ``flexfem converge --metric max_von_mises``.
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


def stroke_limits(spec, result: dict, nominal=None, corner=None) -> dict:
    """The stroke-limit keys of ``result`` (analyze_model's dict) for its single force load:
    stroke_limit_yield (m), stroke_limit_fatigue (m, amplitude about mean_stroke; None without
    fatigue data), fatigue_cycles, fatigue_criterion, fatigue_source, stroke_group,
    stroke_direction (unit vector), stroke_limit_where (m), stroke_stress_basis,
    stroke_stress_singular (the stress sizing them is a singular peak) and stress_per_stroke
    (Pa/m); {} without a single force load. ``nominal``: a callable giving the beam model's
    result, used where the continuum's peak is at a sharp corner; ``corner``: the sharp
    re-entrant corner of the continuum's mesh at its peak (corners.py; None: none), or
    "unchecked" (a 3-D mesh)."""
    load = single_force(spec)
    if load is None:
        return {}
    direction = np.asarray(load.vector, float) / np.linalg.norm(load.vector)
    sized = _sized_by(spec, result, nominal, corner)
    if "stroke_limit_yield" in sized:  # sized by nothing: the reason
        return {"stroke_group": load.group, **sized}
    source, basis = sized["source"], sized["basis"]
    stroke = _along(source["mean_displacement"][load.group], direction)
    stress, where = source["max_von_mises"], source["max_von_mises_location"]
    if not (stroke > 0 and stress > 0):
        return {}
    per_stroke = stress / stroke
    a, m = spec.analysis, spec.material
    missing = {"stroke_limit_yield": yield_needs(m),
               "stroke_limit_fatigue": fatigue_needs(m, a.fatigue, a.mean_stroke)}
    missing = {k: v for k, v in missing.items() if v is not None}
    out = {"stroke_group": load.group, "stroke_direction": direction.tolist(),
           "stress_per_stroke": per_stroke, "stroke_stress_basis": basis,
           "stroke_stress_singular": sized["singular"],
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


def _corner_text(corner, leaf) -> str:
    if corner is None:
        return f"the square root of flexure {leaf + 1}"
    x, y = (round(1e3 * v, 6) + 0.0 for v in corner["point"])  # mm, no -1e-15
    return (f"a sharp re-entrant corner of the outline at ({x:.4g}, {y:.4g}) mm (interior "
            f"angle {corner['angle_deg']:.0f} deg, no fillet)")


def _sized_by(spec, result, nominal, corner) -> dict:
    """{"source": the result whose peak sizes the limits, "basis": its description,
    "singular": whether that peak is singular}, or the keys of no limit where the continuum's
    peak is singular and the beam model cannot stand in."""
    basis = "peak von Mises stress of the continuum"
    if result.get("solver") == "beam":
        return {"source": result, "singular": False,
                "basis": "nominal beam stress |N|/A + |M| c/I (no stress concentration)"}
    where = result["max_von_mises_location"]
    leaf = sharp_root_near(spec.mechanism, where) if spec.mechanism is not None else None
    found = corner if isinstance(corner, dict) else None
    if found is None and leaf is None:
        if corner == "unchecked" and spec.mechanism is None:
            return {"source": result, "singular": False, "basis": basis + (
                " (a 3-D drawing: not checked for a singular corner; see flexfem converge "
                "--metric max_von_mises)")}
        return {"source": result, "singular": False, "basis": basis + (
            " (no sharp re-entrant corner at the peak: at a fillet or notch it converges "
            "under refinement)")}
    at = _corner_text(found, leaf)
    try:
        beam = nominal() if nominal is not None else None
    except ValueError as error:  # the beam model cannot stand in: say so, size by nothing
        return {"stroke_stress_basis": f"none: the continuum's peak sits at {at} (singular) "
                f"and the beam model cannot give the nominal stress ({error})",
                "stroke_stress_singular": True,
                "stroke_limit_yield": None, "stroke_limit_fatigue": None}
    if beam is not None:
        return {"source": beam, "singular": False, "basis": (
            f"nominal beam stress: the continuum's peak sits at {at}, a singular corner (it "
            "grows under refinement); give it a fillet to size the stroke by the fillet's "
            "stress")}
    return {"source": result, "singular": True, "basis": basis + (
        f" at {at}: singular, it grows without bound under refinement, so these limits "
        "shrink as the mesh is refined and are no material limit; give the corner a fillet")}


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
