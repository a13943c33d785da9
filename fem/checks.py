"""The package's checks of plain values, defined once: a real number, a positive one, one in a
range, a count (a whole number), one of given choices, a number or None.

Each returns the value (a float; an int for a count) or raises :class:`InputError`, a
ValueError in one style that names the owner (where one is given), the value's name and the
value: ``DBMAParams: b = 0.0 must be a finite number > 0 (m)``. The model-file and
command-line readers reword it with their place (file and line, the option's text)."""
import math
import numbers


class InputError(ValueError):
    """A refused value: its ``name``, the ``value``, what it ``must`` be and its ``owner``
    (None: none named); ``str(error)`` says all four in one line."""

    def __init__(self, name: str, value, must: str, owner: str | None = None):
        self.name, self.value, self.must, self.owner = name, value, must, owner
        where = f"{owner}: " if owner else ""
        super().__init__(f"{where}{name} = {value!r} must be {must}")

    def __reduce__(self):  # raised in a worker process, re-raised in the study's
        return InputError, (self.name, self.value, self.must, self.owner)


def is_real(value) -> bool:
    """A real number (int, float, numpy scalar), not a bool; inf and nan included."""
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def is_finite(value) -> bool:
    """A finite real number, not a bool."""
    return is_real(value) and math.isfinite(value)


def _unit(unit: str | None) -> str:
    return f" ({unit})" if unit else ""


def real(name: str, value, owner: str | None = None) -> float:
    """``value`` as a float if it is a finite real number (bools refused), else InputError."""
    if not is_finite(value):
        raise InputError(name, value, "a finite number", owner)
    return float(value)


def positive(name: str, value, allow_none: bool = False, owner: str | None = None,
             unit: str | None = None):
    """``value`` as a float if it is a finite number > 0 (None if ``allow_none``), else
    InputError; ``unit`` is named in the message."""
    if isinstance(value, float) and 0.0 < value < math.inf:  # the common case, fast
        return value
    if value is None and allow_none:
        return None
    if not (is_finite(value) and value > 0):
        raise InputError(name, value, f"a finite number > 0{_unit(unit)}", owner)
    return float(value)


def in_range(name: str, value, bounds: tuple, unit: str | None = None,
             owner: str | None = None, closed: bool = True) -> float:
    """``value`` as a float if it is a finite number within ``bounds`` (low, high): inclusive
    when ``closed``, exclusive else; InputError otherwise."""
    low, high = bounds
    inside = is_finite(value) and (low <= value <= high if closed else low < value < high)
    if not inside:
        shown = f"[{low:g}, {high:g}]" if closed else f"({low:g}, {high:g})"
        raise InputError(name, value, f"a finite number in {shown}{_unit(unit)}", owner)
    return float(value)


def count(name: str, value, least: int = 1, most: int | None = None,
          owner: str | None = None) -> int:
    """``value`` as an int if it is a whole number (an int, not a bool or a float) from
    ``least`` to ``most`` (None: no upper end), else InputError."""
    whole = isinstance(value, numbers.Integral) and not isinstance(value, bool)
    if not (whole and value >= least and (most is None or value <= most)):
        must = (f"a whole number >= {least:,}" if most is None else
                f"a whole number from {least:,} to {most:,}")
        raise InputError(name, value, must, owner)
    return int(value)


def one_of(name: str, value, choices, owner: str | None = None):
    """``value`` if it is one of ``choices`` (a kind, a method), else InputError listing them."""
    if value not in choices:
        raise InputError(name, value, f"one of {', '.join(map(repr, choices))}", owner)
    return value


def finite_or_none(name: str, value, none_means: str = "free"):
    """``value`` as a float if finite, None if None, else a ValueError naming ``name``."""
    if value is None:
        return None
    if not is_finite(value):
        raise InputError(name, value, f"a finite number or None ({none_means})")
    return float(value)
