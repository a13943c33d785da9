"""How the report writes numbers: meaningful digits, units, differences and tolerances."""
import math
from pathlib import Path

SIGNIFICANT = 4
# SI values are printed in the unit a designer reads them in: (largest |value|, factor, unit)
DISPLAY_UNITS = {"m": ((1e-3, 1e-6, "um"), (0.1, 1e-3, "mm")),
                 "Pa": ((1e6, 1.0, "Pa"), (1e9, 1e6, "MPa"), (math.inf, 1e9, "GPa"))}


def display(value: float, unit: str) -> tuple[float, str]:
    """(value, unit) rescaled for reading: 2.7e-5 m -> (27, 'um'), 2.1e8 Pa -> (210, 'MPa')."""
    for bound, factor, shown in DISPLAY_UNITS.get(unit, ()):
        if abs(value) < bound:
            return value / factor, shown
    return value, unit


def wrap_degrees(value: float) -> tuple[float, int]:
    """(angle in (-180, 180] deg, whole turns): value = angle + 360 turns."""
    angle = value - 360.0 * math.floor(value / 360.0)  # [0, 360)
    angle = angle - 360.0 if angle > 180.0 else angle
    return angle, round((value - angle) / 360.0)


def _turns(turns: int) -> str:
    return f" {'+' if turns > 0 else '-'} {abs(turns)} turn{'s' if abs(turns) > 1 else ''}"


def number(value, unit: str = "") -> str:
    """A value to 4 significant digits (no exponent between 1e-3 and 1e6), with its unit
    (lengths and stresses rescaled, see ``display``; angles wrapped to (-180, 180] deg, the
    whole turns written beside them); '-' for None, NaN or infinity; other types as text."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return "-" if value is None else str(value)
    if not math.isfinite(value):
        return "-"
    if unit == "deg" and not -180.0 < value <= 180.0:
        angle, turns = wrap_degrees(value)
        return number(angle, unit) + _turns(turns)
    value, unit = display(value, unit) if value != 0 else (value, unit)
    if isinstance(value, int) or float(value).is_integer() and abs(value) < 1e6:
        text = f"{int(value)}"
    elif value != 0 and not 1e-3 <= abs(value) < 1e6:
        text = f"{value:.{SIGNIFICANT - 1}e}"
    else:
        text = f"{value:.{SIGNIFICANT}g}"
    return f"{text} {unit}" if unit and unit != "-" else text


def _absolute(row: dict) -> bool:
    return row.get("difference_kind") == "absolute"


def margin_text(row: dict) -> str:
    """How far a value judged against a limit lies from it, in words that say which side is
    good: '47.1x the minimum', '21.7x below the maximum' (within), '2.25x short of the
    minimum', '3x over the maximum' (beyond), as a ratio where it is 2 or more, else the
    signed distance in the row's unit ('+1.6 Hz above the minimum', '-2.32 Hz short of the
    minimum')."""
    value, limit, unit = row.get("flexfem"), row.get("reference"), row.get("unit", "")
    if not all(isinstance(v, (int, float)) and math.isfinite(v) for v in (value, limit)):
        return "-"
    upper = row.get("limit") == "upper"
    bound = "maximum" if upper else "minimum"
    gap = value - limit
    within = gap <= 0 if upper else gap >= 0
    if limit > 0 and value > 0:
        ratio = value / limit
        if ratio >= 2:
            return f"{ratio:.3g}x the {bound}" + ("" if within else ", over it")
        if ratio <= 0.5:
            return f"{1 / ratio:.3g}x " + (f"below the {bound}" if within else
                                            f"short of the {bound}")
    text = number(abs(gap), "" if unit == "-" else unit)
    where = ("above" if gap > 0 else "below") if within else (
        "over" if upper else "short of")
    return f"{'+' if gap > 0 else '-'}{text} {where} the {bound}"


def difference_text(row: dict) -> str:
    """'+1.2 %' (relative) or '+0.3 deg' / '+1.5 pp' (absolute) or '-'; for a row judged
    against a limit, its margin (:func:`margin_text`), never a percentage."""
    if row.get("limit"):
        return margin_text(row)
    d = row.get("difference")
    if not isinstance(d, (int, float)) or not math.isfinite(d):
        return "-"
    if _absolute(row):
        unit = "pp" if row.get("unit") == "%" else row.get("unit", "")
        if unit == "deg" and abs(d) > 180:
            angle, turns = wrap_degrees(d)
            return f"{angle:+.3g} deg{_turns(turns)}"
        return f"{d:+.3g} {unit}"
    return f"{100 * d:+.2f} %" if abs(d) < 0.01 else f"{100 * d:+.1f} %"


def tolerance_text(row: dict) -> str:
    """'±5 %' (relative) or '±1 deg' (absolute) or '-' when not judged."""
    if row.get("limit"):
        return {"upper": "at most", "lower": "at least"}[row["limit"]]
    t = row.get("tolerance")
    if not isinstance(t, (int, float)):
        return "-"
    if _absolute(row):
        unit = "pp" if row.get("unit") == "%" else row.get("unit", "")
        return f"±{t:g} {unit}"
    return f"±{100 * t:g} %"


def is_image(name: str) -> bool:
    return Path(name).suffix.lower() in (".png", ".jpg", ".jpeg", ".svg")

