"""The ``[[body]]`` and ``[[flexure]]`` tables of a model file (docs/model_files.md, "Bodies
and flexures") -> :class:`flexfem.geometry.mechanism.Mechanism`, and the [[supports]] and
[[loads]] such a file gives (x, y and, for the extruded solid, z). Every coordinate and size is a
number (m) or an expression of the ``[parameters]`` (expressions.evaluate_expression); errors
name the model file, the line and the body or flexure."""
from dataclasses import replace
import math

from ..mechanism import Body, Leaf, Mechanism, Notch
from .expressions import evaluate_expression, is_number
from .material_table import check_density, parse_material
from .tables import Locator, check_keys, parse_analysis, parse_loads, parse_mesh, parse_supports

BODY_KEYS = ("name", "box", "polygon")
FLEXURE_KEYS = {"leaf": ("kind", "name", "between", "from", "to", "thickness", "fillet"),
                "circular_notch": ("kind", "name", "between", "from", "to", "thickness",
                                   "radius"),
                "elliptical_notch": ("kind", "name", "between", "from", "to", "thickness",
                                     "radius", "across")}


def _value(raw, names, where):
    return evaluate_expression(raw, names, where)


def _point(raw, names, where) -> tuple:
    if not (isinstance(raw, list) and len(raw) == 2):
        raise ValueError(f"{where} = {raw!r} must be a point [x, y] (m)")
    for v in raw:
        if isinstance(v, float) and not math.isfinite(v):
            raise ValueError(f"{where}: {raw!r} has {v}, not a finite number (m)")
    return tuple(_value(v, names, where) for v in raw)


def _boxes(raw, names, where) -> tuple:
    """One box [[x0, y0], [x1, y1]] or a list of them."""
    if isinstance(raw, list) and len(raw) == 2 and all(
            isinstance(p, list) and len(p) == 2 and not isinstance(p[0], list) for p in raw):
        raw = [raw]
    if not (isinstance(raw, list) and raw):
        raise ValueError(f"{where} = {raw!r} must be [[x0, y0], [x1, y1]] (two opposite "
                         "corners, m) or a list of such boxes")
    out = []
    for box in raw:
        if not (isinstance(box, list) and len(box) == 2):
            raise ValueError(f"{where}: {box!r} must be two opposite corners [[x0, y0], [x1, y1]]")
        out.append(tuple(_point(p, names, where) for p in box))
    return tuple(out)


def _is_point(raw) -> bool:
    return isinstance(raw, list) and len(raw) == 2 and not any(isinstance(v, list) for v in raw)


def _polygons(raw, names, where) -> tuple:
    """One polygon [[x, y], [x, y], [x, y], ...] (its vertices in order around it) or a list
    of them."""
    if isinstance(raw, list) and raw and _is_point(raw[0]):
        raw = [raw]
    if not (isinstance(raw, list) and raw and all(isinstance(p, list) and p for p in raw)):
        raise ValueError(f"{where} = {raw!r} must be the vertices [[x, y], [x, y], [x, y], ...] "
                         "of a polygon (m, in order around it) or a list of such polygons")
    out = []
    for k, polygon in enumerate(raw):
        label = f"{where} {k + 1}" if len(raw) > 1 else where
        if not all(_is_point(p) for p in polygon):
            raise ValueError(f"{label}: {polygon!r} must be a list of vertices [x, y] (m)")
        out.append(tuple(_point(p, names, label) for p in polygon))
    return tuple(out)


def body_name(entry: dict, i: int, loc: Locator) -> str:
    """The name of [[body]] ``i``: a non-empty string other than 'solid' (the group of the
    whole part), or a one-line error naming the body."""
    name = entry.get("name")
    if not isinstance(name, str) or not name.strip() or name == "solid":
        raise loc.error(f"[[body]] name = {name!r} must be a non-empty string (not 'solid'): "
                        "the body's group in every model", "body", "name", i)
    return name


def _body(entry, i, names, loc: Locator) -> Body:
    check_keys(entry, BODY_KEYS, loc, "body", i, "[[body]]")
    name = body_name(entry, i, loc)
    if "box" not in entry and "polygon" not in entry:
        raise loc.error(f"[[body]] {name!r} needs box = [[x0, y0], [x1, y1]] or polygon = "
                        "[[x, y], [x, y], [x, y], ...] (m)", "body", None, i)
    parts = {}
    for key, parse in (("box", _boxes), ("polygon", _polygons)):
        if key in entry:
            try:
                parts[key] = parse(entry[key], names, f"[[body]] {name!r} {key}")
            except ValueError as error:
                raise loc.error(str(error), "body", key, i) from None
    try:
        return Body(name, parts.get("box", ()), loc.at("body", "name", i),
                    parts.get("polygon", ()))
    except ValueError as error:
        key = "polygon" if f"body {name!r}: polygon" in str(error) else "box"
        raise loc.error(str(error).removeprefix(loc.at("body", "name", i) + ": "), "body",
                        key, i) from None


def flexure_head(entry, i: int, loc: Locator, kinds: dict, optional=("kind", "name", "fillet"),
                 choose: str = "choose one of") -> tuple:
    """The head of the ``i``-th [[flexure]] table, planar or spatial: its ``kind`` (one of
    ``kinds``, {kind: its keys}; ``choose`` introduces them in the refusal), its keys (all but
    ``optional`` required), ``between`` (two body names) and ``name``: (kind, between, name)."""
    if not isinstance(entry, dict):
        raise loc.error(f"[[flexure]] must be a table, not {entry!r}", "flexure", None, i)
    kind = entry.get("kind", "leaf")
    if kind not in kinds:
        raise loc.error(f"[[flexure]] kind = {kind!r}; {choose} {', '.join(kinds)}",
                        "flexure", "kind", i)
    check_keys(entry, kinds[kind], loc, "flexure", i, f"[[flexure]] ({kind})")
    missing = [k for k in kinds[kind] if k not in optional and k not in entry]
    if missing:
        raise loc.error(f"[[flexure]] ({kind}) needs {', '.join(missing)}", "flexure", None, i)
    between = entry["between"]
    if not (isinstance(between, list) and len(between) == 2
            and all(isinstance(b, str) for b in between)):
        raise loc.error(f"[[flexure]] between = {between!r} must name two bodies "
                        "[\"A\", \"B\"]", "flexure", "between", i)
    name = entry.get("name", "")
    if not isinstance(name, str):
        raise loc.error(f"[[flexure]] name = {name!r} must be a string", "flexure", "name", i)
    return kind, between, name


def _flexure(entry, i, names, loc: Locator):
    kind, between, name = flexure_head(entry, i, loc, FLEXURE_KEYS)
    keys = FLEXURE_KEYS[kind]
    values = {}
    for key in keys[3:]:
        if key not in entry:
            continue
        try:
            values[key] = (_point(entry[key], names, f"[[flexure]] {key}")
                           if key in ("from", "to") else
                           _value(entry[key], names, f"[[flexure]] {key}"))
        except ValueError as error:
            raise loc.error(str(error), "flexure", key, i) from None
    common = dict(between=tuple(between), start=values["from"], end=values["to"],
                  thickness=values["thickness"], name=name, source=loc.at("flexure", None, i))
    if kind == "leaf":
        return Leaf(fillet=values.get("fillet", 0.0), **common)
    return Notch(radius=values["radius"], across=values.get("across"), **common)


def check_arrays(raw: dict, loc: Locator) -> None:
    """A one-line error unless the file's [[body]] and [[flexure]] are each an array of at
    least one table (planar or spatial)."""
    for table in ("body", "flexure"):
        value = raw.get(table)
        if not (isinstance(value, list) and value and all(isinstance(e, dict) for e in value)):
            raise loc.error(f"{table} must be an array of tables: [[{table}]] ... (at least one)",
                            None, table)


def parse_mechanism(raw: dict, names: dict, depth: float, loc: Locator,
                    supported=None) -> Mechanism:
    """The Mechanism of the model file's ``[[body]]`` and ``[[flexure]]`` tables, checked
    (:meth:`Mechanism.check`, ``supported``: the held groups); ``names``: the parameters
    {name: value}; ``depth``: the [section] thickness (m)."""
    check_arrays(raw, loc)
    bodies = tuple(_body(e, i, names, loc) for i, e in enumerate(raw["body"]))
    flexures = tuple(_flexure(e, i, names, loc) for i, e in enumerate(raw["flexure"]))
    mechanism = Mechanism(bodies, flexures, depth, str(loc.path))
    mechanism.check(supported)
    return mechanism


def check_held_bodies(raw: dict, supports, loc: Locator) -> None:
    """Refuse a support whose group is neither a [[body]] nor a body's face, by its line
    (before the mechanism's own check would find it held by nothing)."""
    bodies = sorted(str(b["name"]) for b in raw.get("body", []) if isinstance(b, dict)
                    and "name" in b)
    for i, s in enumerate(supports):
        if s.group not in bodies and s.group.rpartition(".")[0] not in bodies:
            raise loc.error(f"[[supports]] group = {s.group!r} is no body (nor a body's face); "
                            f"bodies: {', '.join(bodies)}", "supports", "group", i)


def body_supports(raw, dim: int, loc: Locator) -> tuple:
    """The [[supports]] of bodies and flexures: x, y and z (m, prescribed displacements). A z
    holds the extruded solid's out-of-plane motion (--dim 3: with x or y alone the solid could
    slide along z); in the plane, where nothing moves out of it, z = 0 is what the plane holds
    already and any other z needs --dim 3."""
    entries = raw
    if isinstance(raw, list) and dim == 2:
        entries = []
        for i, entry in enumerate(raw):
            if isinstance(entry, dict) and "z" in entry:
                if not (is_number(entry["z"]) and entry["z"] == 0):
                    raise loc.error(f"[[supports]] z = {entry['z']!r}: an out-of-plane "
                                    "displacement needs --dim 3 (the plane holds z = 0)",
                                    "supports", "z", i)
                entry = {k: v for k, v in entry.items() if k != "z"}
            entries.append(entry)
    return parse_supports(entries, dim, loc)


def body_loads(raw, dim: int, loc: Locator) -> tuple:
    """The [[loads]] of bodies and flexures: in-plane forces (F_x, F_y), or (F_x, F_y, F_z)
    pushing out of the plane, which only the 3-D models (--dim 3) take; dim components each."""
    entries, out_of_plane = raw, {}
    if isinstance(raw, list):
        entries = []
        for i, entry in enumerate(raw):
            force = entry.get("force") if isinstance(entry, dict) else None
            if isinstance(force, list) and len(force) == 3 and is_number(force[2]):
                if dim == 2 and force[2] != 0:
                    raise loc.error(f"[[loads]] force = {force!r}: an out-of-plane force "
                                    "(F_z) needs --dim 3 (the extruded solid or the spatial "
                                    "beam model)", "loads", "force", i)
                out_of_plane[i], entry = float(force[2]), {**entry, "force": force[:2]}
            entries.append(entry)
    loads = parse_loads(entries, 2, loc)
    return tuple(replace(load, vector=tuple(load.vector) + (out_of_plane.get(i, 0.0),)
                         * (dim - 2)) for i, load in enumerate(loads))


def mechanism_parts(raw: dict, loc: Locator, section, supports, loads, dim: int,
                    refined: str) -> dict:
    """The tables every file of bodies and flexures has, planar or spatial: [material], the
    ``section`` (a SectionSpec), [mesh] (no ``refine``: ``refined`` says what sizes each
    flexure's elements), [[supports]] (at least one) and [[loads]] read by ``supports`` and
    ``loads`` (``parse(raw, dim, loc)``), [analysis]; {name: parsed table}."""
    parts = {
        "material": parse_material(raw["material"], loc),
        "section": section,
        "mesh": parse_mesh(raw.get("mesh", {}), loc),
        "supports": supports(raw.get("supports", []), dim, loc),
        "loads": loads(raw.get("loads", []), dim, loc),
        "analysis": parse_analysis(raw.get("analysis", {}), loc),
    }
    if parts["mesh"].refine:
        raise loc.error(f"[mesh] refine: {refined}", "mesh", "refine")
    if not parts["supports"]:
        raise loc.error("the mechanism has no support: hold a body with [[supports]] group = "
                        "'NAME'", None)
    check_density(parts, loc)
    return parts
