"""Strength limits of a linear-elastic flexure: how far it may move before it yields, and how
far it may cycle for its material's fatigue life (SI units).

In a linear analysis every stress is proportional to the stroke: sigma = s delta, s the stress
per unit stroke (Pa/m). The yield-limited stroke is Sy / (n s). A stroke cycling with amplitude
delta_a about a mean delta_m (a preload or an offset) has stress amplitude s delta_a and mean
s delta_m; the modified Goodman line (Budynas and Nisbett, Shigley's Mechanical Engineering
Design, 10th ed., Eq. 6-46) allows

    sigma_a / Se + sigma_m / Sut = 1 / n,

and the Soderberg line (Eq. 6-45) is the same with the yield strength Sy for Sut (more
conservative). Se: the material's fatigue strength at its cycles (data/materials.toml). The
stress is the von Mises equivalent stress, amplitude and mean alike (Shigley's
distortion-energy approach to multiaxial fatigue, Section 6-14); a compressive mean is taken
as zero (it does not lower the allowed amplitude in either line, conservatively).
"""
import math

CRITERIA = ("goodman", "soderberg")


def yield_stroke(stress_per_stroke: float, yield_strength: float,
                 safety_factor: float = 1.0) -> float:
    """The stroke (m) at which the peak stress reaches yield_strength / safety_factor."""
    _check(stress_per_stroke, safety_factor)
    return yield_strength / (safety_factor * stress_per_stroke)


def fatigue_stroke(stress_per_stroke: float, material, mean_stroke: float = 0.0,
                   criterion: str = "goodman", safety_factor: float = 1.0) -> float | None:
    """The stroke amplitude (m) the flexure may cycle with about ``mean_stroke`` (m) for the
    material's fatigue_cycles, by the ``criterion`` line; None without fatigue data; 0 where
    the mean stroke alone uses up the allowed stress."""
    _check(stress_per_stroke, safety_factor)
    if criterion not in CRITERIA:
        raise ValueError(f"criterion = {criterion!r} must be one of {CRITERIA}")
    if material.fatigue_strength is None:
        return None
    static = material.ultimate_strength if criterion == "goodman" else material.yield_strength
    mean_stress = max(stress_per_stroke * abs(mean_stroke), 0.0)
    amplitude = material.fatigue_strength * (1.0 / safety_factor - mean_stress / static)
    return max(amplitude, 0.0) / stress_per_stroke


def _check(stress_per_stroke: float, safety_factor: float) -> None:
    if not (math.isfinite(stress_per_stroke) and stress_per_stroke > 0):
        raise ValueError(f"stress per stroke = {stress_per_stroke!r} Pa/m must be finite > 0")
    if not (math.isfinite(safety_factor) and safety_factor >= 1):
        raise ValueError(f"safety_factor = {safety_factor!r} must be >= 1")
