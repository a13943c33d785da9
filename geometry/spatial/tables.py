"""The ``[[body]]`` and ``[[flexure]]`` tables of a spatial model file (docs/spatial.md) ->
:class:`~.description.SpatialMechanism`. A file is spatial when a body's box has 3-D corners
(or a body is a cylinder or prism). Coordinates and sizes are numbers (m), quantities with
units or expressions of the ``[parameters]`` (the planar format's expressions and units);
errors name the model file, the line and the body or flexure."""
from dataclasses import replace
from pathlib import Path
import math
import tomllib

from ..user_model.expressions import evaluate_expression
from ..user_model.mechanism_tables import body_name, check_arrays, flexure_head
from ..user_model.quantities import with_si_units
from ..user_model.tables import Locator, check_keys
from .detect import is_spatial  # noqa: F401 - the spatial tables' own test, re-exported
from .description import AXES, Cylinder, Plate, Pose, Prism, SolidBody, SpatialMechanism, Wire

BODY_KEYS = ("name", "box", "cylinder", "prism", "pose")
POSE_KEYS = ("axis", "angle", "about")
CYLINDER_KEYS = ("from", "to", "diameter")
PRISM_KEYS = ("polygon", "axis", "span")
FLEXURE_KEYS = {"wire": ("kind", "name", "between", "from", "to", "diameter", "fillet",
                         "crosses"),
                "leaf": ("kind", "name", "between", "from", "to", "thickness", "width",
                         "width_along", "fillet", "crosses")}


def _values(raw, n: int, names, where) -> tuple:
    if not (isinstance(raw, list) and len(raw) == n
            and not any(isinstance(v, (list, dict)) for v in raw)):
        raise ValueError(f"{where} = {raw!r} must be {n} numbers (m)")
    out = tuple(evaluate_expression(v, names, where) for v in raw)
    if not all(math.isfinite(v) for v in out):
        raise ValueError(f"{where} = {raw!r} must be finite numbers")
    return out


def _positive(raw, names, where) -> float:
    value = evaluate_expression(raw, names, where)
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"{where} = {raw!r} must be a length > 0 (m)")
    return value


def _boxes(raw, names, where) -> tuple:
    if isinstance(raw, list) and len(raw) == 2 and all(
            isinstance(p, list) and p and not isinstance(p[0], list) for p in raw):
        raw = [raw]
    if not (isinstance(raw, list) and raw and all(isinstance(b, list) and len(b) == 2
                                                  for b in raw)):
        raise ValueError(f"{where} = {raw!r} must be [[x0, y0, z0], [x1, y1, z1]] (two "
                         "opposite corners, m) or a list of such boxes")
    boxes = []
    for box in raw:
        lo, hi = (_values(p, 3, names, where) for p in box)
        if min(abs(a - b) for a, b in zip(lo, hi)) < 1e-6:
            raise ValueError(f"{where}: box {[list(lo), list(hi)]} has a side under 1 um")
        boxes.append((lo, hi))
    return tuple(boxes)


def _table(raw, keys, where) -> dict:
    if not isinstance(raw, dict):
        raise ValueError(f"{where} = {raw!r} must be an inline table {{{', '.join(keys)}}}")
    unknown = sorted(set(raw) - set(keys))
    missing = [k for k in keys if k not in raw]
    if unknown or missing:
        raise ValueError(f"{where} needs exactly the keys {', '.join(keys)}"
                         + (f"; unknown {', '.join(unknown)}" if unknown else "")
                         + (f"; missing {', '.join(missing)}" if missing else ""))
    return raw


def _cylinders(raw, names, where) -> tuple:
    entries = raw if isinstance(raw, list) else [raw]
    out = []
    for entry in entries:
        entry = _table(entry, CYLINDER_KEYS, where)
        out.append(Cylinder(_values(entry["from"], 3, names, f"{where} from"),
                            _values(entry["to"], 3, names, f"{where} to"),
                            _positive(entry["diameter"], names, f"{where} diameter")))
    return tuple(out)


def _prisms(raw, names, where) -> tuple:
    entries = raw if isinstance(raw, list) else [raw]
    out = []
    for entry in entries:
        entry = _table(entry, PRISM_KEYS, where)
        if entry["axis"] not in AXES:
            raise ValueError(f"{where} axis = {entry['axis']!r} must be 'x', 'y' or 'z'")
        polygon = entry["polygon"]
        if not (isinstance(polygon, list) and len(polygon) >= 3):
            raise ValueError(f"{where} polygon must be at least 3 vertices [[u, v], ...] (m)")
        vertices = tuple(_values(p, 2, names, f"{where} polygon") for p in polygon)
        out.append(Prism(vertices, entry["axis"], _values(entry["span"], 2, names,
                                                          f"{where} span")))
    return tuple(out)


def _pose(raw, names, where, centre) -> Pose:
    """A [[body]]'s ``pose = {axis = [x, y, z], angle = A, about = [x, y, z]}``: turned by A
    (rad, or "30 deg") about ``axis`` through ``about`` (m; default ``centre``, the middle
    of its parts' bounding box)."""
    if not isinstance(raw, dict):
        raise ValueError(f"{where} = {raw!r} must be an inline table {{axis, angle, about}}")
    unknown = sorted(set(raw) - set(POSE_KEYS))
    missing = [k for k in ("axis", "angle") if k not in raw]
    if unknown or missing:
        raise ValueError(f"{where} takes axis, angle and (optionally) about"
                         + (f"; unknown {', '.join(unknown)}" if unknown else "")
                         + (f"; missing {', '.join(missing)}" if missing else ""))
    axis = _values(raw["axis"], 3, names, f"{where} axis")
    if not any(axis):
        raise ValueError(f"{where} axis = [0, 0, 0] must be a direction")
    angle = evaluate_expression(raw["angle"], names, f"{where} angle")
    if not math.isfinite(angle):
        raise ValueError(f"{where} angle = {raw['angle']!r} must be a finite angle (rad)")
    about = (_values(raw["about"], 3, names, f"{where} about") if "about" in raw
             else tuple(float(c) for c in centre))
    return Pose(axis, angle, about)


def _body(entry, i, names, loc: Locator) -> SolidBody:
    check_keys(entry, BODY_KEYS, loc, "body", i, "[[body]]")
    name = body_name(entry, i, loc)
    if not any(k in entry for k in ("box", "cylinder", "prism")):
        raise loc.error(f"[[body]] {name!r} needs box = [[x0, y0, z0], [x1, y1, z1]], "
                        "cylinder = {from, to, diameter} or prism = {polygon, axis, span} (m)",
                        "body", None, i)
    parts = {}
    for key, parse in (("box", _boxes), ("cylinder", _cylinders), ("prism", _prisms)):
        if key in entry:
            try:
                parts[key] = parse(entry[key], names, f"[[body]] {name!r} {key}")
            except ValueError as error:
                raise loc.error(str(error), "body", key, i) from None
    body = SolidBody(name, parts.get("box", ()), parts.get("cylinder", ()),
                     parts.get("prism", ()), loc.at("body", "name", i))
    if "pose" not in entry:
        return body
    lo, hi = body.extent()
    try:
        pose = _pose(entry["pose"], names, f"[[body]] {name!r} pose", (lo + hi) / 2)
    except ValueError as error:
        raise loc.error(str(error), "body", "pose", i) from None
    return replace(body, pose=pose)


def _flexure(entry, i, names, loc: Locator):
    kind, between, name = flexure_head(entry, i, loc, FLEXURE_KEYS,
                                       ("kind", "name", "fillet", "crosses"),
                                       "a spatial mechanism's flexures:")
    keys = FLEXURE_KEYS[kind]
    crosses = entry.get("crosses", [])
    if not (isinstance(crosses, list) and all(isinstance(c, str) for c in crosses)):
        raise loc.error(f"[[flexure]] crosses = {crosses!r} must name flexures [\"A\", ...]",
                        "flexure", "crosses", i)
    values = {}
    for key in keys[3:]:
        if key not in entry or key == "crosses":
            continue
        where = f"[[flexure]] {key}"
        try:
            if key in ("from", "to", "width_along"):
                values[key] = _values(entry[key], 3, names, where)
            elif key == "fillet":
                values[key] = evaluate_expression(entry[key], names, where)
                if not values[key] >= 0:
                    raise ValueError(f"{where} = {entry[key]!r} must be >= 0 (m)")
            else:
                values[key] = _positive(entry[key], names, where)
        except ValueError as error:
            raise loc.error(str(error), "flexure", key, i) from None
    common = dict(between=tuple(between), start=values["from"], end=values["to"],
                  fillet=values.get("fillet", 0.0), name=name, crosses=tuple(crosses),
                  source=loc.at("flexure", None, i))
    if kind == "wire":
        return Wire(diameter=values["diameter"], **common)
    if not any(values["width_along"]):
        raise loc.error("[[flexure]] width_along = [0, 0, 0] must be a direction", "flexure",
                        "width_along", i)
    return Plate(thickness=values["thickness"], width=values["width"],
                 width_along=values["width_along"], **common)


def split_moments(raw_loads, names: dict, loc: Locator) -> tuple:
    """([[loads]] entries without their ``moment``, ((body, (M_x, M_y, M_z) N m, source),
    ...)): a spatial file's moments on bodies (about the global axes at the body's centroid),
    read apart from the planar format's forces; an entry with a moment alone gets a zero
    force."""
    if not isinstance(raw_loads, list):
        return raw_loads, ()
    entries, moments = [], []
    for i, entry in enumerate(raw_loads):
        if isinstance(entry, dict) and "moment" in entry:
            entry = dict(entry)
            try:
                vector = _values(entry.pop("moment"), 3, names, "[[loads]] moment")
            except ValueError as error:
                raise loc.error(f"{error} (N m)", "loads", "moment", i) from None
            if not any(k in entry for k in ("force", "traction", "pressure")):
                entry["force"] = [0.0, 0.0, 0.0]
            moments.append((entry.get("group"), vector, loc.at("loads", "moment", i)))
        entries.append(entry)
    return entries, tuple(moments)


def parse_spatial(raw: dict, names: dict, loc: Locator, supported=None) -> SpatialMechanism:
    """The SpatialMechanism of a model file's tables (``raw`` in SI units), checked
    (:meth:`SpatialMechanism.check`; ``supported``: the held groups, None: unchecked);
    ``names``: the [parameters] {name: value}."""
    check_arrays(raw, loc)
    bodies = tuple(_body(e, i, names, loc) for i, e in enumerate(raw["body"]))
    flexures = tuple(_flexure(e, i, names, loc) for i, e in enumerate(raw["flexure"]))
    mechanism = SpatialMechanism(bodies, flexures, str(loc.path))
    mechanism.check()
    if supported is not None:
        _check_supports(raw, mechanism, loc)
    return mechanism


def _check_supports(raw: dict, mechanism: SpatialMechanism, loc: Locator) -> None:
    """Every [[supports]] group a body (the line of one that is not), and at least one
    (the file and its bodies named where the table is missing)."""
    names = [b.name for b in mechanism.bodies]
    entries = raw.get("supports", [])
    entries = entries if isinstance(entries, list) else []
    for i, entry in enumerate(entries):
        group = entry.get("group") if isinstance(entry, dict) else None
        if group not in names:
            raise loc.error(f"[[supports]] group = {group!r} is no body: a spatial mechanism "
                            f"is held by its bodies ({', '.join(names)})", "supports",
                            "group", i)
    if not entries:
        raise loc.error("the mechanism has no support: hold a body with [[supports]] group = "
                        f"'NAME' (bodies: {', '.join(names)})", None)


def load_spatial(path, overrides: dict | None = None) -> tuple:
    """(SpatialMechanism, raw tables in SI, parameters) of the spatial model file ``path``;
    ``overrides`` {NAME: value} replace [parameters] entries. The supports' groups must
    hold a body."""
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"{path}: the model file does not exist")
    text = path.read_text()
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ValueError(f"{path}: not valid TOML: {error}") from None
    loc = Locator(path, text)
    table = dict(raw.get("parameters", {}))
    for name, value in (overrides or {}).items():
        if name not in table:
            raise ValueError(f"{path}: override {name!r} is not a [parameters] name of "
                             f"{path.name}; its names: {', '.join(sorted(table)) or 'none'}")
        table[name] = value
    raw = with_si_units({**raw, "parameters": table}, path)
    if not is_spatial(raw):
        raise loc.error("not a spatial mechanism: no body has a 3-D box, a cylinder or a "
                        "prism (a planar file: docs/model_files.md)", "body")
    parameters = {}
    for name, value in raw["parameters"].items():
        parameters[name] = evaluate_expression(value, parameters, f"[parameters] {name}")
    supports = raw.get("supports", [])
    held = {s.get("group") for s in supports if isinstance(s, dict)} if isinstance(
        supports, list) else set()
    return parse_spatial(raw, parameters, loc, held), raw, parameters
