"""A toy mechanism for the study engine: a (tapered) cantilever with a tip load.

The tip deflection is the unit-load (virtual work) integral

    delta = integral_0^L  P (L - x)^2 / (E I(x)) dx,   I(x) = w t(x)^3 / 12,

with the thickness t varying linearly from ``thickness_root_m`` to ``thickness_tip_m``.
``evaluate`` computes it two ways, side by side like a real mechanism's FEM and formula:
numerically, with the composite trapezoid rule over ``n`` equal "elements" (error
proportional to h^2, the known convergence order), and exactly (P L^3 / (3 E I) for a uniform
beam, the closed-form integral for a taper). For a uniform beam the integrand is quadratic and
the trapezoid error is exactly L h^2 f''/12 = delta h^2 / (2 L^2): a pure power law, on which
Richardson extrapolation is exact.

The engine's tests add hooks (sleep, fail, crash) in a mechanism of their own
(tests/studies/engine/toy_hooks.py), not here.
"""
import math
from dataclasses import dataclass, fields

from ...fem import checks
from ..engine.validate import declare

BASE_ELEMENTS = 8  # elements at size_factor = 1
#: Units of the metrics of :func:`evaluate` (the parameters' names end in their unit).
UNITS = {"tip_deflection*": "m", "stiffness*": "N/m", "root_stress": "Pa", "h": "m",
         "dofs": "-"}


@dataclass(frozen=True)
class CantileverParams:
    """Cantilever design (SI units): length, width and thickness in m, Young's modulus in Pa,
    tip load in N."""

    length_m: float = 0.1
    width_m: float = 0.01
    thickness_root_m: float = 0.002
    thickness_tip_m: float = 0.002
    youngs_modulus_pa: float = 200e9
    load_n: float = 1.0

    def __post_init__(self):
        for name in ("length_m", "width_m", "thickness_root_m", "thickness_tip_m",
                     "youngs_modulus_pa"):
            value = checks.positive(name, getattr(self, name))
            if name.endswith("_m") and not value <= 10.0:
                raise ValueError(f"{name} = {value!r} m is larger than a cantilever of this "
                                 "model (at most 10 m); lengths are in m")


def second_moment_of_area(width_m: float, thickness_m: float) -> float:
    """I = w t^3 / 12 of a rectangular section, m^4."""
    return width_m * thickness_m**3 / 12.0


def tip_deflection_exact(p: CantileverParams) -> float:
    """Exact tip deflection, m: P L^3 / (3 E I) for a uniform beam; for a linear taper the
    unit-load integral in closed form, with v = a + b u the thickness at u = L - x:
    12 P / (E w b^3) [ln v + 2a/v - a^2/(2 v^2)] from v = t_tip to t_root."""
    a, t_root, length = p.thickness_tip_m, p.thickness_root_m, p.length_m
    b = (t_root - a) / length
    if abs(b * length) < 1e-3 * a:  # (nearly) uniform: the closed form cancels badly
        # second-order expansion in the taper: 1/t^3 ~ (1/a^3)(1 - 3 b u / a + 6 (b u / a)^2)
        return 12 * p.load_n / (p.youngs_modulus_pa * p.width_m * a**3) * (
            length**3 / 3 - 3 * b / a * length**4 / 4 + 6 * (b / a) ** 2 * length**5 / 5)

    def primitive(v):
        return math.log(v) + 2 * a / v - a**2 / (2 * v**2)

    integral = (primitive(t_root) - primitive(a)) / b**3
    return 12 * p.load_n / (p.youngs_modulus_pa * p.width_m) * integral


def tip_deflection_trapezoid(p: CantileverParams, n_elements: int) -> float:
    """Tip deflection, m, from the composite trapezoid rule on ``n_elements`` equal intervals
    of the unit-load integral (error O(h^2), h = L / n)."""
    h = p.length_m / n_elements
    total = 0.0
    for i in range(n_elements + 1):
        x = i * h
        t = p.thickness_root_m + (p.thickness_tip_m - p.thickness_root_m) * x / p.length_m
        f = p.load_n * (p.length_m - x) ** 2 / (p.youngs_modulus_pa * second_moment_of_area(p.width_m, t))
        total += f if 0 < i < n_elements else f / 2
    return total * h


def root_stress(p: CantileverParams) -> float:
    """Bending stress at the clamped root, Pa: sigma = 6 P L / (w t_root^2)."""
    return 6 * p.load_n * p.length_m / (p.width_m * p.thickness_root_m**2)


def elements_for(size_factor: float = 1.0, n_elements: int | None = None) -> int:
    """Number of elements: ``n_elements`` if given, else BASE_ELEMENTS / size_factor (rounded)."""
    if n_elements is not None:
        if int(n_elements) < 1:
            raise ValueError(f"n_elements = {n_elements!r} must be >= 1")
        return int(n_elements)
    if not 1e-4 <= size_factor <= 1e4:
        raise ValueError(f"size_factor = {size_factor!r} must be in [1e-4, 1e4]")
    return max(1, round(BASE_ELEMENTS / size_factor))


@declare(parameters=CantileverParams, positive=("stiffness*", "h", "dofs"))
def evaluate(params: dict, size_factor: float = 1.0, n_elements: int | None = None) -> dict:
    """Metrics of the toy cantilever (SI): tip deflection (m) numerical and exact, stiffness
    (N/m) both ways, root stress (Pa), element size ``h`` (m) and ``dofs`` (nodes).

    Missing parameters take the CantileverParams defaults; unknown ones raise ValueError.
    """
    known = {f.name for f in fields(CantileverParams)}
    unknown = sorted(set(params) - known)
    if unknown:
        raise ValueError(f"unknown toy parameter(s) {unknown}; known: {sorted(known)}")
    p = CantileverParams(**params)
    n = elements_for(size_factor, n_elements)
    deflection = tip_deflection_trapezoid(p, n)
    exact = tip_deflection_exact(p)
    return {"tip_deflection": deflection, "tip_deflection_analytical": exact,
            "stiffness": p.load_n / deflection, "stiffness_analytical": p.load_n / exact,
            "root_stress": root_stress(p), "h": p.length_m / n, "dofs": n + 1}
