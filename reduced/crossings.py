"""Crossings of a model file's beams: the solid joint where two declared beams cross.

Two leaves of in-plane thicknesses t_i, t_j whose centre lines cross at an angle alpha overlap
in a solid parallelogram (a rhombus for equal thicknesses): leaf j's band is t_j / sin(alpha)
long along leaf i's centre line, and leaf i's edges (t_i / 2 off its centre line) leave it
(t_i / 2) cot(alpha) further on. Leaf i is a free beam only where its whole section has left
the joint, so the beam model makes each beam rigid (joined to the crossing node by an exact
rigid link) over

    a_i = t_j / (2 sin alpha) + (t_i / 2) cot(alpha) - root x t_i

on either side of the crossing point: the joint less the root extension by which every beam
enters the block it meets (``root`` x its thickness, 0.38 by default, docs/beam.md, "Joints
and slenderness"): the stress field spreads into the joint as into any block. A crossing is a
point inside the points of two or more beams (not an end); beams that only meet at an end
stay welded there. Lengths in m.
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
    the widest other beam's joint t_j / (2 sin alpha) + (t_i / 2) cot(alpha) less root x
    t_i, at least 0."""
    p = line.points[k]
    t_i = line.thickness(line.thickness.arc[k])
    sides = []
    for q in (line.points[k - 1], line.points[k + 1]):
        d_i, half = _unit(p, q), 0.0
        for other, m in others:
            t_j = other.thickness(other.thickness.arc[m])
            for r in (other.points[m - 1], other.points[m + 1]):
                d_j = _unit(other.points[m], r)
                sin = abs(float(d_i[0] * d_j[1] - d_i[1] * d_j[0]))
                if sin < math.sin(math.radians(10)):
                    raise ValueError(f"{line.source}: [[beam]] crosses another beam at "
                                     f"{list(p)} at less than 10 degrees; a crossing "
                                     "needs a clear angle (or join them with a [[rigid]])")
                cot = abs(float(d_i @ d_j)) / sin
                half = max(half, t_j / (2 * sin) + t_i / 2 * cot)
        sides.append(max(0.0, half - root * t_i))
    return tuple(sides)


def crossings(beams, tol: float, root: float) -> list:
    """The crossings of ``beams`` (BeamLine tuple): every inner point shared by two or more
    beams, with the cuts of each beam's rigid stubs (the joint less ``root`` x thickness,
    see the module docstring). ValueError naming the beam when a stub would reach
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
