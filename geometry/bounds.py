"""Physically meaningful bounds shared by the parameter classes of the mechanisms.

A value that passes these checks can be drawn, meshed and solved in double precision: a
length between 10 nm and 10 m (below, a part is no elastic continuum -- MEMS flexures are
some 100 nm and more; above, no flexure), at most SPAN_MAX between the largest and smallest
length of one design (a mesh that resolves the smallest feature of a part 10^4 times larger
already has millions of elements), a Young's modulus between 1 kPa (gels) and 10 TPa, and a
density between 1 kg/m^3 (aerogels) and 10^5 kg/m^3. Types are checked first: a length is a
real number (not a bool, a string, None, a list or a complex), as in DBMAParams.
"""
import math
import numbers

LENGTH_MIN = 1e-8   # m
LENGTH_MAX = 10.0   # m
SPAN_MAX = 1e4      # largest / smallest length of one design
MODULUS_RANGE = (1e3, 1e13)   # Pa
DENSITY_RANGE = (1.0, 1e5)    # kg/m^3


def real(owner: str, name: str, value) -> float:
    """``value`` as a float if it is a finite real number (bools refused), else ValueError."""
    if not (isinstance(value, numbers.Real) and not isinstance(value, bool)
            and math.isfinite(value)):
        raise ValueError(f"{owner}: {name} = {value!r} must be a finite number")
    return float(value)


def length(owner: str, name: str, value, zero_allowed: bool = False) -> float:
    """A length (m) in [LENGTH_MIN, LENGTH_MAX] (or exactly 0 when ``zero_allowed``)."""
    value = real(owner, name, value)
    if zero_allowed and value == 0:
        return value
    if not LENGTH_MIN <= value <= LENGTH_MAX:
        raise ValueError(f"{owner}: {name} = {value!r} m must be in [{LENGTH_MIN:g}, "
                         f"{LENGTH_MAX:g}] m (10 nm to 10 m)")
    return value


def span(owner: str, lengths: dict) -> None:
    """Refuse a design whose largest length exceeds SPAN_MAX times its smallest."""
    positive = {k: v for k, v in lengths.items() if v > 0}
    small, large = min(positive, key=positive.get), max(positive, key=positive.get)
    if positive[large] > SPAN_MAX * positive[small]:
        raise ValueError(f"{owner}: {large} = {positive[large]!r} m is more than {SPAN_MAX:g} "
                         f"times {small} = {positive[small]!r} m: no mesh resolves both")


def in_range(owner: str, name: str, value, bounds: tuple, unit: str) -> float:
    """``value`` (a finite real) within ``bounds`` (inclusive), else ValueError."""
    value = real(owner, name, value)
    if not bounds[0] <= value <= bounds[1]:
        raise ValueError(f"{owner}: {name} = {value!r} {unit} must be in [{bounds[0]:g}, "
                         f"{bounds[1]:g}] {unit}")
    return value
