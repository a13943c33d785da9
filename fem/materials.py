"""Linear-elastic isotropic materials: a small library with sources, and user-defined ones."""
import math
from dataclasses import dataclass

from ..data import shared_toml
from . import checks


@dataclass(frozen=True)
class Material:
    """An isotropic linear-elastic material (the library's: :func:`material`).

    Parameters
    ----------
    name : str
        A label, for messages and reports.
    E : float
        Young's modulus (Pa), > 0.
    nu : float
        Poisson's ratio (-), in (-1, 0.5).
    rho : float or None
        Density (kg/m^3), > 0; None: unknown, for static analyses (masses and
        frequencies need it: :attr:`density` says so).
    yield_strength : float
        The stress at which the design fails (Pa; the fracture strength of a brittle
        material); math.inf where unknown.
    source : str
        Where the values come from.
    ultimate_strength : float
        The ultimate tensile strength (Pa); math.inf where unknown.
    fatigue_strength : float or None
        The fully reversed stress amplitude survived for ``fatigue_cycles`` cycles (Pa);
        None: no fatigue data.
    fatigue_cycles : float or None
        The cycles (-) of ``fatigue_strength``, >= 1; given with it or not at all.
    fatigue_source : str
        Where the fatigue data come from.

    Raises
    ------
    ValueError
        One line naming the material and the value out of range.
    """

    name: str
    E: float
    nu: float
    rho: float | None
    yield_strength: float = math.inf
    source: str = "user-defined"
    ultimate_strength: float = math.inf
    fatigue_strength: float | None = None
    fatigue_cycles: float | None = None
    fatigue_source: str = ""

    def __post_init__(self):
        owner = f"material {self.name!r}"
        checked = {"E": checks.positive("E", self.E, owner=owner, unit="Pa"),
                   "nu": checks.in_range("nu", self.nu, (-1.0, 0.5), owner=owner, closed=False)}
        if self.rho is not None:
            checked["rho"] = checks.positive("rho", self.rho, owner=owner, unit="kg/m^3")
        for name in ("yield_strength", "ultimate_strength"):
            value = getattr(self, name)
            if not (checks.is_real(value) and value > 0):
                raise checks.InputError(name, value, "> 0 (Pa; math.inf for none)", owner)
            checked[name] = float(value)
        if (self.fatigue_strength is None) != (self.fatigue_cycles is None):
            raise ValueError(f"material {self.name!r}: give fatigue_strength and fatigue_cycles "
                             "together (or neither)")
        if self.fatigue_strength is not None:
            checked["fatigue_strength"] = checks.positive(
                "fatigue_strength", self.fatigue_strength, owner=owner, unit="Pa")
            if not (checks.is_finite(self.fatigue_cycles) and self.fatigue_cycles >= 1):
                raise checks.InputError("fatigue_cycles", self.fatigue_cycles,
                                        "a finite number >= 1", owner)
            checked["fatigue_cycles"] = float(self.fatigue_cycles)
        for name, value in checked.items():
            object.__setattr__(self, name, value)

    @property
    def density(self) -> float:
        """rho (kg/m^3); a ValueError naming the material where it has none (a mass matrix,
        a frequency, an inertia needs it)."""
        if self.rho is None:
            raise ValueError(f"material {self.name!r} has no density: masses and frequencies "
                             "need rho (kg/m^3)")
        return self.rho

    @property
    def density_or_nan(self) -> float:
        """rho (kg/m^3), NaN where unknown: for the masses a model is built with and may
        never use (its modal and weight solvers ask :attr:`density`, which refuses)."""
        return math.nan if self.rho is None else self.rho

    @property
    def lame(self) -> tuple[float, float]:
        """Lame parameters (lambda, mu) in Pa, for 3-D and plane strain."""
        lam = self.E * self.nu / ((1 + self.nu) * (1 - 2 * self.nu))
        mu = self.E / (2 * (1 + self.nu))
        return lam, mu

    def as_dict(self) -> dict:
        return {"name": self.name, "E": self.E, "nu": self.nu, "rho": self.rho,
                "yield_strength": self.yield_strength,
                "ultimate_strength": self.ultimate_strength,
                "fatigue_strength": self.fatigue_strength,
                "fatigue_cycles": self.fatigue_cycles}


def _library() -> dict:
    """data/materials.toml (parsed once per process)."""
    return shared_toml("materials.toml")


def material_names() -> list[str]:
    """Names of the materials in the library (data/materials.toml)."""
    return sorted(_library())


def material(name: str) -> Material:
    """A material from the library by name, e.g. ``material("aluminium_6061_t6")``."""
    table = _library()
    if not isinstance(name, str) or name not in table:
        raise ValueError(f"unknown material {name!r}; known: {', '.join(sorted(table))}")
    return Material(name=name, **table[name])
