"""Heaviside projection of the filtered densities (Wang, Lazarov, Sigmund 2011, "On
projection methods, convergence and robust formulations in topology optimization", Struct
Multidisc Optim 43:767-784, doi:10.1007/s00158-010-0602-y) with top88's continuation."""
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Projection:
    """rho = (tanh(beta eta) + tanh(beta (x - eta))) / (tanh(beta eta) + tanh(beta (1 - eta)))
    of the filtered densities x. ``beta`` starts at ``beta`` and doubles after ``every``
    iterations at one value or when the design change falls below the optimiser's
    tolerance, up to ``beta_max``; the run converges only at ``beta_max``."""

    beta: float = 1.0
    eta: float = 0.5
    beta_max: float = 32.0
    every: int = 50

    def __post_init__(self):
        for key in ("beta", "beta_max"):
            value = getattr(self, key)
            if not (isinstance(value, (int, float)) and np.isfinite(value) and value > 0):
                raise ValueError(f"projection.{key} = {value!r}: must be a number > 0")
        if self.beta_max < self.beta or self.beta_max > 1024:
            raise ValueError(f"projection.beta_max = {self.beta_max!r}: must be in "
                             f"[beta, 1024]")
        if not (isinstance(self.eta, (int, float)) and 0 < self.eta < 1):
            raise ValueError(f"projection.eta = {self.eta!r}: must be in (0, 1)")
        if isinstance(self.every, bool) or not isinstance(self.every, int) or self.every < 1:
            raise ValueError(f"projection.every = {self.every!r}: must be an integer >= 1")

    def next_beta(self, beta: float, at_beta: int, change: float, tolerance: float) -> float:
        """beta for the next iteration, after ``at_beta`` iterations at ``beta``."""
        if beta < self.beta_max and (at_beta >= self.every or change <= tolerance):
            return min(2.0 * beta, self.beta_max)
        return beta


def project(x: np.ndarray, beta: float, eta: float) -> np.ndarray:
    """Projected densities of filtered densities x."""
    a = np.tanh(beta * eta)
    return (a + np.tanh(beta * (x - eta))) / (a + np.tanh(beta * (1.0 - eta)))


def project_derivative(x: np.ndarray, beta: float, eta: float) -> np.ndarray:
    """d project / d x, elementwise."""
    a = np.tanh(beta * eta)
    return beta * (1.0 - np.tanh(beta * (x - eta)) ** 2) / (a + np.tanh(beta * (1.0 - eta)))
