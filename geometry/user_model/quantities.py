"""Values with units in model files: ``"40 mm"``, ``"210 GPa"``, ``"7850 kg/m^3"``, ``"5 deg"``.

A model file's numbers are SI. Where a designer writes a number with a unit instead, the
file is read as if it held the SI value: each quantity (a number followed by a unit, parsed
by pint) becomes its value in SI base units, checked against the dimension its key takes
(:data:`DIMENSIONS`: a thickness is a length, E a pressure, rho a density, a force a force).
In an expression the quantities are replaced in place (``"L + 2 mm"`` -> ``"L + (0.002)"``),
each checked the same way; [parameters] take any unit (their SI value is what the
expressions use). Angles become radians. Outputs stay SI.
"""
from functools import lru_cache
import re

from .expressions import CONSTANTS, FUNCTIONS

#: The dimension each numeric key takes, by table (pint dimension names); None: any unit.
DIMENSIONS = {
    "material": {"E": "pressure", "rho": "density", "yield_strength": "pressure",
                 "ultimate_strength": "pressure", "fatigue_strength": "pressure",
                 "nu": "dimensionless", "fatigue_cycles": "dimensionless"},
    "section": {"thickness": "length"},
    "mesh": {"size": "length", "refine": {"size": "length", "distance": "length"}},
    "analysis": {"mean_stroke": "length", "harmonic": {"f_max": "frequency"}},
    "body": {"box": "length", "polygon": "length",
             "cylinder": {"from": "length", "to": "length", "diameter": "length"},
             "prism": {"polygon": "length", "span": "length"},
             "pose": {"axis": "dimensionless", "angle": "dimensionless", "about": "length"}},
    "flexure": {"from": "length", "to": "length", "thickness": "length", "fillet": "length",
                "radius": "length", "across": "length", "diameter": "length",
                "width": "length"},
    "supports": {"x": "length", "y": "length", "z": "length"},
    "loads": {"force": "force"},
    "beam": {"points": "length", "thickness": "length", "depth": "length"},
}
_PINT_DIMENSIONS = {"length": "[length]", "pressure": "[pressure]", "density": "[density]",
                    "force": "[force]", "frequency": "[frequency]", "dimensionless": ""}
_UNIT = r"[A-Za-zµμ°Ω][A-Za-z0-9_µμ°Ω]*(?:\s*(?:\^|\*\*)\s*-?\d+)?"
_QUANTITY = re.compile(
    rf"(?<![\w.])(?P<number>(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)(?![\d.]|[eE][-+]?\d)\s*"
    rf"(?P<unit>{_UNIT}(?:\s*/\s*{_UNIT})*)")


@lru_cache(maxsize=1)
def registry():
    """pint's unit registry (loaded once, when a file first uses a unit)."""
    import pint

    return pint.UnitRegistry()


def si_value(number: str, unit: str, dimension, where: str) -> float:
    """``number`` ``unit`` in SI base units; ValueError naming ``where`` for an unknown unit
    or one of another dimension than ``dimension`` (None: any)."""
    import pint

    ureg = registry()
    try:
        quantity = ureg.Quantity(float(number), unit.replace("^", "**"))
    except (pint.errors.UndefinedUnitError, pint.errors.DefinitionSyntaxError,
            AttributeError, TypeError, ValueError, SyntaxError) as error:
        raise ValueError(f"{where}: {number} {unit!r} is not a unit pint knows ({error})"
                         ) from None
    if dimension is not None:
        wanted = ureg.get_dimensionality(_PINT_DIMENSIONS[dimension])
        if quantity.dimensionality != wanted:
            raise ValueError(f"{where}: '{number} {unit}' is {_described(quantity)}, but "
                             f"this value is a {dimension}")
    return float(quantity.to_base_units().magnitude)


def _described(quantity) -> str:
    """'a length', 'an angle', ... of a pint quantity, or its dimensionality."""
    ureg = registry()
    if quantity.dimensionless:
        return "an angle" if quantity.units in (ureg.degree, ureg.radian) else "a pure number"
    for name, dims in _PINT_DIMENSIONS.items():
        if dims and quantity.dimensionality == ureg.get_dimensionality(dims):
            return f"a {name}"
    return f"of dimension {quantity.dimensionality}"


def _convert(value, dimension, where: str, reserved: set):
    """``value`` (a number, a string, a list or an inline table) with its quantities in SI."""
    if isinstance(value, list):
        return [_convert(v, dimension, where, reserved) for v in value]
    if isinstance(value, dict):
        sub = dimension if isinstance(dimension, dict) else {}
        return {k: _convert(v, sub.get(k), f"{where}.{k}", reserved) if k in sub else v
                for k, v in value.items()}
    if not isinstance(value, str) or isinstance(dimension, dict):
        return value
    found = [m for m in _QUANTITY.finditer(value) if m.group("unit") not in reserved]
    if not found:
        return value
    whole = len(found) == 1 and found[0].group().strip() == value.strip()
    if whole:
        return si_value(found[0]["number"], found[0]["unit"], dimension, where)
    out, end = [], 0
    for m in found:
        si = si_value(m["number"], m["unit"], dimension, f"{where} = {value!r}")
        out += [value[end:m.start()], f"({si!r})"]
        end = m.end()
    return "".join(out + [value[end:]])


def with_si_units(raw: dict, path) -> dict:
    """The model file ``raw`` with every quantity of its numeric keys in SI (see the
    module); ValueError naming ``path``, the table and the key otherwise."""
    parameters = raw.get("parameters") if isinstance(raw.get("parameters"), dict) else {}
    reserved = set(parameters) | set(FUNCTIONS) | set(CONSTANTS)
    out = dict(raw)
    if parameters:
        out["parameters"] = {k: _convert(v, None, f"{path}: [parameters] {k}", reserved)
                             for k, v in parameters.items()}
    for table, keys in DIMENSIONS.items():
        value = raw.get(table)
        entries = value if isinstance(value, list) else [value]
        converted = []
        for i, entry in enumerate(entries):
            if not isinstance(entry, dict):
                converted.append(entry)
                continue
            where = f"{path}: [{table}]" if not isinstance(value, list) else \
                f"{path}: [[{table}]] {i + 1}"
            converted.append({k: _convert(v, keys[k], f"{where} {k}", reserved)
                              if k in keys else v for k, v in entry.items()})
        if value is not None:
            out[table] = converted if isinstance(value, list) else converted[0]
    points = raw.get("points")  # [points] NAME = { body = ..., at = [x, y] }: at is a length
    if isinstance(points, dict):
        out["points"] = {name: {**p, "at": _convert(p["at"], "length",
                                                     f"{path}: [points] {name} at", reserved)}
                         if isinstance(p, dict) and "at" in p else p
                         for name, p in points.items()}
    return out
