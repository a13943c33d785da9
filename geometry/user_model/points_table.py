"""The ``[points]`` table of a file of bodies and flexures: named points of its bodies, e.g.
a mirror's centre or a probe's tip, observed as groups are (``tip.ux``, ``tip.rz``):

    [points]
    tip = { body = "stage", at = [0.0, "L + 0.008"] }

A point moves with its body as a rigid body does: its displacement is the body's, carried by
the body's rotation from the body's centroid to the point (studies/user_model/observe.py), in
the continuum and the beam model alike; it need not lie in the body's material (the centre of
a hole). ``at`` is [x, y] (m; in 3-D a third coordinate z, default the mid-depth), numbers,
lengths with a unit (``"40 mm"``, read by quantities.py) or expressions of the [parameters]
(``"L + 8 mm"``).
"""
from .expressions import evaluate_expression


def parse_points(raw, parameters: dict, bodies, dim: int, taken, loc) -> dict:
    """{name: (body, (x, y[, z]))} of the [points] table; ValueError naming the file, the
    line and the point for a bad entry. ``taken``: the group names a point may not reuse;
    ``loc``: the file's Locator (tables.py)."""
    if raw is None:
        return {}
    if not isinstance(raw, dict):
        raise loc.error(f"[points] must be a table of NAME = {{ body = \"BODY\", at = [x, y] }}, "
                        f"not {raw!r}", None, "points")
    out = {}
    for name, entry in raw.items():
        where = loc.at("points", name)
        if name in taken or "." in name:
            raise ValueError(f"{where}: [points] {name!r} is already a group (a body or a "
                             "face); give the point its own name")
        if not isinstance(entry, dict) or set(entry) != {"body", "at"}:
            raise ValueError(f"{where}: [points] {name} = {entry!r}: write {{ body = \"BODY\", "
                             "at = [x, y] }")
        if entry["body"] not in bodies:
            raise ValueError(f"{where}: [points] {name}: body {entry['body']!r} is not a body; "
                             f"bodies: {', '.join(bodies)}")
        at = entry["at"]
        if not isinstance(at, list) or len(at) not in (2, 3) or (len(at) == 3 and dim == 2):
            raise ValueError(f"{where}: [points] {name}: at = {at!r} must be [x, y]"
                             f"{' or [x, y, z]' if dim == 3 else ''} (m)")
        out[name] = (entry["body"], tuple(
            evaluate_expression(v, parameters, f"{where}: [points] {name} at") for v in at))
    return out
