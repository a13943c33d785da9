"""Selection rules for CAD geometry: conditions of the expression language (expressions.py,
never ``eval``-ed).

A rule such as ``"x < 1e-9"`` or ``"abs(y - 0.02) < 1e-6 and zmax <= 0.001"`` is evaluated on
each gmsh entity of the rule's dimension. Names: ``x``, ``y``, ``z`` (the entity's centre of
mass, m) and ``xmin``, ``ymin``, ``zmin``, ``xmax``, ``ymax``, ``zmax`` (its bounding box, m).
Grammar: numbers, those names, ``pi``, ``+ - * / **``, parentheses, ``abs sqrt sin cos tan
atan atan2``, comparisons ``< <= > >= ==`` (``==`` within 1e-9 relative), ``and``, ``or``,
``not``.
"""
from .expressions import compile_expression

NAMES = ("x", "y", "z", "xmin", "ymin", "zmin", "xmax", "ymax", "zmax")


def compile_rule(text: str):
    """Parse ``text`` once; return ``predicate(values: dict) -> bool`` (values: the NAMES, m).
    Raises ValueError for anything that is not a condition of the NAMES (expressions.py)."""
    if not isinstance(text, str) or not text.strip():
        raise ValueError(f"where = {text!r} must be a non-empty condition such as 'x < 0.001'")
    rule = compile_expression(text, frozenset(NAMES), condition=True,
                              what="a value of the entity")
    return lambda values: bool(rule(values))


def entity_values(gmsh, dim: int, tag: int) -> dict:
    """The NAMES of one gmsh entity: centre of mass and bounding box (m)."""
    xmin, ymin, zmin, xmax, ymax, zmax = gmsh.model.getBoundingBox(dim, tag)
    if dim == 0:
        x, y, z = gmsh.model.getValue(0, tag, [])
    else:
        x, y, z = gmsh.model.occ.getCenterOfMass(dim, tag)
    return dict(zip(NAMES, (x, y, z, xmin, ymin, zmin, xmax, ymax, zmax)))
