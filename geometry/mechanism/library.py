"""Composite flexures, written once as bodies and flexures (m). Each returns a
:class:`~.description.Mechanism` with a body "ground" to hold and a body "stage" to load; its
closed form is in the docstring (the tests check both models against it).

>>> from flexfem.geometry.mechanism.library import parallel_guide
>>> guide = parallel_guide(length=0.04, thickness=0.001, depth=0.01)
>>> [b.name for b in guide.bodies]
['ground', 'stage']
"""
import math

from .description import Body, Leaf, Mechanism

BLOCK = 0.006  # m: the height of the ground's and stage's blocks


def _box(x0, y0, x1, y1):
    return ((x0, y0), (x1, y1))


def parallel_guide(length: float, thickness: float, depth: float, spacing: float = 0.02,
                   fillet: float = 0.0) -> Mechanism:
    """Two parallel leaves ``spacing`` apart from the ground to the stage: lateral stiffness
    24 E I / L^3 (fixed-guided leaves, I = depth t^3 / 12)."""
    half, side = spacing / 2, spacing / 2 + BLOCK
    bodies = (Body("ground", (_box(-side, -BLOCK, side, 0.0),)),
              Body("stage", (_box(-side, length, side, length + BLOCK),)))
    leaves = tuple(Leaf(("ground", "stage"), (x, 0.0), (x, length), thickness, fillet)
                   for x in (-half, half))
    return Mechanism(bodies, leaves, depth)


def compound_parallelogram(length: float, thickness: float, depth: float,
                           inner: float = 0.012, outer: float = 0.048,
                           fillet: float = 0.0) -> Mechanism:
    """A folded compound parallelogram: the outer leaves (``outer`` apart) carry a shuttle from
    a ground in two blocks, the inner leaves (``inner`` apart) the stage from the shuttle; all
    leaves ``length`` long, so the lateral stiffness is 12 E I / L^3 (two guides in series)."""
    gap = (outer - inner) / 2
    stage = inner / 2 + gap / 3
    ground_in, ground_out = inner / 2 + 2 * gap / 3, outer / 2 + gap / 3
    bodies = (Body("ground", (_box(-ground_out, -BLOCK, -ground_in, 0.0),
                              _box(ground_in, -BLOCK, ground_out, 0.0))),
              Body("shuttle", (_box(-ground_out, length, ground_out, length + BLOCK),)),
              Body("stage", (_box(-stage, -BLOCK, stage, 0.0),)))
    leaves = tuple(Leaf((body, "shuttle"), (x, 0.0), (x, length), thickness, fillet)
                   for body, xs in (("ground", (-outer / 2, outer / 2)),
                                    ("stage", (-inner / 2, inner / 2))) for x in xs)
    return Mechanism(bodies, leaves, depth)


def cross_pivot(length: float, thickness: float, depth: float, angle_deg: float = 90.0,
                crossing: bool = True) -> Mechanism:
    """A pivot of two leaves ``length`` long at ``angle_deg`` to each other.

    ``crossing``: the leaves cross at their middles, L cos(angle / 2) / 2 above the ground, and
    are joined there (the planar, monolithic "cartwheel" pivot: four half-leaves from a rigid
    joint, K = 8 E I / L). Otherwise the leaves meet neither each other nor the pivot: they run from
    the ground to the stage on the lines through the pivot (0, 1.25 L cos(angle / 2)), each
    from 1.25 L to 0.25 L before it (a remote-centre pivot: the stage turns about that point,
    K = 2 :func:`pivot_stiffness` (EI, L, -0.25))."""
    half = math.radians(angle_deg) / 2
    dx, dy = math.sin(half), math.cos(half)
    rise = length * dy
    if crossing:
        ends = [((-s * length * dx / 2, 0.0), (s * length * dx / 2, rise)) for s in (-1, 1)]
        width = length * dx / 2 + BLOCK
    else:
        ends = [((s * 1.25 * length * dx, 0.0), (s * 0.25 * length * dx, rise))
                for s in (-1, 1)]
        width = 1.25 * length * dx + BLOCK
    bodies = (Body("ground", (_box(-width, -BLOCK, width, 0.0),)),
              Body("stage", (_box(-width, rise, width, rise + BLOCK),)))
    leaves = tuple(Leaf(("ground", "stage"), a, b, thickness) for a, b in ends)
    return Mechanism(bodies, leaves, depth)


def pivot_stiffness(EI: float, length: float, p: float) -> float:
    """Rotational stiffness (N m/rad) of one leaf (bending stiffness EI, N m^2) whose stage end
    turns about a point p x length from it along the leaf toward the ground (p < 0: beyond the
    stage): (E I / L)(4 - 12 p + 12 p^2) (Euler-Bernoulli, inextensible; p = 1/2, the middle,
    gives E I / L)."""
    return EI / length * (4 - 12 * p + 12 * p * p)
