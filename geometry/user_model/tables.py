"""Validation of the tables of a model file, one function per table. Each takes the raw
TOML value and a :class:`Locator` (to name the file and line in errors) and returns frozen
dataclasses with SI values."""
from dataclasses import dataclass, field
from pathlib import Path

from ...fem import checks
from ...fem.budget import MAX_FREQUENCY_POINTS, MAX_MODES
from .expressions import is_number
from .toml_lines import find_line

SECTION_KINDS = ("plane_stress", "plane_strain", "solid")
LOAD_KINDS = ("force", "traction", "pressure")
SOLVERS = ("auto", "direct", "amg")
#: Lengths a flexure mechanism has (m): a thinner part or a larger one is a units mistake.
LENGTHS = (1e-6, 10.0)


@dataclass(frozen=True)
class Locator:
    """The model file (its path and text): ``at(table, key, index)`` -> 'file line N: '."""

    path: Path
    text: str

    def at(self, table=None, key=None, index: int = 0) -> str:
        line = find_line(self.text, table, key, index)
        if line is None and key is not None and table is not None:
            line = find_line(self.text, table, None, index)
        return f"{self.path} line {line}" if line else f"{self.path}"

    def error(self, message: str, table=None, key=None, index: int = 0) -> ValueError:
        return ValueError(f"{self.at(table, key, index)}: {message}")


@dataclass(frozen=True)
class SectionSpec:
    """kind: plane_stress | plane_strain | solid; thickness: out-of-plane thickness (m), 1
    for plane strain by default and for solids."""

    kind: str
    thickness: float = 1.0


@dataclass(frozen=True)
class GroupEntry:
    """An entry of the model file on Physical group ``group``, read at ``source`` (by keyword)."""

    group: str
    source: str = field(default="", kw_only=True)


@dataclass(frozen=True)
class Refinement(GroupEntry):
    """Element ``size`` (m) within ``distance`` (m) of group ``group``."""

    size: float
    distance: float


@dataclass(frozen=True)
class MeshOptions:
    """order: 1 or 2 (element order, applied by Model); size: largest element size (m) or None
    for the geometry file's sizes; refine: Refinement tuple."""

    order: int = 2
    size: float | None = None
    refine: tuple = ()


@dataclass(frozen=True)
class SupportSpec(GroupEntry):
    """group held: all components at 0 (components None) or {axis index: value (m)}."""

    components: dict | None


@dataclass(frozen=True)
class LoadSpec(GroupEntry):
    """kind 'force' (total force on the group, N) or 'traction' (Pa): vector per axis."""

    kind: str
    vector: tuple


@dataclass(frozen=True)
class SelectRule(GroupEntry):
    """Physical group ``group`` made of the CAD entities of dimension ``dim`` where the
    condition ``where`` holds (see selection.py)."""

    dim: int
    where: str


@dataclass(frozen=True)
class Harmonic:
    """A frequency response of the model file's loads: ``group``'s mean displacement along
    ``component`` ('x', 'y', 'z') at ``points`` frequencies from 0 to ``f_max`` (Hz), modal
    damping ratio ``damping`` (-), ``n_modes`` modes (plus the static correction)."""

    group: str
    component: str
    f_max: float
    points: int = 201
    damping: float = 0.02
    n_modes: int = 20


@dataclass(frozen=True)
class Analysis:
    """modes: number of natural frequencies (None: none); steps: load steps of a nonlinear
    (large-deflection) solve (None: linear only); solver: 'auto', 'direct' or 'amg';
    compliance: a boundary group whose rigid-face compliance matrix is reported (None: none);
    buckling: number of linear buckling factors of the loads (None: none); harmonic: a
    Harmonic (None: none); the stroke limits' safety_factor (>= 1), mean_stroke (m, the
    offset or preload the stroke cycles about) and fatigue criterion ('goodman' or
    'soderberg'; studies/user_model/stroke.py); stroke_check: check them by a large-deflection
    solve (studies/user_model/stroke_check.py)."""

    modes: int | None = None
    steps: int | None = None
    solver: str = "auto"
    compliance: str | None = None
    buckling: int | None = None
    harmonic: Harmonic | None = None
    safety_factor: float = 1.0
    mean_stroke: float = 0.0
    fatigue: str = "goodman"
    stroke_check: bool = False


def check_keys(raw, allowed, loc: Locator, table, index: int = 0, what=None) -> dict:
    """Refuse a non-table and unknown keys by name."""
    what = what or f"[{table}]"
    if not isinstance(raw, dict):
        raise loc.error(f"{what} must be a table, not {raw!r}", table, None, index)
    unknown = sorted(set(raw) - set(allowed))
    if unknown:
        raise loc.error(f"{what}: unknown key{'s' if len(unknown) > 1 else ''} "
                        f"{', '.join(map(repr, unknown))}; allowed: {', '.join(allowed)}",
                        table, unknown[0], index)
    return raw


def located(check, raw: dict, key: str, loc: Locator, table, index: int = 0, what=None,
            at=None, **options):
    """``check`` (one of fem/checks.py's) of ``raw[key]``, its refusal naming the file and
    the line of ``at`` (default ``key``): ``located(checks.count, raw, "modes", loc,
    "analysis")``."""
    try:
        return check(f"{what or f'[{table}]'} {key}", raw[key], **options)
    except checks.InputError as error:
        raise loc.error(str(error), table, at or key, index) from None


def positive(raw: dict, key: str, loc: Locator, table, index: int = 0, what=None):
    """``raw[key]`` as a float > 0 (SI), else the model file's refusal."""
    return located(checks.positive, raw, key, loc, table, index, what, unit="SI")


def parse_section(raw, dim: int, loc: Locator) -> SectionSpec:
    raw = check_keys(raw, ("kind", "thickness"), loc, "section")
    kind = raw.get("kind")
    if kind not in SECTION_KINDS:
        raise loc.error(f"[section] kind = {kind!r}; choose one of {', '.join(SECTION_KINDS)}",
                        "section", "kind")
    if (kind == "solid") != (dim == 3):
        raise loc.error(f"[section] kind = {kind!r} does not fit dim = {dim} (2-D: plane_stress "
                        "or plane_strain; 3-D: solid)", "section", "kind")
    if kind == "solid":
        if "thickness" in raw:
            raise loc.error("[section] thickness is for 2-D sections; a solid has none",
                            "section", "thickness")
        return SectionSpec(kind)
    if "thickness" not in raw:
        if kind == "plane_stress":
            raise loc.error("[section] plane_stress needs thickness (m, out of plane)", "section")
        return SectionSpec(kind)
    thickness = positive(raw, "thickness", loc, "section")
    if not LENGTHS[0] <= thickness <= LENGTHS[1]:
        raise loc.error(f"[section] thickness = {thickness!r} m is outside {LENGTHS[0]:g} to "
                        f"{LENGTHS[1]:g} m; lengths are in m", "section", "thickness")
    return SectionSpec(kind, thickness)


def parse_mesh(raw, loc: Locator) -> MeshOptions:
    raw = check_keys(raw, ("order", "size", "refine"), loc, "mesh")
    order = raw.get("order", 2)
    if order not in (1, 2) or isinstance(order, bool):
        raise loc.error(f"[mesh] order = {order!r} must be 1 or 2", "mesh", "order")
    size = positive(raw, "size", loc, "mesh") if "size" in raw else None
    refine = raw.get("refine", [])
    if not isinstance(refine, list):
        raise loc.error("[mesh] refine must be a list of {group, size, distance} tables",
                        "mesh", "refine")
    rules = []
    for r in refine:
        what = "[mesh] refine entry"
        check_keys(r, ("group", "size", "distance"), loc, "mesh", what=what)
        if not isinstance(r.get("group"), str) or "size" not in r or "distance" not in r:
            raise loc.error(f"{what} {r!r} needs group, size and distance (m)", "mesh", "refine")
        rules.append(Refinement(r["group"], positive(r, "size", loc, "mesh", what=what),
                                positive(r, "distance", loc, "mesh", what=what),
                                source=loc.at("mesh", "refine")))
    return MeshOptions(int(order), size, tuple(rules))


def _entries(raw, name: str, loc: Locator) -> list:
    if not isinstance(raw, list) or not all(isinstance(e, dict) for e in raw):
        raise loc.error(f"{name} must be an array of tables: [[{name}]] ...", None, name)
    return raw


def _group(entry: dict, table: str, loc: Locator, i: int) -> str:
    group = entry.get("group")
    if not isinstance(group, str) or not group:
        raise loc.error(f"[[{table}]] needs group = \"NAME\" (a Physical group)", table, "group", i)
    return group


def parse_supports(raw, dim: int, loc: Locator) -> tuple:
    axes = ("x", "y", "z")[:dim]
    out = []
    for i, entry in enumerate(_entries(raw, "supports", loc)):
        check_keys(entry, ("group", *axes), loc, "supports", i, "[[supports]]")
        group = _group(entry, "supports", loc, i)
        components = {}
        for k, axis in enumerate(axes):
            if axis in entry:
                if not is_number(entry[axis]):
                    raise loc.error(f"[[supports]] {axis} = {entry[axis]!r} must be a number "
                                    "(prescribed displacement, m)", "supports", axis, i)
                components[k] = float(entry[axis])
        out.append(SupportSpec(group, components or None, source=loc.at("supports", "group", i)))
    return tuple(out)


def parse_loads(raw, dim: int, loc: Locator) -> tuple:
    out = []
    for i, entry in enumerate(_entries(raw, "loads", loc)):
        check_keys(entry, ("group", *LOAD_KINDS), loc, "loads", i, "[[loads]]")
        group = _group(entry, "loads", loc, i)
        kinds = [k for k in LOAD_KINDS if k in entry]
        if len(kinds) != 1:
            raise loc.error(f"[[loads]] on {group!r} needs exactly one of force (N, total), "
                            "traction (Pa)", "loads", "group", i)
        kind, value = kinds[0], entry[kinds[0]]
        if kind == "pressure":
            raise loc.error("[[loads]] pressure is not available yet (flexfem.fem has no "
                            "pressure load); give traction = [...] (Pa) on a flat face",
                            "loads", "pressure", i)
        if not (isinstance(value, list) and len(value) == dim and all(map(is_number, value))):
            raise loc.error(f"[[loads]] {kind} = {value!r} must be a list of {dim} numbers "
                            f"({'N' if kind == 'force' else 'Pa'})", "loads", kind, i)
        out.append(LoadSpec(group, kind, tuple(map(float, value)), source=loc.at("loads", kind, i)))
    return tuple(out)


def parse_selects(raw, loc: Locator) -> tuple:
    from .selection import compile_rule

    out = []
    for i, entry in enumerate(_entries(raw, "select", loc)):
        check_keys(entry, ("group", "dim", "where"), loc, "select", i, "[[select]]")
        group = _group(entry, "select", loc, i)
        dim = entry.get("dim")
        if dim not in (0, 1, 2, 3) or isinstance(dim, bool):
            raise loc.error(f"[[select]] dim = {dim!r} must be 0, 1, 2 or 3 (point, curve, "
                            "surface, volume)", "select", "dim", i)
        try:
            compile_rule(entry.get("where"))
        except ValueError as error:
            raise loc.error(f"[[select]] where: {error}", "select", "where", i) from None
        out.append(SelectRule(group, int(dim), entry["where"], source=loc.at("select", "where", i)))
    return tuple(out)


def parse_harmonic(raw, loc: Locator) -> Harmonic:
    """[analysis] harmonic = { group, component, f_max, points, damping, n_modes }."""
    what = "[analysis] harmonic"
    raw = check_keys(raw, ("group", "component", "f_max", "points", "damping", "n_modes"),
                     loc, "analysis", what=what)
    for key in ("group", "component", "f_max"):
        if key not in raw:
            raise loc.error(f"{what}: '{key}' is required", "analysis", "harmonic")
    if not isinstance(raw["group"], str):
        raise loc.error(f"{what} group = {raw['group']!r} must be a group name", "analysis",
                        "harmonic")
    if raw["component"] not in ("x", "y", "z"):
        raise loc.error(f"{what} component = {raw['component']!r}; choose x, y or z",
                        "analysis", "harmonic")
    rules = {"f_max": (checks.positive, {"unit": "Hz"}), "points": (checks.count, {"least": 3}),
             "damping": (checks.in_range, {"bounds": (0, 1), "closed": False}),
             "n_modes": (checks.count, {})}
    for key, (check, options) in rules.items():
        if key in raw:
            located(check, raw, key, loc, "analysis", what=what, at="harmonic", **options)
    for key, cap in (("points", MAX_FREQUENCY_POINTS), ("n_modes", MAX_MODES)):
        if raw.get(key, 0) > cap:
            raise loc.error(f"{what} {key} = {raw[key]:,} is above the most flexfem solves, "
                            f"{cap:,}: " + ("the response is kept at every frequency for every "
                                            "DOF (points x DOFs x 16 bytes: 10,000 x 100,000 "
                                            "DOFs is 16 GB)" if key == "points" else
                                            "each mode is a vector of the model's size and "
                                            "the solve's time grows as their square"),
                            "analysis", "harmonic")
    return Harmonic(**{k: (float(v) if k in ("f_max", "damping") else v)
                       for k, v in raw.items()})


def parse_analysis(raw, loc: Locator) -> Analysis:
    raw = check_keys(raw, ("modes", "steps", "solver", "compliance", "buckling", "harmonic",
                           "safety_factor", "mean_stroke", "fatigue", "stroke_check"), loc,
                     "analysis")
    check = {"true": True, "false": False}.get(raw.get("stroke_check"), raw.get("stroke_check",
                                                                          False))  # or --set
    if not isinstance(check, bool):
        raise loc.error(f"[analysis] stroke_check = {raw['stroke_check']!r} must be true or "
                        "false", "analysis", "stroke_check")
    values = {}
    if "safety_factor" in raw:
        located(checks.in_range, raw, "safety_factor", loc, "analysis", bounds=(1, 100))
    if "mean_stroke" in raw and not (is_number(raw["mean_stroke"])
                                     and abs(raw["mean_stroke"]) <= LENGTHS[1]):
        raise loc.error(f"[analysis] mean_stroke = {raw['mean_stroke']!r} must be a length "
                        "(m)", "analysis", "mean_stroke")
    if raw.get("fatigue", "goodman") not in ("goodman", "soderberg"):
        raise loc.error(f"[analysis] fatigue = {raw['fatigue']!r}; choose goodman or soderberg",
                        "analysis", "fatigue")
    if "compliance" in raw:
        if not isinstance(raw["compliance"], str):
            raise loc.error(f"[analysis] compliance = {raw['compliance']!r} must be the name "
                            "of a boundary group (the face made rigid)", "analysis", "compliance")
        values["compliance"] = raw["compliance"]
    if "harmonic" in raw:
        values["harmonic"] = parse_harmonic(raw["harmonic"], loc)
    for key in ("modes", "steps", "buckling"):
        if key in raw:
            v = located(checks.count, raw, key, loc, "analysis")
            if key in ("modes", "buckling") and v > MAX_MODES:
                raise loc.error(f"[analysis] {key} = {v:,} is above the most flexfem solves, "
                                f"{MAX_MODES}: a flexure is designed on its first few; each "
                                "one is a vector of the model's size and the eigen-solve's "
                                "time grows as their square", "analysis", key)
            values[key] = v
    solver = raw.get("solver", "auto")
    if solver not in SOLVERS:
        raise loc.error(f"[analysis] solver = {solver!r}; choose one of {', '.join(SOLVERS)}",
                        "analysis", "solver")
    return Analysis(values.get("modes"), values.get("steps"), solver,
                    values.get("compliance"), values.get("buckling"), values.get("harmonic"),
                    float(raw.get("safety_factor", 1.0)), float(raw.get("mean_stroke", 0.0)),
                    raw.get("fatigue", "goodman"), check)
