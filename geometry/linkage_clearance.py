"""Clearance of a linkage's links drawn as bars of a given width (single-layer layouts).

Each link is drawn along its centre-line (see :attr:`.linkage.Link.polylines`); two links overlap
where their centre-lines come closer than the bar width (m), away from the joints they share.
"""
import numpy as np

from .linkage import Linkage, Trace


def link_segments(linkage: Linkage, q, *, include_ground=False) -> dict:
    """Centre-line segments of each link in pose ``q``: {link: [(name0, name1, p0, p1), ...]}
    (see :attr:`.linkage.Link.polylines`)."""
    segments = {}
    for link in linkage.links:
        if link.name == linkage.ground and not include_ground:
            continue
        segments[link.name] = [(a, b, linkage.point_position(q, link.name, a),
                                linkage.point_position(q, link.name, b)) for a, b in link.segment_names]
    return segments


def segment_distance(p0, p1, r0, r1) -> float:
    """Shortest distance (m) between segments p0-p1 and r0-r1."""
    p0, p1, r0, r1 = (np.asarray(v, float) for v in (p0, p1, r0, r1))

    def cross(a, b):
        return a[0] * b[1] - a[1] * b[0]

    d1, d2, w = p1 - p0, r1 - r0, r0 - p0
    denom = cross(d1, d2)
    if denom != 0:
        s, t = cross(w, d2) / denom, cross(w, d1) / denom
        if 0 <= s <= 1 and 0 <= t <= 1:
            return 0.0

    def point_segment(p, a, b):
        ab = b - a
        t = 0.0 if not ab.any() else np.clip(np.dot(p - a, ab) / np.dot(ab, ab), 0.0, 1.0)
        return float(np.hypot(*(a + t * ab - p)))

    return min(point_segment(p0, r0, r1), point_segment(p1, r0, r1),
               point_segment(r0, p0, p1), point_segment(r1, p0, p1))


def _trim(name0, name1, p0, p1, shared, clearance):
    """Shorten a segment by ``clearance`` (m) at each end that is a joint shared with the other link."""
    length = np.hypot(*(p1 - p0))
    u = (p1 - p0) / length if length > 0 else np.zeros(2)
    cut0 = clearance if name0 in shared else 0.0
    cut1 = clearance if name1 in shared else 0.0
    if cut0 + cut1 >= length:
        return None
    return p0 + cut0 * u, p1 - cut1 * u


def overlapping_links(linkage: Linkage, q, width: float, joint_clearance: float = None) -> list:
    """Pairs of links (sorted names) whose bars of ``width`` (m) intersect in pose ``q``.

    Two bars overlap where their centre-lines come closer than ``width``. Near a joint the two
    links share (both carry the joint's point) the bars meet by design, so each segment is
    first shortened there by ``joint_clearance`` (m; default 2 * width). The ground is left out.
    """
    if width <= 0:
        raise ValueError(f"width = {width} m, must be > 0")
    clearance = 2.0 * width if joint_clearance is None else joint_clearance
    joint_points = {}
    for joint in linkage.joints:
        for name in joint.links:
            joint_points.setdefault(name, set()).add(joint.point)
    segments = link_segments(linkage, q)
    names = sorted(segments)
    pairs = []
    for i, a in enumerate(names):
        for b in names[i + 1:]:
            shared = joint_points.get(a, set()) & joint_points.get(b, set())
            if _links_overlap(segments[a], segments[b], shared, clearance, width):
                pairs.append((a, b))
    return pairs


def _links_overlap(segs_a, segs_b, shared, clearance, width):
    for na0, na1, pa0, pa1 in segs_a:
        ta = _trim(na0, na1, pa0, pa1, shared, clearance)
        for nb0, nb1, pb0, pb1 in segs_b:
            tb = _trim(nb0, nb1, pb0, pb1, shared, clearance)
            if ta is not None and tb is not None and segment_distance(*ta, *tb) < width:
                return True
    return False


def overlapping_links_along(trace_: Trace, width: float, joint_clearance: float = None) -> list:
    """Pairs of links that overlap (see :func:`overlapping_links`) in any pose of a trace."""
    found = set()
    for q in trace_.poses:
        found.update(overlapping_links(trace_.linkage, q, width, joint_clearance))
    return sorted(found)
