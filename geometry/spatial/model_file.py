"""A spatial model file (bodies with 3-D boxes, cylinders or prisms, and wire and leaf
flexures) -> the fields of its :class:`~flexfem.geometry.user_model.spec.ModelSpec` (dim 3,
the bodies' names as boundary groups, "solid" the whole), with the planar format's
[material], [mesh], [[supports]], [[loads]] and [analysis] tables."""
from dataclasses import replace

from ..user_model.mechanism_tables import mechanism_parts
from ..user_model.tables import SectionSpec, parse_loads, parse_supports
from .tables import parse_spatial, split_moments

#: Tables a spatial file may hold.
SPATIAL_KEYS = ("description", "parameters", "material", "mesh", "supports", "loads",
                "analysis", "body", "flexure")


def spatial_spec(raw: dict, parameters: dict, loc, dim: int | None = None) -> tuple:
    """(fields {material, section, mesh, supports, loads, analysis, spatial}, groups {name:
    dimension}) of a spatial model file (``raw``: its tables in SI units, ``parameters``
    evaluated; ``loc`` its Locator); ``dim``: --dim, None or 3."""
    for key in raw:
        if key not in SPATIAL_KEYS:
            raise loc.error(f"{key!r} in a spatial mechanism (3-D bodies): its tables are "
                            f"{', '.join(SPATIAL_KEYS)}", key if isinstance(
                                raw[key], (dict, list)) else None, None)
    if dim not in (None, 3):
        raise loc.error(f"--dim {dim}: a mechanism of 3-D bodies is spatial (dim 3)", "body")
    if "material" not in raw:
        raise loc.error("[material] is required", None)
    if not raw.get("supports"):  # before the shared tables' own refusal: name the bodies
        bodies = raw.get("body") if isinstance(raw.get("body"), list) else []
        names = [str(b["name"]) for b in bodies if isinstance(b, dict) and "name" in b]
        raise loc.error("the mechanism has no support: hold a body with [[supports]] group = "
                        f"'NAME' (bodies: {', '.join(names)})", None)
    loads, moments = split_moments(raw.get("loads", []), parameters, loc)
    parts = mechanism_parts(raw, loc, SectionSpec("solid"), parse_supports,
                            lambda _, dim, where: parse_loads(loads, dim, where), 3,
                            "every flexure is refined already (its diameter or thickness "
                            "sets its element size)")
    mechanism = parse_spatial(raw, parameters, loc, {s.group for s in parts["supports"]})
    names = {b.name for b in mechanism.bodies}
    for body, _, source in moments:
        if body not in names:
            raise ValueError(f"{source}: [[loads]] moment on {body!r}: a moment acts on a "
                             f"body; bodies: {', '.join(sorted(names))}")
    mechanism = replace(mechanism, moments=moments)
    groups = {b.name: 2 for b in mechanism.bodies} | {"solid": 3}
    return {**parts, "spatial": mechanism}, groups
