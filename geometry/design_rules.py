"""Fabrication design-rule check of a 2-D flexure geometry (eight-bar thesis, Chapter 6).

A geometry is a list of rectangles (:class:`~flexfem.geometry.flexure_linkage.Part`: a
centre-line and a width), e.g. ``eightbar_layout(params).parts``. Rules (data/fabrication_rules.toml,
thesis p. 38): every beam at least ``min_beam_width`` wide; no two parts closer than
``min_gap`` without touching; and each part's gap to its nearest non-touching neighbour (the
trench it faces) at most ``max_gap`` -- our reading of "the gap width is between 0.7 micron
and 50 microns" for a layout with open space (docs/eightbar.md).
"""
from dataclasses import dataclass

import numpy as np

from ..data import load_toml
from ..fem import checks
from .flexure_linkage import inside_convex, polygon_distance
from .linkage_clearance import segment_distance

UM = 1e-6


@dataclass(frozen=True)
class FabricationRules:
    """min_beam_width, min_gap, max_gap in m; source: where they come from."""

    min_beam_width: float
    min_gap: float
    max_gap: float
    source: str = "user-defined"

    def __post_init__(self):
        for name in ("min_beam_width", "min_gap", "max_gap"):
            checks.positive(name, getattr(self, name), owner="FabricationRules", unit="m")
        if not self.max_gap > self.min_gap:
            raise ValueError(f"max_gap = {self.max_gap} m must be > min_gap = {self.min_gap} m")


def fabrication_rules(name: str = "thesis_mems") -> FabricationRules:
    """Rules ``name`` from data/fabrication_rules.toml, in m."""
    table = load_toml("fabrication_rules.toml")
    if name not in table or "min_beam_width_um" not in table[name]:
        known = [k for k, v in table.items() if "min_beam_width_um" in v]
        raise ValueError(f"unknown fabrication rules {name!r}; known: {known}")
    t = table[name]
    return FabricationRules(t["min_beam_width_um"] * UM, t["min_gap_um"] * UM,
                            t["max_gap_um"] * UM, t["source"])


@dataclass(frozen=True)
class Violation:
    """kind: "beam_width", "gap_too_small" or "gap_too_large"; value and bound in m;
    location (x, y) in m; parts: the part name(s) involved."""

    kind: str
    value: float
    bound: float
    location: tuple
    parts: tuple

    def as_dict(self) -> dict:
        return {"kind": self.kind, "value_m": self.value, "bound_m": self.bound,
                "x_m": self.location[0], "y_m": self.location[1], "parts": " / ".join(self.parts)}


def _distance(P, Q) -> float:
    """Distance (m) between two convex polygons, 0 where they touch or overlap."""
    if inside_convex(P[0], Q) or inside_convex(Q[0], P):
        return 0.0
    return min(segment_distance(a0, a1, b0, b1)
               for a0, a1 in zip(P, np.roll(P, -1, axis=0))
               for b0, b1 in zip(Q, np.roll(Q, -1, axis=0)))


def gaps(parts) -> list:
    """[(distance m, location (x, y) m, name_a, name_b)]: each part's gap to its nearest
    neighbour (the part it faces across the narrowest trench), and every gap narrower than
    that to another part is included too (pairs listed once)."""
    polys = [np.asarray(p.corners()) for p in parts]
    n = len(parts)
    dist = np.full((n, n), np.inf)
    for i in range(n):
        for k in range(i + 1, n):
            dist[i, k] = dist[k, i] = _distance(polys[i], polys[k])
    pairs = set()
    for i in range(n):
        row = np.where(dist[i] > 0, dist[i], np.inf)
        if np.isfinite(row).any():
            pairs.add(tuple(sorted((i, int(np.argmin(row))))))
    out = []
    for i, k in sorted(pairs):
        d, where = polygon_distance(polys[i], polys[k])
        out.append((d, tuple(float(c) for c in where), parts[i].name, parts[k].name))
    return out


def small_gaps(parts, bound: float) -> list:
    """[(distance m, location, name_a, name_b)] of every pair of parts closer than ``bound``
    (m) without touching."""
    polys = [np.asarray(p.corners()) for p in parts]
    out = []
    for i in range(len(parts)):
        for k in range(i + 1, len(parts)):
            d = _distance(polys[i], polys[k])
            if 0 < d < bound:
                out.append((d, polygon_distance(polys[i], polys[k])[1], parts[i].name,
                            parts[k].name))
    return out


def check_design_rules(parts, rules: FabricationRules | None = None) -> list:
    """Violations of ``rules`` (default: the thesis' MEMS rules) by the rectangles ``parts``
    (m): beams narrower than min_beam_width, facing gaps outside [min_gap, max_gap]."""
    rules = rules or fabrication_rules()
    parts = list(parts)
    if not parts:
        raise ValueError("parts is empty: nothing to check")
    found = []
    for p in parts:
        if p.width < rules.min_beam_width * (1 - 1e-9):
            centre = tuple((np.asarray(p.p0) + np.asarray(p.p1)) / 2)
            found.append(Violation("beam_width", p.width, rules.min_beam_width,
                                   tuple(float(c) for c in centre), (p.name,)))
    for d, where, a, b in small_gaps(parts, rules.min_gap):
        found.append(Violation("gap_too_small", d, rules.min_gap, where, (a, b)))
    for d, where, a, b in gaps(parts):
        if d > rules.max_gap:
            found.append(Violation("gap_too_large", d, rules.max_gap, where, (a, b)))
    return found


def violation_summary(violations) -> dict:
    """Count of violations by kind, and the worst value of each kind (m)."""
    out = {}
    for v in violations:
        entry = out.setdefault(v.kind, {"count": 0, "worst_m": v.value, "bound_m": v.bound})
        entry["count"] += 1
        worse = min if v.kind != "gap_too_large" else max
        entry["worst_m"] = worse(entry["worst_m"], v.value)
    return out
