"""The package's input checks, defined once: what a number is, a positive number, a number or
None. Each check names the value it refuses (``name = value must be ...``)."""
import math
import numbers


def is_real(value) -> bool:
    """A real number (int, float, numpy scalar), not a bool; inf and nan included."""
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def is_finite(value) -> bool:
    """A finite real number, not a bool."""
    return is_real(value) and math.isfinite(value)


def positive(name: str, value, allow_none: bool = False):
    """``value`` as a float if it is a finite number > 0 (None if allowed), else a
    ValueError naming ``name``."""
    if isinstance(value, float) and 0.0 < value < math.inf:  # the common case, fast
        return value
    if value is None and allow_none:
        return None
    if not (is_finite(value) and value > 0):
        raise ValueError(f"{name} = {value!r} must be a finite number > 0")
    return float(value)


def finite_or_none(name: str, value, none_means: str = "free"):
    """``value`` as a float if finite, None if None, else a ValueError naming ``name``."""
    if value is None:
        return None
    if not is_finite(value):
        raise ValueError(f"{name} = {value!r} must be a finite number or None ({none_means})")
    return float(value)
