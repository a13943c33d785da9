"""The unit of a study's parameter or metric, for axis labels: a mechanism's own table first
(exact names, or ``"prefix_*"`` patterns), then the project's name suffixes (``_hz``, ``_m``,
``_pct`` ...). None when neither says: the name is shown alone rather than with a guess."""

SUFFIXES = (("_hz", "Hz"), ("_pct", "%"), ("_deg", "deg"), ("_rad", "rad"), ("_mm", "mm"),
            ("_um", "um"), ("_m", "m"), ("_n", "N"), ("_pa", "Pa"), ("_s", "s"), ("_kg", "kg"))


def unit_of(name: str, table=None) -> str | None:
    """The unit of quantity ``name`` ("-" for a dimensionless one) from ``table`` ({name or
    "prefix_*": unit}) or the name's suffix; None if unknown."""
    table = table or {}
    if name in table:
        return table[name]
    for pattern, unit in table.items():
        if pattern.endswith("*") and name.startswith(pattern[:-1]):
            return unit
    lowered = name.lower()
    for suffix, unit in SUFFIXES:
        if lowered.endswith(suffix):
            return unit
    return None
