"""Spatial flexure mechanisms built from a few numbers (SI units, m): each function returns a
checked :class:`~.description.SpatialMechanism` whose base is ``base`` and whose moving body
is ``stage`` (``rotor`` for the pivot), for ``beam_model`` (studies/spatial/beam_model.py)
and ``mesh_spatial`` (continuum.py) alike. The first three are examples/spatial's files
written as functions (the same numbers: a test); the folded guide is the leaf guide twice
in series.

Blocks: each body is a box ``block`` thick along the flexures, reaching ``margin`` beyond
them."""
import numpy as np

from ..bounds import length, span
from .description import Plate, SolidBody, SpatialMechanism, Wire

MM = 1e-3


def _lengths(owner: str, **values) -> None:
    """Refuse a value that is no length (m) or a design whose lengths span more than
    geometry/bounds.py allows, naming it."""
    span(owner, {name: length(owner, name, v) for name, v in values.items()})


def _box(lo, hi) -> tuple:
    return (tuple(float(v) for v in lo), tuple(float(v) for v in hi))


def _checked(bodies, flexures, what: str) -> SpatialMechanism:
    mechanism = SpatialMechanism(tuple(bodies), tuple(flexures), source=what)
    mechanism.check()
    return mechanism


def wire_guide(L: float = 30 * MM, d: float = 1 * MM, a: float = 12 * MM,
               margin: float = 4 * MM, block: float = 5 * MM) -> SpatialMechanism:
    """A stage on four wires of length ``L`` and diameter ``d`` along z, at (+-a, +-a):
    k_x = k_y = 4 12 E I / L^3, k_z = 4 E A / L."""
    _lengths("wire_guide", L=L, d=d, a=a, margin=margin, block=block)
    s = a + margin
    bodies = [SolidBody("base", (_box((-s, -s, -block), (s, s, 0.0)),)),
              SolidBody("stage", (_box((-s, -s, L), (s, s, L + block)),))]
    corners = [(-a, -a), (a, -a), (a, a), (-a, a)]
    wires = [Wire(("base", "stage"), (x, y, 0.0), (x, y, L), d, name=f"w{k + 1}")
             for k, (x, y) in enumerate(corners)]
    return _checked(bodies, wires, "wire_guide")


def _leaf(between, start, end, t, w, name) -> Plate:
    return Plate(between, tuple(map(float, start)), tuple(map(float, end)), t, w, (1.0, 0.0, 0.0),
                 name=name)


def leaf_guide(L: float = 30 * MM, t: float = 1 * MM, w: float = 10 * MM,
               d: float = 20 * MM) -> SpatialMechanism:
    """Two leaves (length ``L``, thickness ``t``, width ``w`` along x) in the planes
    y = -d/2 and y = +d/2 between a base and a stage; the stage moves along y:
    k_y = 2 12 E I / L^3, I = w t^3 / 12."""
    _lengths("leaf_guide", L=L, t=t, w=w, d=d)
    x, y = w / 2 + 2 * MM, d / 2 + 3 * MM
    bodies = [SolidBody("base", (_box((-x, -y, -5 * MM), (x, y, 0.0)),)),
              SolidBody("stage", (_box((-x, -y, L), (x, y, L + 5 * MM)),))]
    leaves = [_leaf(("base", "stage"), (0, side * d / 2, 0), (0, side * d / 2, L), t, w, name)
              for side, name in ((-1, "front"), (1, "back"))]
    return _checked(bodies, leaves, "leaf_guide")


def cross_pivot(h: float = 20 * MM, t: float = 0.5 * MM, w: float = 5 * MM,
                g: float = 1 * MM) -> SpatialMechanism:
    """A two-layer cross-spring pivot: two leaves crossing at 90 degrees at (0, h/2), one in
    each layer along z (width ``w``, the layers ``g`` apart), between a base (y < 0) and a
    rotor (y > h); its rotational stiffness about z is 2 E I / L (Wittrick), L = h sqrt 2."""
    _lengths("cross_pivot", h=h, t=t, w=w, g=g)
    x, depth = h / 2 + 3 * MM, 2 * w + g
    bodies = [SolidBody("base", (_box((-x, -5 * MM, 0.0), (x, 0.0, depth)),)),
              SolidBody("rotor", (_box((-x, h, 0.0), (x, h + 5 * MM, depth)),))]
    leaves = [Plate(("base", "rotor"), (-h / 2, 0.0, w / 2), (h / 2, h, w / 2), t, w,
                    (0.0, 0.0, 1.0), name="lower"),
              Plate(("base", "rotor"), (h / 2, 0.0, w + g + w / 2), (-h / 2, h, w + g + w / 2),
                    t, w, (0.0, 0.0, 1.0), name="upper")]
    return _checked(bodies, leaves, "cross_pivot")


def folded_leaf_guide(L: float = 30 * MM, t: float = 1 * MM, w: float = 10 * MM,
                      outer: float = 40 * MM, inner: float = 16 * MM) -> SpatialMechanism:
    """A folded leaf guide: two outer leaves (planes y = +-outer/2) from the base up to an
    intermediate body, the ``fold``, and two inner leaves (y = +-inner/2) from the fold back
    down to the stage, which lies between the base's two blocks at their level. Two leaf
    guides in series: k_y = 12 E I / L^3 (I = w t^3 / 12), the fold moving half the stage's
    stroke; compact, and the stage's drop along a stroke is the two guides' difference."""
    _lengths("folded_leaf_guide", L=L, t=t, w=w, outer=outer, inner=inner)
    rim = 3 * MM
    if outer / 2 - inner / 2 <= 2 * rim:
        raise ValueError(f"folded_leaf_guide: outer = {outer:g} m must exceed inner = "
                         f"{inner:g} m by more than {4 * rim:g} m (the blocks round the "
                         "leaves' roots, and a gap between the base and the stage)")
    x, o, i = w / 2 + 2 * MM, outer / 2, inner / 2
    bodies = [SolidBody("base", (_box((-x, -o - rim, -5 * MM), (x, -o + rim, 0.0)),
                                 _box((-x, o - rim, -5 * MM), (x, o + rim, 0.0)))),
              SolidBody("fold", (_box((-x, -o - rim, L), (x, o + rim, L + 5 * MM)),)),
              SolidBody("stage", (_box((-x, -i - rim, -5 * MM), (x, i + rim, 0.0)),))]
    leaves = [_leaf(("base", "fold"), (0, side * o, 0), (0, side * o, L), t, w, name)
              for side, name in ((-1, "outer_front"), (1, "outer_back"))]
    leaves += [_leaf(("fold", "stage"), (0, side * i, L), (0, side * i, 0), t, w, name)
               for side, name in ((-1, "inner_front"), (1, "inner_back"))]
    return _checked(bodies, leaves, "folded_leaf_guide")


def closed_form_stiffness(mechanism_name: str, E: float, **numbers) -> float:
    """The closed-form stiffness (N/m) along the drive of ``wire_guide`` (k_x),
    ``leaf_guide`` and ``folded_leaf_guide`` (k_y) for their ``numbers`` (m) in E (Pa)."""
    if mechanism_name == "wire_guide":
        return 4 * 12 * E * (np.pi * numbers["d"] ** 4 / 64) / numbers["L"] ** 3
    pairs = {"leaf_guide": 2.0, "folded_leaf_guide": 1.0}[mechanism_name]
    return pairs * 12 * E * numbers["w"] * numbers["t"] ** 3 / 12 / numbers["L"] ** 3
