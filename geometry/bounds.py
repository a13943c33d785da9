"""Physically meaningful bounds shared by the parameter classes of the mechanisms.

A value that passes these checks can be drawn, meshed and solved in double precision: a
length between 10 nm and 10 m (below, a part is no elastic continuum -- MEMS flexures are
some 100 nm and more; above, no flexure), at most SPAN_MAX between the largest and smallest
length of one design (a mesh that resolves the smallest feature of a part 10^4 times larger
already has millions of elements), a Young's modulus between 1 kPa (gels) and 10 TPa, and a
density between 1 kg/m^3 (aerogels) and 10^5 kg/m^3. Types are checked first: a length is a
real number (not a bool, a string, None, a list or a complex), as in DBMAParams.
"""
from ..fem import checks

LENGTH_MIN = 1e-8   # m
LENGTH_MAX = 10.0   # m
SPAN_MAX = 1e4      # largest / smallest length of one design
MODULUS_RANGE = (1e3, 1e13)   # Pa
DENSITY_RANGE = (1.0, 1e5)    # kg/m^3


def length(owner: str, name: str, value, zero_allowed: bool = False) -> float:
    """A length (m) in [LENGTH_MIN, LENGTH_MAX] (or exactly 0 when ``zero_allowed``)."""
    value = checks.real(name, value, owner)
    if zero_allowed and value == 0:
        return value
    if not LENGTH_MIN <= value <= LENGTH_MAX:
        raise checks.InputError(name, value, f"a length in [{LENGTH_MIN:g}, {LENGTH_MAX:g}] m "
                                "(10 nm to 10 m)", owner)
    return value


def span(owner: str, lengths: dict) -> None:
    """Refuse a design whose largest length exceeds SPAN_MAX times its smallest."""
    positive = {k: v for k, v in lengths.items() if v > 0}
    small, large = min(positive, key=positive.get), max(positive, key=positive.get)
    if positive[large] > SPAN_MAX * positive[small]:
        raise ValueError(f"{owner}: {large} = {positive[large]!r} m is more than {SPAN_MAX:g} "
                         f"times {small} = {positive[small]!r} m: no mesh resolves both")


def lengths(owner: str, params, names, zero_allowed=()) -> dict:
    """Check the fields ``names`` of the frozen dataclass ``params`` as lengths (m): each a
    finite number > 0 (>= 0 for those in ``zero_allowed``) within :func:`length`'s bounds,
    stored as a float. Returns {name: length} (for :func:`span`)."""
    for name in names:
        value = checks.real(name, getattr(params, name), owner)
        if not (value > 0 or (name in zero_allowed and value == 0)):
            least = ">=" if name in zero_allowed else ">"
            raise checks.InputError(name, value, f"a finite number {least} 0 (m)", owner)
        object.__setattr__(params, name, length(owner, name, value, name in zero_allowed))
    return {name: getattr(params, name) for name in names}
