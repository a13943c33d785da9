"""The DBMA hinge design search's spec: the box of hinge dimensions (b, h, l in m), the
constraints (working-mode frequency in Hz, stress at the actuator stroke in Pa, output
stiffness in N/m) and their margins; :mod:`.optimize` runs the search. SI units.
"""
import itertools
import math
from dataclasses import dataclass, fields, replace

import numpy as np

from ...data import load_toml
from ...geometry.dbma.drawing import DBMALayout, check_layout
from ...geometry.dbma.params import DBMAParams

NAMES = ("b", "h", "l")
ACTIVE_TOL = 0.01  # a constraint within 1 % of its bound is reported active
# the response bandwidth the DBMA was built for (Abstract): the default frequency bound, Hz
PAPER_BANDWIDTH_HZ = float(load_toml("dbma_paper.toml")["frequency"]["bandwidth_Hz"])
MAX_EVALUATIONS = 10_000  # FEM solves of a search: hours on the search mesh


class InfeasibleSpecError(ValueError):
    """No design within the bounds meets the constraints."""


@dataclass(frozen=True)
class OptimizeSpec:
    """Bounds (m) and constraints of the DBMA hinge design search.

    b, h, l bounds (m): hinge thickness, hinge offset, hinge length; every design in the box
    must be buildable (checked at its eight corners against DBMAParams and the layout).
    min_frequency_hz (Hz, default 300: the paper's bandwidth, data/dbma_paper.toml), 0: none;
    safety_factor (>= 1) against yield at the actuator stroke stroke_m (m, elongation, 1 nm
    to 1 mm); min_output_stiffness (N/m), 0: none. max_evaluations: search-mesh FEM
    evaluations (8 to MAX_EVALUATIONS; COBYQA's first model needs 2 n + 1 = 7);
    search_size_factor / check_size_factor: meshes of the search and of the final check;
    n_seed: Sobol points screened; seed: Sobol seed.
    """

    b_min: float = 0.3e-3
    b_max: float = 1.2e-3
    h_min: float = 0.5e-3
    h_max: float = 4.0e-3
    l_min: float = 2.0e-3
    l_max: float = 8.0e-3
    min_frequency_hz: float = PAPER_BANDWIDTH_HZ
    safety_factor: float = 1.5
    stroke_m: float = 20e-6
    min_output_stiffness: float = 3.0e5
    max_evaluations: int = 40
    search_size_factor: float = 1.0
    check_size_factor: float = 1.0
    n_seed: int = 1024
    seed: int = 0

    def __post_init__(self):
        for f in fields(self):
            v = getattr(self, f.name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise ValueError(f"OptimizeSpec: {f.name} = {v!r} must be a finite number")
        for name in ("b", "h", "l"):
            lo, hi = getattr(self, f"{name}_min"), getattr(self, f"{name}_max")
            if not lo > 0:
                raise ValueError(f"OptimizeSpec: {name}_min = {lo!r} must be > 0 (m)")
            if not hi > lo:
                raise ValueError(f"OptimizeSpec: {name}_max = {hi!r} must be > {name}_min = {lo!r} (m)")
        for name in ("min_frequency_hz", "min_output_stiffness"):
            if getattr(self, name) < 0:
                raise ValueError(f"OptimizeSpec: {name} = {getattr(self, name)!r} must be >= 0 (0: no constraint)")
        if not self.safety_factor >= 1:
            raise ValueError(f"OptimizeSpec: safety_factor = {self.safety_factor!r} must be >= 1")
        if not 1e-9 <= self.stroke_m <= 1e-3:
            raise ValueError(f"OptimizeSpec: stroke_m = {self.stroke_m!r} must be from 1 nm to "
                             "1 mm (m: a piezo stack's elongation is tens of um, and the "
                             "amplifier's linear model holds for small strokes)")
        for name, low in (("max_evaluations", 8), ("n_seed", 16), ("seed", 0)):
            v = getattr(self, name)
            if not (isinstance(v, int) and v >= low):
                raise ValueError(f"OptimizeSpec: {name} = {v!r} must be an integer >= {low}")
        if self.max_evaluations > MAX_EVALUATIONS:
            raise ValueError(f"OptimizeSpec: max_evaluations = {self.max_evaluations!r} must be "
                             f"an integer from 8 to {MAX_EVALUATIONS} (each is a FEM solve)")
        for name in ("search_size_factor", "check_size_factor"):
            if not 0.05 <= getattr(self, name) <= 20:
                raise ValueError(f"OptimizeSpec: {name} = {getattr(self, name)!r} must be in [0.05, 20]")

    @property
    def lower(self) -> np.ndarray:
        return np.array([self.b_min, self.h_min, self.l_min])

    @property
    def upper(self) -> np.ndarray:
        return np.array([self.b_max, self.h_max, self.l_max])


def quick_spec(spec: OptimizeSpec) -> OptimizeSpec:
    """The smoke-run settings: at most 12 FEM evaluations and 256 screened designs."""
    return replace(spec, max_evaluations=min(spec.max_evaluations, 12),
                   n_seed=min(spec.n_seed, 256))


def check_box(spec: OptimizeSpec, base: DBMAParams) -> None:
    """ValueError unless every (b, h, l) in the box builds a DBMA: the limits (h + b < c, h + b
    < ls, b < a, l < e, ll > 2 c + b + arm_gap) bind at the largest corner, DBMAParams' ranges
    and slenderness limits (10 nm <= h, ll / b <= 10^4, ...) at the others: all eight are
    checked, the largest first."""
    for ends in itertools.product(("max", "min"), repeat=3):
        names = [f"{n}_{end}" for n, end in zip(NAMES, ends)]
        b, h, l = (getattr(spec, name) for name in names)
        try:
            check_layout(replace(base, b=b, h=h, l=l), DBMALayout())
        except ValueError as error:
            raise ValueError(f"OptimizeSpec: the corner ({', '.join(names)}) = ({b!r}, {h!r}, "
                             f"{l!r}) m cannot be built: {error}") from None


def constraints_of(spec: OptimizeSpec, yield_strength: float) -> list[tuple]:
    """(name, metric key, bound, kind) of each active-able constraint; kind '>=' or '<='."""
    out = [("stress", "von_mises_at_stroke", yield_strength / spec.safety_factor, "<=")]
    if spec.min_frequency_hz > 0:
        out.append(("frequency", "fn_working", spec.min_frequency_hz, ">="))
    if spec.min_output_stiffness > 0:
        out.append(("output_stiffness", "k_out", spec.min_output_stiffness, ">="))
    return out


def margins(metrics: dict, constraints: list[tuple]) -> np.ndarray:
    """log(value / bound) for '>=', log(bound / value) for '<=': >= 0 where met (-)."""
    return np.array([math.log(metrics[key] / bound) * (1 if kind == ">=" else -1)
                     for _, key, bound, kind in constraints])


def constraint_table(metrics: dict, constraints: list[tuple]) -> list[dict]:
    """Each constraint's value, bound, margin, whether met and active (within 1 %)."""
    return [{"constraint": name, "metric": key, "value": metrics[key], "bound": bound,
             "kind": kind, "margin": metrics[key] / bound - 1,
             "met": bool(metrics[key] >= bound if kind == ">=" else metrics[key] <= bound),
             "active": bool(abs(metrics[key] / bound - 1) <= ACTIVE_TOL)}
            for name, key, bound, kind in constraints]


def at_bounds(spec: OptimizeSpec, x) -> list[str]:
    """Design variables within 1 % of their range from a bound, e.g. ["l = l_min"]."""
    out = []
    for name, v, lo, hi in zip(NAMES, x, spec.lower, spec.upper):
        out += [f"{name} = {name}_min"] if v - lo <= ACTIVE_TOL * (hi - lo) else []
        out += [f"{name} = {name}_max"] if hi - v <= ACTIVE_TOL * (hi - lo) else []
    return out
