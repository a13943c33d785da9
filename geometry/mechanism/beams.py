"""The planar beam model of a :class:`~.description.Mechanism`, as the
:class:`~flexfem.geometry.user_model.beam_tables.BeamSpec` the beam model builder takes
(reduced/model_file.py): every flexure a beam on its centre line over its free
span, with its thickness profile (a leaf's root fillets, a notch's circle), every body a rigid
block holding the flexures' roots and standing for its group at the centroid of its outline
where no flexure meets it (:meth:`Mechanism.outline_centre`: the continuum's force on the
body's outline acts there, and its mean displacement is the displacement there for a body that
moves rigidly). The root, notch and crossing corrections of the builder apply as
to any declared beam model (docs/model_files.md, "The beam model"). Lengths in m."""
import numpy as np

from ..user_model.beam_tables import BeamLine, BeamSpec, Profile, RigidBody
from .description import Leaf, Mechanism, cross2

#: stations on a fillet or a notch (the profile is linear between them)
STATIONS = 33


def _rounded(s: np.ndarray, r: float) -> np.ndarray:
    """The added thickness 2 (r - sqrt(r^2 - (r - s)^2)) of a circular fillet of radius r at a
    distance s from the root (0 beyond s = r)."""
    u = np.clip(r - s, 0.0, None)
    return 2 * (r - np.sqrt(np.clip(r * r - u * u, 0.0, None)))


def profile(flexure, length: float) -> Profile:
    """The in-plane thickness t(s) (m) of ``flexure`` along its free span of ``length`` (m):
    a leaf's constant thickness with its (square-root) fillets, a notch's
    t + 2 b (1 - sqrt(1 - ((s - a) / a)^2)) (semi-axes a along, b across; a = b: circular)."""
    t = flexure.thickness
    if isinstance(flexure, Leaf):
        if flexure.fillet <= 0:
            return Profile((0.0, length), (t, t))
        r = flexure.fillet
        near = np.linspace(0.0, r, STATIONS)
        s = np.concatenate([near, length - near[::-1]])
        ends = sorted({min(r, length / 2), max(length - r, length / 2)})  # the fillets' ends
        return Profile(tuple(s.tolist()),
                       tuple((t + _rounded(np.minimum(s, length - s), r)).tolist()),
                       breaks=tuple(ends))
    along, across = flexure.semi_axes
    s = np.linspace(0.0, length, 4 * STATIONS + 1)
    u = np.clip((s - along) / along, -1.0, 1.0)
    values = t + 2 * across * (1 - np.sqrt(1 - u * u))
    return Profile(tuple(s.tolist()), tuple(values.tolist()))


def _crossing(span, other, tol: float):
    """The point (2,) where the free spans ``span`` and ``other`` cross inside both, or None
    (parallel spans, or meeting at an end)."""
    cross = cross2(span.d, other.d)
    if abs(cross) < 1e-12:
        return None
    offset = other.a - span.a
    s = cross2(offset, other.d) / cross
    u = cross2(offset, span.d) / cross
    inside = tol < s < span.length - tol and tol < u < other.length - tol
    return span.a + s * span.d if inside else None


def beam_spec(mechanism: Mechanism, elements: int = 20, **options) -> BeamSpec:
    """The BeamSpec of ``mechanism``; ``options``: the builder's (shear, root_extension,
    crossings, roots, notch_correction)."""
    lines, joins = [], {b.name: [] for b in mechanism.bodies}
    spans = [mechanism.span(i) for i in range(len(mechanism.flexures))]
    for i, (f, span) in enumerate(zip(mechanism.flexures, spans)):
        a, b = tuple(span.a.tolist()), tuple(span.b.tolist())
        inner = sorted((float((p - span.a) @ span.d), tuple(p.tolist()))
                       for j, other in enumerate(spans) if j != i
                       for p in [_crossing(span, other, mechanism.tol)] if p is not None)
        lines.append(BeamLine((a, *(p for _, p in inner), b), profile(f, span.length),
                              mechanism.depth, elements, f.source))
        joins[f.between[0]].append(a)
        joins[f.between[1]].append(b)
    rigid = tuple(RigidBody(tuple(joins[b.name]),
                            {b.name: tuple(mechanism.outline_centre(b.name).tolist())},
                            b.blocks, b.source) for b in mechanism.bodies)  # boxes, polygons
    groups = {b.name: i for i, b in enumerate(mechanism.bodies)}
    return BeamSpec(tuple(lines), rigid, elements=elements, source=mechanism.source,
                    groups=groups, **options)
