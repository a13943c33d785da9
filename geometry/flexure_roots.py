"""Filleted flexure roots: the quarter-circle fillets where a beam flexure meets its links.

A flexure (:class:`~flexfem.geometry.flexure_linkage.Part` of kind "flexure", width w, length L)
meets a W-wide bar or hub, collinear with it, at each end: two re-entrant right-angled corners
per end, where a sharp corner is a stress singularity. A root fillet of radius r fills each
corner with the region between the corner's two edges and a quarter circle tangent to both
(centre r from each): it adds r^2 (1 - pi/4) of material per corner, 4 per flexure.

With fillets a flexure is drawn as three surfaces: two *root zones* (the last r + w of its
length at each end with the two fillets, one surface each, so no internal edge touches the
arcs) meshed unstructured and fine, and the straight *middle* rectangle, structured as the
sharp flexure is. All lengths in m.
"""
import math

import numpy as np


def root_zone_depth(radius: float, width: float) -> float:
    """Length (m) of a flexure's root zone along its axis: the fillet (radius) plus one
    flexure width, so the fillet's tangent point, near which the stress peaks, lies inside
    the finely meshed zone."""
    return radius + width


def check_root_fillet_radius(radius, parts, link_width: float) -> float:
    """``radius`` (m) as a float, or ValueError naming root_fillet_radius and the bound it
    breaks: finite and >= 0; the fillet must fit the step from the flexure to the link,
    w / 2 + r <= W / 2; the two root zones must leave a straight middle, 2 (r + w) < L."""
    if not (isinstance(radius, (int, float, np.floating, np.integer)) and not isinstance(radius, bool)
            and math.isfinite(radius) and radius >= 0):
        raise ValueError(f"root_fillet_radius = {radius!r} m, must be a finite number >= 0")
    radius = float(radius)
    if radius == 0.0:
        return radius
    for part in parts:
        if part.kind != "flexure":
            continue
        step = (link_width - part.width) / 2
        if radius > step * (1 + 1e-12):
            raise ValueError(f"root_fillet_radius = {radius} m, must be <= (link_width - width) / 2 "
                             f"= {step:.6g} m for {part.name} (the fillet must fit the step from "
                             "the flexure to its link)")
        limit = part.length / 2 - part.width
        if not radius < limit:
            raise ValueError(f"root_fillet_radius = {radius} m, must be < length / 2 - width = "
                             f"{limit:.6g} m for {part.name} (the filleted roots must leave a "
                             "straight middle)")
    return radius


def root_zone_outline(part, end: int, radius: float) -> dict:
    """Outline of the root zone at end ``end`` (0: ``part.p0``, 1: ``part.p1``) of a flexure
    ``part`` with fillets of ``radius`` (m). Returns {"inner": (a, a') the across edge shared
    with the middle, "tangent": (b, b') the arcs' tangent points on the flexure sides,
    "face": (f, f') the arcs' ends on the link's face, "centre": (c, c') the arcs' centres},
    each point an (x, y) array in m; primed points on the -n side."""
    p0, p1 = np.asarray(part.p0, float), np.asarray(part.p1, float)
    d = (p1 - p0) / np.linalg.norm(p1 - p0)
    n = np.array([-d[1], d[0]])
    e, out = (p0, -d) if end == 0 else (p1, d)  # the end point and the outward axis direction
    w, r = part.width, radius
    depth = root_zone_depth(r, w)
    pair = lambda along, across: (e + along * out + across * n, e + along * out - across * n)
    return {"inner": pair(-depth, w / 2), "tangent": pair(-r, w / 2),
            "face": pair(0.0, w / 2 + r), "centre": pair(-r, w / 2 + r)}


def draw_filleted_flexure(occ, part, radius: float) -> list:
    """Draw a flexure with root fillets in the OCC kernel ``occ``: [(root zone at p0 tag,
    "root"), (middle tag, "middle"), (root zone at p1 tag, "root")]."""
    def point(xy):
        return occ.addPoint(float(xy[0]), float(xy[1]), 0.0)

    zones = []
    for end in (0, 1):
        o = root_zone_outline(part, end, radius)
        a, a_ = (point(p) for p in o["inner"])
        b, b_ = (point(p) for p in o["tangent"])
        f, f_ = (point(p) for p in o["face"])
        c, c_ = (point(p) for p in o["centre"])
        curves = [occ.addLine(a, b), occ.addCircleArc(b, c, f), occ.addLine(f, f_),
                  occ.addCircleArc(f_, c_, b_), occ.addLine(b_, a_), occ.addLine(a_, a)]
        zones.append(occ.addPlaneSurface([occ.addCurveLoop(curves)]))
    o0, o1 = root_zone_outline(part, 0, radius), root_zone_outline(part, 1, radius)
    corners = [o0["inner"][1], o1["inner"][1], o1["inner"][0], o0["inner"][0]]
    pts = [point(p) for p in corners]
    lines = [occ.addLine(pts[i], pts[(i + 1) % 4]) for i in range(4)]
    middle = occ.addPlaneSurface([occ.addCurveLoop(lines)])
    return [(zones[0], "root"), (middle, "middle"), (zones[1], "root")]

