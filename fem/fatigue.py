"""Strength limits of a flexure: how far it may move before it yields, and how far it may
cycle for its material's fatigue life (SI units).

Linear flexure. Every stress is proportional to the stroke: sigma = s delta, s the stress per
unit stroke (Pa/m). The yield-limited stroke is Sy / (n s). A stroke cycling with amplitude
delta_a about a mean delta_m (an offset) has stress amplitude s delta_a and mean s delta_m; the
modified Goodman line (Budynas and Nisbett, Shigley's Mechanical Engineering Design, 10th ed.,
Eq. 6-46) allows

    sigma_a / Se + sigma_m / Sut = 1 / n,

and the Soderberg line (Eq. 6-45) is the same with the yield strength Sy for Sut (more
conservative). Se: the material's fatigue strength at its cycles (data/materials.toml). The
stress is the von Mises equivalent stress, amplitude and mean alike (Shigley's
distortion-energy approach to multiaxial fatigue, Section 6-14). ``fatigue_stroke`` takes a
mean stroke's stress as tensile (the face it pulls governs).

Compressive mean (:func:`allowed_amplitude`). A compressive mean stress does not lower the
allowed amplitude: failure occurs when sigma_a = Se / n, or when the first cycle yields,
sigma_a + |sigma_m| = Sy / n (Budynas and Nisbett, Shigley's Mechanical Engineering Design,
9th ed., 2011, Section 6-12 "Fatigue Failure Criteria for Fluctuating Stress", p. 305 and the
left half of Fig. 6-25; the chapter's summary, p. 346, "sigma_m < 0: sigma_a = Se / n"; a
ductile metal's compressive yield strength taken equal to Sy). Goodman and Soderberg agree
there.

Preloaded (nonlinear) flexure (:func:`yield_stroke_curve`, :func:`fatigue_stroke_curve`). A
preload P puts a mean stress sigma_p (-P / A for a compressed leaf) at the peak point, and the
stroke's stress is no longer linear in the stroke: the peak von Mises S_i is known at computed
states x_i (a large-deflection FEM). The curve is interpolated linearly between them, starting
from the preload's stress |sigma_p| at x = 0, and never extrapolated: a limit no computed state
reaches is returned as the last computed stroke, a lower bound, with ``reached`` False. The
stroke's own stress is b(x) = S(|x|) - |sigma_p|, odd in x (a symmetric flexure), added to the
preload's on one face and taken from it on the other. A cycle x_m +- x_a then has the
amplitude (b(x_m + x_a) - b(x_m - x_a)) / 2 and the means sigma_p +- (b(x_m + x_a) + b(x_m -
x_a)) / 2, each face judged by :func:`allowed_amplitude`.
"""
import math

import numpy as np

CRITERIA = ("goodman", "soderberg")


def yield_stroke(stress_per_stroke: float, yield_strength: float,
                 safety_factor: float = 1.0) -> float:
    """The stroke (m) at which the peak stress reaches yield_strength / safety_factor."""
    _check(stress_per_stroke, safety_factor)
    return yield_strength / (safety_factor * stress_per_stroke)


def allowed_amplitude(mean_stress: float, material, criterion: str = "goodman",
                      safety_factor: float = 1.0) -> float | None:
    """The stress amplitude (Pa, >= 0) a point may cycle with about ``mean_stress`` (Pa;
    < 0: compressive) for the material's fatigue_cycles: a tensile mean by the ``criterion``
    line, a compressive one by Se / n and the first cycle's yield (module); None without
    fatigue data."""
    _check_factor(safety_factor)
    if criterion not in CRITERIA:
        raise ValueError(f"criterion = {criterion!r} must be one of {CRITERIA}")
    if material.fatigue_strength is None:
        return None
    Se, n = material.fatigue_strength, safety_factor
    if mean_stress >= 0:
        static = material.ultimate_strength if criterion == "goodman" else material.yield_strength
        amplitude = Se * (1.0 / n - mean_stress / static)
    else:
        amplitude = min(Se / n, material.yield_strength / n + mean_stress)
    return max(amplitude, 0.0)


def fatigue_stroke(stress_per_stroke: float, material, mean_stroke: float = 0.0,
                   criterion: str = "goodman", safety_factor: float = 1.0) -> float | None:
    """The stroke amplitude (m) the flexure may cycle with about ``mean_stroke`` (m) for the
    material's fatigue_cycles, by the ``criterion`` line; None without fatigue data; 0 where
    the mean stroke alone uses up the allowed stress."""
    _check(stress_per_stroke, safety_factor)
    amplitude = allowed_amplitude(stress_per_stroke * abs(mean_stroke), material, criterion,
                                  safety_factor)
    return None if amplitude is None else amplitude / stress_per_stroke


def yield_stroke_curve(strokes, peak_stresses, yield_strength: float,
                       safety_factor: float = 1.0,
                       preload_stress: float = 0.0) -> tuple[float, bool]:
    """(stroke, reached): where the peak stress curve of computed states (strokes > 0, m or
    rad, increasing; peak von Mises, Pa), from |preload_stress| (Pa) at 0, first reaches
    yield_strength / safety_factor; (the last stroke, False) if no state reaches it."""
    _check_factor(safety_factor)
    x, S = _curve(strokes, peak_stresses, preload_stress)
    level = yield_strength / safety_factor
    above = np.nonzero(S >= level)[0]
    if above.size == 0:
        return float(x[-1]), False
    k = int(above[0])
    if k == 0:
        return 0.0, True
    return float(np.interp(level, S[k - 1:k + 1], x[k - 1:k + 1])), True


def fatigue_stroke_curve(strokes, peak_stresses, material, preload_stress: float = 0.0,
                         mean_stroke: float = 0.0, criterion: str = "goodman",
                         safety_factor: float = 1.0) -> tuple[float | None, bool]:
    """(amplitude, reached): the stroke amplitude (m or rad) the preloaded flexure of the
    computed states (as :func:`yield_stroke_curve`) may cycle with about ``mean_stroke`` for
    the material's fatigue_cycles, each face of the peak point judged by
    :func:`allowed_amplitude` (module); amplitude None without fatigue data; (the largest
    amplitude within the computed states, False) if none of them reaches the limit."""
    _check_factor(safety_factor)
    if allowed_amplitude(0.0, material, criterion, safety_factor) is None:
        return None, True
    x, S = _curve(strokes, peak_stresses, preload_stress)
    b = S - abs(preload_stress)
    sign = 1.0 if preload_stress >= 0 else -1.0

    def stroke_stress(at):
        return math.copysign(float(np.interp(abs(at), x, b)), at)

    def admissible(a):
        hi, lo = stroke_stress(mean_stroke + a), stroke_stress(mean_stroke - a)
        amplitude, mid = 0.5 * (hi - lo), 0.5 * (hi + lo)
        return all(amplitude <= allowed_amplitude(preload_stress + face * mid, material,
                                                  criterion, safety_factor) * (1 + 1e-12)
                   for face in (sign, -sign))

    top = float(x[-1]) - abs(mean_stroke)
    if top <= 0 or not admissible(0.0):
        return 0.0, top > 0
    if admissible(top):
        return top, False
    low, high = 0.0, top
    for _ in range(80):
        mid = 0.5 * (low + high)
        low, high = (mid, high) if admissible(mid) else (low, mid)
    return low, True


def _curve(strokes, peak_stresses, preload_stress):
    """(x, S) with the straight state (0, |preload_stress|) first; checks the states."""
    x, S = np.asarray(strokes, float), np.asarray(peak_stresses, float)
    if x.ndim != 1 or x.shape != S.shape or x.size == 0:
        raise ValueError("strokes and peak_stresses must be 1-D, of one length, not empty")
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(S)) and x[0] > 0
            and np.all(np.diff(x) > 0)):
        raise ValueError(f"strokes = {x.tolist()} must be finite, > 0 and increasing, "
                         "stresses finite")
    if not math.isfinite(preload_stress):
        raise ValueError(f"preload_stress = {preload_stress!r} Pa must be finite")
    return np.concatenate([[0.0], x]), np.concatenate([[abs(preload_stress)], S])


def _check_factor(safety_factor: float) -> None:
    if not (math.isfinite(safety_factor) and safety_factor >= 1):
        raise ValueError(f"safety_factor = {safety_factor!r} must be >= 1")


def _check(stress_per_stroke: float, safety_factor: float) -> None:
    if not (math.isfinite(stress_per_stroke) and stress_per_stroke > 0):
        raise ValueError(f"stress per stroke = {stress_per_stroke!r} Pa/m must be finite > 0")
    _check_factor(safety_factor)
