"""Tolerances of a study: a Monte Carlo of the outputs over the manufacturing scatter of its
parameters, their spread, and which tolerance matters most (first- and total-order Sobol
indices by SALib: Saltelli's sampling and Jansen/Saltelli estimators, not hand-written).

A study file declares, beside its base design::

    [tolerances]
    n = 256                  # Saltelli base sample: n (k + 2) designs for k toleranced names
    seed = 0
    [tolerances.parameters]
    flexure_width = { nominal = 0.3e-3, tolerance = 10e-6, distribution = "normal" }
    base_flexure_width = { nominal = 0.4e-3, tolerance = 10e-6 }   # normal by default

``tolerance`` is the half-width of the band a shop guarantees: for "normal" it is three
standard deviations (99.7 % of parts inside nominal +- tolerance), for "uniform" the band's
half-width (every value equally likely). The designs are ordinary cases of the study: stored
as they complete, resumable, on local workers or Dask. SI units.
"""
from dataclasses import dataclass, field
import math

import numpy as np

DISTRIBUTIONS = ("normal", "uniform")
KEYS = ("n", "seed", "parameters")


@dataclass(frozen=True)
class Tolerance:
    """One toleranced parameter: ``nominal`` +- ``tolerance`` (SI), ``distribution``."""

    nominal: float
    tolerance: float
    distribution: str = "normal"

    def __post_init__(self):
        for name in ("nominal", "tolerance"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) \
                    or not math.isfinite(value):
                raise ValueError(f"tolerance {name} = {value!r} must be a finite number")
        if not self.tolerance > 0:
            raise ValueError(f"tolerance = {self.tolerance!r} must be > 0")
        if self.distribution not in DISTRIBUTIONS:
            raise ValueError(f"distribution = {self.distribution!r} must be one of "
                             f"{DISTRIBUTIONS}")

    def salib(self) -> tuple[list, str]:
        """(bounds, dist) as SALib's problem takes them."""
        if self.distribution == "normal":
            return [self.nominal, self.tolerance / 3], "norm"
        return [self.nominal - self.tolerance, self.nominal + self.tolerance], "unif"


@dataclass(frozen=True)
class Tolerances:
    """The study's toleranced parameters {name: Tolerance}, Saltelli's base sample ``n`` (a
    power of two) and the scrambling ``seed``."""

    parameters: dict = field(default_factory=dict)
    n: int = 256
    seed: int = 0

    def __post_init__(self):
        if not self.parameters:
            raise ValueError("[tolerances.parameters] is empty: give at least one")
        if not (isinstance(self.n, int) and self.n >= 8 and self.n & (self.n - 1) == 0):
            raise ValueError(f"tolerances.n = {self.n!r} must be a power of two >= 8 "
                             "(Sobol' sequences balance only there)")
        if not (isinstance(self.seed, int) and self.seed >= 0):
            raise ValueError(f"tolerances.seed = {self.seed!r} must be an integer >= 0")

    @property
    def problem(self) -> dict:
        names = list(self.parameters)
        specs = [self.parameters[k].salib() for k in names]
        return {"num_vars": len(names), "names": names, "bounds": [b for b, _ in specs],
                "dists": [d for _, d in specs]}

    def points(self) -> list[dict]:
        """The n (k + 2) designs of Saltelli's scheme, {name: value}, in SALib's order."""
        from SALib.sample import sobol

        samples = sobol.sample(self.problem, self.n, calc_second_order=False,
                               scramble=True, seed=self.seed)
        return [dict(zip(self.problem["names"], map(float, row))) for row in samples]

    def analyze(self, outputs: list[dict]) -> dict:
        """{metric: {mean, std, low, high (the 0.135 and 99.865 percentiles: +-3 sigma),
        first_order {name: S1}, total_order {name: ST}, first_order_conf, total_order_conf
        (95 % bootstrap half-widths), dominant (the name of the largest ST)}} over the
        metrics every design returned as finite numbers; ``outputs`` in :meth:`points`' order."""
        from SALib.analyze import sobol

        names = self.problem["names"]
        metrics = sorted(set.intersection(*(set(o) for o in outputs)))
        out = {}
        for metric in metrics:
            y = np.array([o[metric] for o in outputs], dtype=float)
            if not np.all(np.isfinite(y)) or np.ptp(y) == 0:
                continue
            s = sobol.analyze(self.problem, y, calc_second_order=False, seed=self.seed)
            total = dict(zip(names, map(float, s["ST"])))
            out[metric] = {
                "mean": float(y.mean()), "std": float(y.std(ddof=1)),
                "low": float(np.percentile(y, 0.135)), "high": float(np.percentile(y, 99.865)),
                "first_order": dict(zip(names, map(float, s["S1"]))),
                "first_order_conf": dict(zip(names, map(float, s["S1_conf"]))),
                "total_order": total,
                "total_order_conf": dict(zip(names, map(float, s["ST_conf"]))),
                "dominant": max(total, key=total.get)}
        return out


def tolerances_from_dict(table) -> Tolerances:
    """The [tolerances] table of a study file; ValueError naming the bad key."""
    if not isinstance(table, dict):
        raise ValueError(f"[tolerances] must be a table, not {table!r}")
    unknown = sorted(set(table) - set(KEYS))
    if unknown:
        raise ValueError(f"[tolerances]: unknown key(s) {unknown}; allowed: {list(KEYS)}")
    raw = table.get("parameters", {})
    if not isinstance(raw, dict):
        raise ValueError("[tolerances.parameters] must be a table of "
                         "NAME = { nominal, tolerance, distribution }")
    parameters = {}
    for name, spec in raw.items():
        if not isinstance(spec, dict) or set(spec) - {"nominal", "tolerance", "distribution"} \
                or not {"nominal", "tolerance"} <= set(spec):
            raise ValueError(f"tolerances.parameters.{name} = {spec!r} must be "
                             "{ nominal = X, tolerance = DX, distribution = \"normal\" | "
                             "\"uniform\" }")
        try:
            parameters[name] = Tolerance(**spec)
        except (TypeError, ValueError) as error:
            raise ValueError(f"tolerances.parameters.{name}: {error}") from None
    return Tolerances(parameters, table.get("n", 256), table.get("seed", 0))
