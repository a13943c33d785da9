"""Oblique roots: where a beam's flexible length begins when it leaves its block at an angle.

A leaf of thickness t whose centre line leaves a block face at the angle phi has its two edges
meet the face (t/2) cot(phi) before and after the centre line: between them each section of
the leaf is partly inside the block. In beam theory a section stays plane, so a section held
by the block on part of its depth turns with the block: the leaf bends freely only where its
whole section has left the block, at the acute edge's meeting with the face,

    s_root = (t / 2) cot(phi)

along the centre line from its meeting with the face (0 for a square root), from where the
stress spreads into the block as at a square root (the common root extension). The same rule
as the leaves' solid joint where two beams cross (:mod:`.crossings`); no new constant. Checked
against the continuum for phi = 15-90 degrees (examples/oblique_leaf/root_table.py,
docs/model_files.md "The beam model"). Lengths in m.
"""
import math

import numpy as np

from ..geometry.polygon import edge_at

SHALLOWEST = 10.0  # degrees: a shallower root is refused, as a shallower crossing


def face_normal(point, blocks, tol: float):
    """The unit normal (2,) of the face of one of the rectangles ``blocks`` ((2, 2) opposite
    corners, m) or polygons ((k, 2) vertices) that ``point`` (m) lies on; None where it lies
    on none or on a corner."""
    for block in blocks:
        if len(block) > 2:
            edge = edge_at(block, point, tol, corners=False)
            if edge is not None:
                return np.array([-edge[1], edge[0]])
            continue
        (x0, y0), (x1, y1) = block
        (xl, xh), (yl, yh) = sorted((x0, x1)), sorted((y0, y1))
        inside_x = xl + tol < point[0] < xh - tol
        inside_y = yl + tol < point[1] < yh - tol
        if inside_y and min(abs(point[0] - xl), abs(point[0] - xh)) <= tol:
            return np.array([1.0, 0.0])
        if inside_x and min(abs(point[1] - yl), abs(point[1] - yh)) <= tol:
            return np.array([0.0, 1.0])
    return None


def root_offset(point, direction, thickness: float, blocks, tol: float, where: str) -> float:
    """s_root (m): how far along ``direction`` (unit (2,), out of the block into the beam) from
    ``point`` (m, on a face of ``blocks``) the beam's whole section of ``thickness`` (m) has
    left the block: (t/2) cot(phi), phi the angle between beam and face; 0 where the point lies
    on no face (no block declared there). ValueError prefixed by ``where`` below 10 degrees."""
    normal = face_normal(point, blocks, tol)
    if normal is None:
        return 0.0
    sin = abs(float(np.dot(direction, normal)))
    if sin < math.sin(math.radians(SHALLOWEST)):
        raise ValueError(f"{where}: [[beam]] leaves its block at {list(point)} at "
                         f"{math.degrees(math.asin(min(sin, 1.0))):.3g} degrees, less than "
                         f"{SHALLOWEST:g}: a root needs a clear angle")
    return thickness / 2 * math.sqrt(max(0.0, 1.0 - sin * sin)) / sin
