"""The names a model file's overrides may set (``--set``, a study's grid, sample, tolerances
and front variables, ``'table.key'`` options), and the refusal of any other with the known
ones and the nearest (difflib). A misspelled name must never run the unchanged design."""
import difflib

from .beam_tables import OPTION_KEYS

#: The keys of each table an override ``TABLE.KEY`` may set (tables.py's parse_material,
#: parse_section, parse_mesh and parse_analysis, beam_tables.py's [beam_model]);
#: tests/studies/user_model/test_names_checked.py checks them against the parsers.
OVERRIDE_KEYS = {
    "material": ("name", "E", "nu", "rho", "yield_strength", "ultimate_strength",
                 "fatigue_strength", "fatigue_cycles"),
    "section": ("kind", "thickness"),
    "mesh": ("order", "size", "refine"),
    "analysis": ("modes", "steps", "solver", "compliance", "buckling", "harmonic",
                 "safety_factor", "mean_stroke", "fatigue", "stroke_check"),
    "beam_model": OPTION_KEYS,
}


def nearest(name: str, known) -> str:
    """'; did you mean 'X'?' for the closest of ``known`` to ``name``, or ''."""
    close = difflib.get_close_matches(str(name), [str(k) for k in known], n=1, cutoff=0.6)
    return f"; did you mean {close[0]!r}?" if close else ""


def unknown_name(name: str, what: str, known) -> str:
    """The message for ``name`` naming no ``what``: the known names and the nearest."""
    listed = ", ".join(sorted(map(str, known))) or "none"
    return f"{name!r} is not {what}; known: {listed}{nearest(name, known)}"


def override_keys() -> list[str]:
    """Every ``TABLE.KEY`` an override may name ('material.E', 'mesh.size', ...)."""
    return [f"{t}.{k}" for t, keys in OVERRIDE_KEYS.items() for k in keys]


def check_override_key(name: str, path) -> None:
    """Refuse ``TABLE.KEY`` whose table takes no overrides or whose table has no such key,
    with the model file ``path``, the known tables or keys and the nearest."""
    table, _, key = str(name).rpartition(".")
    if table not in OVERRIDE_KEYS:
        raise ValueError(f"{path}: override {name!r}: only [parameters] names and "
                         f"{', '.join(t + '.KEY' for t in OVERRIDE_KEYS)} can be set"
                         f"{nearest(table, OVERRIDE_KEYS)}")
    if key not in OVERRIDE_KEYS[table]:
        raise ValueError(f"{path}: override {name!r}: "
                         + unknown_name(key, f"a key of [{table}]", OVERRIDE_KEYS[table]))
