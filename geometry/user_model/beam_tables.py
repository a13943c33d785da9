"""The beam declarations of a model file, ``[[beam]]``, ``[[rigid]]`` and ``[beam_model]``
(docs/model_files.md, "The beam model"), validated into a :class:`BeamSpec` with SI values.

Coordinates and sizes are numbers (m) or expressions of the geometry's parameters
(``"L + hs / 2"``, ``"L / (2 * sqrt(2))"``): + - * / ** and parentheses, sqrt, sin, cos, tan,
atan, atan2, abs, pi (expressions.py), so that a sweep that changes L moves the beams with the
sketch. Errors name the model file and line.
"""
from dataclasses import dataclass, field
import math

import numpy as np

from ...fem import checks
from .expressions import evaluate_expression, names_in
from .tables import Locator, check_keys, is_number

BEAM_KEYS = ("points", "thickness", "depth", "elements")
RIGID_KEYS = ("joins", "groups", "blocks")
OPTION_KEYS = ("elements", "shear", "root_extension", "crossings", "roots", "notch_correction")


@dataclass(frozen=True)
class Profile:
    """In-plane thickness t(s) (m) along a beam, s its arc length from the first point (m):
    linear between the values at the points' arc lengths ``arc``, or an ``expression`` of s
    and the parameters ``names``; ``breaks``: arc lengths (m) where the profile changes its
    form (a root fillet's end), each meshed apart (reduced/model_file.py)."""

    arc: tuple
    values: tuple = ()
    expression: str | None = None
    names: dict = field(default_factory=dict)
    breaks: tuple = ()

    def __post_init__(self):
        # the tables as arrays once: np.interp converting the tuples cost 8x the interpolation
        # (a notch's profile is sampled ~600 times per beam model)
        object.__setattr__(self, "_table", (np.asarray(self.arc, dtype=float),
                                            np.asarray(self.values, dtype=float)))

    def __call__(self, s: float) -> float:
        if self.expression is None:
            return float(np.interp(s, *self._table))
        return evaluate_expression(self.expression, {**self.names, "s": s},
                                   "[[beam]] thickness")

    def at(self, s: np.ndarray) -> np.ndarray:
        """t (m) at the arc lengths ``s`` (k,) m: the same values as one call a point."""
        if self.expression is None:
            return np.interp(s, *self._table)
        return np.array([self(x) for x in s.tolist()])

    @property
    def length(self) -> float:
        return self.arc[-1]


@dataclass(frozen=True)
class BeamLine:
    """One flexure: centre-line ``points`` ((k, 2) tuple, m), in-plane ``thickness`` (a
    Profile: t(s), m), out-of-plane ``depth`` (m), ``elements`` per segment."""

    points: tuple
    thickness: Profile
    depth: float
    elements: int
    source: str = ""


@dataclass(frozen=True)
class RigidBody:
    """A rigid block: the beam points it ``joins`` (m), its ``groups`` {continuum group name:
    point standing for it (m), e.g. the face's centre}, its ``blocks`` (rectangles given by
    two opposite corners, or, from a body's polygons, three or more vertices, m) whose mass
    it carries."""

    joins: tuple
    groups: dict
    blocks: tuple = ()
    source: str = ""


@dataclass(frozen=True)
class BeamSpec:
    """The beam model of a model file: beams, rigid bodies and options (elements per segment
    by default, Timoshenko shear, root extension x root thickness at joined ends, crossings
    "rigid" (the leaves' solid joint, reduced/crossings.py) or "weld", oblique roots
    at the "acute_edge" (reduced/roots.py) or the "centre_line"'s meeting with the
    face), and each straight notch corrected by its own 2-D model (reduced/hinge_patch.py)
    unless ``notch_correction`` is false)."""

    beams: tuple
    rigid: tuple
    elements: int = 20
    shear: bool = True
    root_extension: float = 0.38
    crossings: str = "rigid"
    roots: str = "acute_edge"
    notch_correction: bool = True
    source: str = ""
    groups: dict = field(default_factory=dict)


def _point(raw, names, where) -> tuple:
    if not (isinstance(raw, list) and len(raw) == 2):
        raise ValueError(f"{where}: {raw!r} must be a point [x, y] (m)")
    return tuple(evaluate_expression(v, names, where) for v in raw)


def _points(raw, names, where, least: int = 1) -> tuple:
    if not (isinstance(raw, list) and len(raw) >= least):
        raise ValueError(f"{where} must be a list of at least {least} points [x, y] (m)")
    return tuple(_point(p, names, where) for p in raw)


def _length(value, names, where) -> float:
    """A length > 0 (m): a number or an expression of the parameters."""
    v = evaluate_expression(value, names, where)
    return checks.positive(where if v == value else f"{where} = {value!r}", v, unit="m")


def _beam(entry, i, names, depth, elements, loc: Locator) -> BeamLine:
    check_keys(entry, BEAM_KEYS, loc, "beam", i, "[[beam]]")
    for key in ("points", "thickness"):
        if key not in entry:
            raise loc.error(f"[[beam]] needs {key}", "beam", None, i)
    try:
        points = _points(entry["points"], names, "[[beam]] points", 2)
        ts = _profile(entry["thickness"], points, names)
        d = _length(entry["depth"], names, "[[beam]] depth") if "depth" in entry else depth
        n = (checks.count("[[beam]] elements", entry["elements"]) if "elements" in entry
             else elements)
    except ValueError as error:
        key = next((k for k in BEAM_KEYS if f"] {k}" in str(error)), None)
        raise loc.error(str(error), "beam", key, i) from None
    if d is None:
        raise loc.error("[[beam]] depth (out-of-plane, m) is needed: [section] has no "
                        "thickness", "beam", None, i)
    for a, b in zip(points, points[1:]):
        if math.dist(a, b) == 0:
            raise loc.error(f"[[beam]] points: {list(a)} is repeated (a zero-length segment)",
                            "beam", "points", i)
    return BeamLine(points, ts, d, n, loc.at("beam", "points", i))


def _uses_s(value) -> bool:
    """True for an expression string that names s (the arc length)."""
    return "s" in names_in(value)


def _profile(raw, points, names) -> Profile:
    """The Profile of a [[beam]] thickness: one value, one per point, or an expression of s;
    checked > 0 at the points and (an expression) at 64 stations along the beam."""
    where = "[[beam]] thickness"
    arc = tuple(np.concatenate([[0.0], np.cumsum([math.dist(a, b) for a, b in
                                                  zip(points, points[1:])])]).tolist())
    if _uses_s(raw):
        if "s" in names:
            raise ValueError(f"{where}: 's' is the arc length here, but also a parameter")
        profile = Profile(arc, expression=raw, names=dict(names))
        for s in np.linspace(0.0, arc[-1], 64):
            if not profile(s) > 0:
                raise ValueError(f"{where} = {raw!r} is {profile(s)} at s = {s:.4g} m; it "
                                 "must be > 0 along the beam")
        return profile
    listed = isinstance(raw, list)
    if listed and len(raw) != len(points):
        raise ValueError(f"{where}: {len(raw)} values for {len(points)} points (give one, "
                         "one per point, or an expression of s, the arc length)")
    values = tuple(_length(t, names, where) for t in (raw if listed else [raw] * len(points)))
    return Profile(arc, values)


def _rigid(entry, i, names, loc: Locator) -> RigidBody:
    check_keys(entry, RIGID_KEYS, loc, "rigid", i, "[[rigid]]")
    try:
        joins = _points(entry.get("joins"), names, "[[rigid]] joins", 1)
        groups = entry.get("groups", {})
        if not isinstance(groups, dict):
            raise ValueError(f"[[rigid]] groups = {groups!r} must be a table {{ NAME = [x, y] }}")
        points = {str(g): _point(p, names, f"[[rigid]] groups {g}") for g, p in groups.items()}
        blocks = entry.get("blocks", [])
        if not isinstance(blocks, list):
            raise ValueError(f"[[rigid]] blocks = {blocks!r} must be a list of rectangles "
                             "[[x0, y0], [x1, y1]]")
        rects = tuple(_points(b, names, "[[rigid]] blocks", 2) for b in blocks)
        for r in rects:
            if len(r) != 2 or r[0][0] == r[1][0] or r[0][1] == r[1][1]:
                raise ValueError(f"[[rigid]] blocks: {[list(p) for p in r]} must be two "
                                 "opposite corners of a rectangle of non-zero area")
    except ValueError as error:
        key = next((k for k in RIGID_KEYS if f"] {k}" in str(error)), None)
        raise loc.error(str(error), "rigid", key, i) from None
    return RigidBody(joins, points, rects, loc.at("rigid", "joins", i))


def beam_options(raw, loc: Locator) -> dict:
    raw = check_keys(raw, OPTION_KEYS, loc, "beam_model")
    out = {}
    if "elements" in raw:
        try:
            out["elements"] = checks.count("[beam_model] elements", raw["elements"])
        except ValueError as error:
            raise loc.error(str(error), "beam_model", "elements") from None
    for key in ("shear", "notch_correction"):
        if key in raw:
            value = {"true": True, "false": False}.get(raw[key], raw[key])  # from --set
            if not isinstance(value, bool):
                raise loc.error(f"[beam_model] {key} = {raw[key]!r} must be true or false",
                                "beam_model", key)
            out[key] = value
    if "root_extension" in raw:
        v = raw["root_extension"]
        if not (is_number(v) and 0 <= v <= 2):
            raise loc.error(f"[beam_model] root_extension = {v!r} must be a number in [0, 2] "
                            "(x root thickness)", "beam_model", "root_extension")
        out["root_extension"] = float(v)
    if "crossings" in raw:
        if raw["crossings"] not in ("rigid", "weld"):
            raise loc.error(f"[beam_model] crossings = {raw['crossings']!r} must be \"rigid\" "
                            "(the leaves' solid joint) or \"weld\" (a point)", "beam_model",
                            "crossings")
        out["crossings"] = raw["crossings"]
    if "roots" in raw:
        if raw["roots"] not in ("acute_edge", "centre_line"):
            raise loc.error(f"[beam_model] roots = {raw['roots']!r} must be \"acute_edge\" "
                            "(an oblique beam starts where its whole section has left the "
                            "block) or \"centre_line\"", "beam_model", "roots")
        out["roots"] = raw["roots"]
    return out


def parse_beams(raw: dict, names: dict, depth, loc: Locator) -> BeamSpec | None:
    """The BeamSpec of the model file's raw tables (None without [[beam]]); ``names``: the
    geometry's parameters {name: m}; ``depth``: the default out-of-plane depth (m, [section]
    thickness) or None."""
    beams, rigid = raw.get("beam"), raw.get("rigid", [])
    if beams is None:
        if "rigid" in raw or "beam_model" in raw:
            raise loc.error("[[rigid]] and [beam_model] describe a beam model: declare its "
                            "beams with [[beam]]", "rigid" if "rigid" in raw else "beam_model")
        return None
    for name, value in (("beam", beams), ("rigid", rigid)):
        if not (isinstance(value, list) and all(isinstance(e, dict) for e in value)):
            raise loc.error(f"{name} must be an array of tables: [[{name}]] ...", None, name)
    options = beam_options(raw.get("beam_model", {}), loc)
    elements = options.get("elements", 20)
    lines = tuple(_beam(e, i, names, depth, elements, loc) for i, e in enumerate(beams))
    bodies = tuple(_rigid(e, i, names, loc) for i, e in enumerate(rigid))
    groups = {}
    for i, body in enumerate(bodies):
        for g in body.groups:
            if g in groups:
                raise loc.error(f"[[rigid]] groups: {g!r} is given twice", "rigid", "groups", i)
            groups[g] = i
    return BeamSpec(lines, bodies, source=str(loc.path), groups=groups, **options)
