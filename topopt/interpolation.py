"""Material interpolation: Young's modulus of an element from its physical density (0..1)."""
from dataclasses import dataclass

import numpy as np

KINDS = ("simp", "ramp")


@dataclass(frozen=True)
class Interpolation:
    """``kind`` 'simp': E = Emin + x^p (E0 - Emin); 'ramp': E = Emin + x / (1 + p (1 - x))
    (E0 - Emin). ``penal`` is p; ``E0``, ``Emin`` in Pa (top88: 1 and 1e-9)."""

    kind: str = "simp"
    penal: float = 3.0
    E0: float = 1.0
    Emin: float = 1e-9

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"interpolation.kind = {self.kind!r}: choose one of {list(KINDS)}")
        if not (np.isfinite(self.penal) and self.penal >= (0.0 if self.kind == "ramp" else 1.0)):
            raise ValueError(f"interpolation.penal = {self.penal!r}: must be >= 1 for SIMP, "
                             ">= 0 for RAMP")
        if not (np.isfinite(self.E0) and self.E0 > 0):
            raise ValueError(f"material.E = {self.E0!r}: must be > 0 (Pa)")
        if not (np.isfinite(self.Emin) and 0 < self.Emin < self.E0):
            raise ValueError(f"material.Emin = {self.Emin!r}: must be in (0, E)")

    def modulus(self, x: np.ndarray) -> np.ndarray:
        """E(x), Pa."""
        return self.Emin + self._shape(x) * (self.E0 - self.Emin)

    def derivative(self, x: np.ndarray) -> np.ndarray:
        """dE/dx, Pa."""
        p = self.penal
        if self.kind == "simp":
            d = p * x ** (p - 1.0)
        else:
            d = (1.0 + p) / (1.0 + p * (1.0 - x)) ** 2
        return d * (self.E0 - self.Emin)

    def _shape(self, x):
        p = self.penal
        return x**p if self.kind == "simp" else x / (1.0 + p * (1.0 - x))


def mass_factor(x: np.ndarray) -> np.ndarray:
    """The mass of an element of physical density x per solid mass: x above 0.1, 1e5 x^6
    below (Pedersen 2000, Struct Multidisc Optim 20:2-11): near-void elements lose mass faster
    than the SIMP stiffness, so they cannot vibrate on their own as spurious low modes."""
    return np.where(x > 0.1, x, 1e5 * x**6)


def mass_factor_derivative(x: np.ndarray) -> np.ndarray:
    """d mass_factor / dx."""
    return np.where(x > 0.1, 1.0, 6e5 * x**5)
