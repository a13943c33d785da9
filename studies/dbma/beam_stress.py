"""Peak stress of a filleted or notch hinge from the beam model: the nominal stress times a
stress-concentration factor K_t. A filleted hinge's is the published factor of the shoulder
fillet where its straight part meets the body (data/stress_concentration.toml: Roark's Table
17.1, case 17, fits to Peterson's charts; docs/beam_validation_dbma.md, "DBMA: peak stress at the fillets");
a circular notch's is its neck's, from the notch's 2-D model
(:func:`flexfem.reduced.hinge_patch.notch_factors`).

    sigma_peak = K_t,tension |N| / (w b) + K_t,bending 6 |M| / (w b^2)

with N and M the beam's axial force and bending moment at the fillet's tangent point (where
the straight part of thickness b begins; M is linear along a hinge, so its largest value on
the straight part is there), or at a notch's neck. The two peaks lie at the same point (of
the fillet's arc, of the neck's surface) and add (linear elasticity). SI units.
"""
import math

import numpy as np

from ...data import shared_toml

_SOURCE = "shoulder_fillet_flat_bar"


def _coefficients(load: str) -> dict:
    if load not in ("tension", "bending"):
        raise ValueError(f"load = {load!r} must be 'tension' or 'bending'")
    return shared_toml("stress_concentration.toml")[_SOURCE][load]


def shoulder_fillet_kt(d: float, D: float, r: float, load: str) -> float:
    """K_t (-) of a flat bar of width d (m) stepping to D (m) through fillets of radius r (m)
    on both edges, in 'tension' or in-plane 'bending', nominal stress in the d section. The
    fit holds for 0.1 <= h / r <= 20, h = (D - d) / 2; beyond 20 it is taken at 20 (the
    shoulder is then so deep that K_t no longer depends on it: the filleted-hinge specimen in
    tests/studies/dbma/test_dbma_beam_stress.py gives the same peak for h / r = 2.4 to 9.4).
    ValueError for a shallower shoulder or non-positive sizes."""
    for name, value in (("d", d), ("D", D), ("r", r)):
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"shoulder_fillet_kt: {name} = {value!r} must be a finite number > 0 (m)")
    coef = _coefficients(load)
    lo, hi = shared_toml("stress_concentration.toml")[_SOURCE]["h_over_r_range"]
    h = (D - d) / 2
    if not h / r >= lo:
        raise ValueError(f"shoulder_fillet_kt: h / r = {h / r!r} is below the fit's range "
                         f"[{lo}, {hi}] (h = (D - d) / 2 = {h!r} m, r = {r!r} m)")
    if h / r > hi:  # deep shoulder: K_t saturates; evaluate at the range's end
        h = hi * r
        D = d + 2 * h
    hr, x = h / r, 2 * h / D
    rows = coef["low"] if hr <= 2.0 else coef["high"]
    c = [a + b * math.sqrt(hr) + e * hr for a, b, e in rows]
    return c[0] + c[1] * x + c[2] * x ** 2 + c[3] * x ** 3


def hinge_shoulder(p, layout) -> float:
    """Width D (m) of the body a DBMA hinge enters, as a symmetric shoulder: the smaller of the
    two shoulders the hinge meets at its arm's end (the hinge sits h / 2 off the arm's centre
    line), on both sides: D = b + 2 (c - h - b) / 2."""
    return p.b + (p.c - p.h - p.b)


def filleted_peak_stress(model, state, thickness: float, kt_tension: float,
                         kt_bending: float) -> tuple:
    """(peak stress (Pa), element) over the elements of in-plane thickness ``thickness`` (m:
    the hinges' straight parts), from the beam state's axial force and end moments."""
    straight = [e for e, (t0, t1) in enumerate(_end_thicknesses(model.sections))
                if math.isclose(t0, thickness, rel_tol=1e-9)
                and math.isclose(t1, thickness, rel_tol=1e-9)]
    if not straight:
        raise ValueError(f"no element of thickness {thickness!r} m: not a filleted hinge model")
    return end_peak_stress(model, state, straight, kt_tension, kt_bending)


def _end_thicknesses(sections) -> list:
    """[(t at node 1, t at node 2)] (m; NaN: no depth) of each section."""
    nan = math.nan
    return [s.taper[:2] if s.taper else (nan if s.depth_y is None else s.depth_y,) * 2
            for s in sections]


def end_peak_stress(model, state, elements, kt_tension: float, kt_bending: float) -> tuple:
    """(peak stress (Pa), element): K_t times the nominal stress |N| / (w t) + 6 |M| / (w t^2)
    at both ends of each of ``elements`` (rectangular beam elements), the largest. For notch
    hinges: at a neck, where t is least and the K_t belongs."""
    elements = np.asarray(elements)
    sections = [model.sections[e] for e in elements]
    w = np.array([[math.nan if s.depth_z is None else s.depth_z] for s in sections])
    t = np.array(_end_thicknesses(sections))  # the thickness at both ends
    N = np.abs(state.axial_force[elements])[:, None]
    M = np.abs(state.end_moments[elements])
    sigma = kt_tension * N / (w * t) + kt_bending * 6 * M / (w * t ** 2)
    sigma = np.nan_to_num(sigma, nan=-np.inf)
    k = int(np.argmax(sigma))
    return float(sigma.flat[k]), int(elements[k // 2])


def _located(model, peak: float, e: int, kt_t: float, kt_b: float) -> dict:
    xy = model.nodes[model.elements[e]].mean(axis=0)
    return {"peak_stress": peak, "kt_tension": kt_t, "kt_bending": kt_b,
            "peak_stress_location": [float(xy[0]), float(xy[1])]}


def dbma_fillet_stress(p, layout, model, state) -> dict:
    """The DBMA's filleted-hinge peak stress (Pa) from a beam state: K_t of both loads for
    the hinge's shoulder (:func:`hinge_shoulder`), 'peak_stress', 'kt_tension',
    'kt_bending' and where (m)."""
    D, r = hinge_shoulder(p, layout), layout.hinge_fillet_radius
    kt_t = shoulder_fillet_kt(p.b, D, r, "tension")
    kt_b = shoulder_fillet_kt(p.b, D, r, "bending")
    peak, e = filleted_peak_stress(model, state, p.b, kt_t, kt_b)
    return _located(model, peak, e, kt_t, kt_b)


def dbma_notch_stress(p, layout, model, info, state) -> dict:
    """The DBMA's circular-notch peak stress (Pa) from a beam state: the neck's K_t of both
    loads (:func:`flexfem.reduced.hinge_patch.notch_factors`); dbma_fillet_stress's keys."""
    from ...reduced.hinge_patch import notch_factors

    f = notch_factors("circular", p.l, p.b, layout.hinge_fillet_radius, p.nu)
    peak, e = end_peak_stress(model, state, info["hinge_elements"], f.kt_tension,
                              f.kt_bending)
    return _located(model, peak, e, f.kt_tension, f.kt_bending)
