"""A frequency response (:class:`FRF`: amplitude, phase, peaks, bandwidth), damping
(:class:`Rayleigh` or modal ratios) and the frequencies' check; numpy only, shared by the
continuum's :func:`~flexfem.fem.harmonic.solve_harmonic` and the beam model's."""
from dataclasses import dataclass
import math

import numpy as np


@dataclass(frozen=True)
class Rayleigh:
    """Rayleigh damping C = alpha M + beta K: alpha (1/s), beta (s)."""

    alpha: float = 0.0
    beta: float = 0.0

    def __post_init__(self):
        for name in ("alpha", "beta"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value >= 0):
                raise ValueError(f"Rayleigh.{name} = {value!r} must be a finite number >= 0")

    def ratios(self, omega: np.ndarray) -> np.ndarray:
        """Modal damping ratios (-) at the circular frequencies ``omega`` (rad/s)."""
        return self.alpha / (2 * omega) + self.beta * omega / 2


@dataclass(frozen=True, eq=False)
class FRF:
    """A frequency response: frequencies_hz (n,), response (n,) complex (m per the applied
    load amplitudes)."""

    frequencies_hz: np.ndarray
    response: np.ndarray

    @property
    def amplitude(self) -> np.ndarray:
        """|response| (m)."""
        return np.abs(self.response)

    @property
    def phase(self) -> np.ndarray:
        """Phase (rad) of the response relative to the load, in (-pi, pi]."""
        return np.angle(self.response)

    def peaks(self) -> np.ndarray:
        """Frequencies (Hz) of the interior local maxima of the amplitude, each refined by a
        parabola through the sample and its two neighbours."""
        a, f = self.amplitude, self.frequencies_hz
        k = np.flatnonzero((a[1:-1] > a[:-2]) & (a[1:-1] >= a[2:])) + 1
        denom = a[k - 1] - 2 * a[k] + a[k + 1]
        shift = np.where(denom != 0, 0.5 * (a[k - 1] - a[k + 1]) / np.where(denom != 0, denom, 1), 0)
        return f[k] + shift * (f[k + 1] - f[k - 1]) / 2

    def bandwidth(self, near_hz: float) -> float:
        """Half-power (-3 dB) bandwidth (Hz) of the peak nearest ``near_hz``: the width where
        the amplitude exceeds peak / sqrt(2), by linear interpolation between samples.
        Raises ValueError if the sampled range does not reach both half-power points."""
        a, f = self.amplitude, self.frequencies_hz
        peaks = np.flatnonzero((a[1:-1] > a[:-2]) & (a[1:-1] >= a[2:])) + 1
        if len(peaks) == 0:
            raise ValueError("the response has no interior peak")
        k = peaks[np.argmin(np.abs(f[peaks] - near_hz))]
        level = a[k] / math.sqrt(2)
        below = np.flatnonzero(a[:k] < level)
        above = np.flatnonzero(a[k:] < level)
        if len(below) == 0 or len(above) == 0:
            raise ValueError(f"near_hz = {near_hz}: the frequencies do not reach both half-power "
                             "points of that peak; sample a wider band")
        i, j = below[-1], k + above[0]
        lo = f[i] + (level - a[i]) * (f[i + 1] - f[i]) / (a[i + 1] - a[i])
        hi = f[j - 1] + (level - a[j - 1]) * (f[j] - f[j - 1]) / (a[j] - a[j - 1])
        return float(hi - lo)


def damping_ratios(damping, omega: np.ndarray) -> np.ndarray:
    if isinstance(damping, Rayleigh):
        return damping.ratios(omega)
    zeta = np.asarray(damping, dtype=float)
    if zeta.ndim > 1 or (zeta.ndim == 1 and len(zeta) != len(omega)) or \
            not np.all(np.isfinite(zeta)) or np.any(zeta < 0):
        raise ValueError(f"damping = {damping!r} must be a ratio >= 0, one per mode "
                         f"({len(omega)}), or Rayleigh(alpha, beta)")
    return np.broadcast_to(zeta, omega.shape)


def check_frequencies(frequencies_hz) -> np.ndarray:
    f = np.atleast_1d(np.asarray(frequencies_hz, dtype=float))
    if f.ndim != 1 or len(f) == 0 or not np.all(np.isfinite(f)) or np.any(f < 0):
        raise ValueError(f"frequencies_hz = {frequencies_hz!r} must be finite numbers >= 0 (Hz)")
    return f
