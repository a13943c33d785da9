"""Crossings of a model file's beams: the solid joint where two declared beams cross.

Two leaves of in-plane thicknesses t_i, t_j whose centre lines cross at an angle alpha overlap
in a solid rhombus (a parallelogram): along leaf i it is t_j / sin(alpha) long, centred on the
crossing point. Neither leaf bends inside it, so the beam model makes each beam rigid (joined
to the crossing node by an exact rigid link) over

    a_i = t_j / (2 sin alpha) - root x t_i      on either side of the crossing point,

the rhombus less the root extension by which every beam enters the block it meets
(ROOT_EXTENSION x its thickness, docs/beam.md, "Joints and slenderness"): the stress field
spreads into the joint as into any block. A beam that a crossing point splits is a beam with
that point inside its points (not at an end); beams that only meet at an end stay welded
there. Lengths in m.
"""
import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Crossing:
    """A crossing ``point`` (m) and its rigid stubs: ``cuts`` ((beam index, segment index,
    arc length of the cut from that segment's first point, m), ...)."""

    point: tuple
    cuts: tuple


def _unit(a, b) -> np.ndarray:
    d = np.subtract(b, a)
    return d / np.linalg.norm(d)


def _passing(beams, point, tol) -> list:
    """[(beam index, point index)] of the beams with ``point`` among their inner points."""
    return [(i, k) for i, line in enumerate(beams) for k in range(1, len(line.points) - 1)
            if math.dist(line.points[k], point) <= tol]


def _half_length(line, k, others, root: float) -> tuple:
    """(before, after): the rigid length (m) of beam ``line`` on each side of its point k:
    the widest other beam's overlap t_j / (2 sin alpha) less root x t_i, at least 0."""
    p = line.points[k]
    t_i = line.thickness(line.thickness.arc[k])
    sides = []
    for q in (line.points[k - 1], line.points[k + 1]):
        d_i, half = _unit(p, q), 0.0
        for other, m in others:
            t_j = other.thickness(other.thickness.arc[m])
            for r in (other.points[m - 1], other.points[m + 1]):
                sin = abs(float(np.cross(d_i, _unit(other.points[m], r))))
                if sin < math.sin(math.radians(10)):
                    raise ValueError(f"{line.source}: [[beam]] crosses another beam at "
                                     f"{list(p)} at less than 10 degrees; a crossing "
                                     "needs a clear angle (or join them with a [[rigid]])")
                half = max(half, t_j / (2 * sin))
        sides.append(max(0.0, half - root * t_i))
    return tuple(sides)


def crossings(beams, tol: float, root: float) -> list:
    """The crossings of ``beams`` (BeamLine tuple): every inner point shared by two or more
    beams, with the cuts of each beam's rigid stubs (``root`` x thickness less than the
    rhombus, see the module docstring). ValueError naming the beam when a stub would reach
    past the beam's next point."""
    found, seen = [], []
    for line in beams:
        for point in line.points[1:-1]:
            if any(math.dist(point, q) <= tol for q in seen):
                continue
            passing = _passing(beams, point, tol)
            if len(passing) < 2:
                continue
            seen.append(point)
            cuts = []
            for i, k in passing:
                others = [(beams[j], m) for j, m in passing if j != i]
                before, after = _half_length(beams[i], k, others, root)
                pts = beams[i].points
                for seg, s, span in ((k - 1, math.dist(pts[k - 1], pts[k]) - before, before),
                                     (k, after, after)):
                    if span <= 0:
                        continue
                    if span >= math.dist(pts[seg], pts[seg + 1]) - tol:
                        raise ValueError(f"{beams[i].source}: [[beam]] the solid joint where "
                                         f"it crosses another beam at {list(point)} "
                                         f"({span:.3g} m) reaches past its next point")
                    cuts.append((i, seg, s))
            found.append(Crossing(tuple(point), tuple(cuts)))
    return found
