"""Faces of a mechanism's bodies as groups, named as a designer speaks of them.

``"stage.top"`` is the part of body ``stage``'s outline (where no flexure meets it) on its
extreme +y side: the facets whose midpoint lies on the line y = y_max of the body's bounding
box; ``bottom`` is -y, ``right`` +x, ``left`` -x, and ``"stage.face(+x)"`` (``-x``, ``+y``,
``-y``; in 3-D also ``+z``, ``-z``: the body's top and bottom at z = depth and z = 0) says
the same by its outward normal. In the continuum a face is a boundary group of its own (the
facets, :func:`face_facets`); in the beam model, where the body is rigid, it is the body's
motion at the face's centroid (:func:`face_point`), so that a support, a load or an
observation of a face means the same in both models. Lengths in m.
"""
import re

import numpy as np

from .plane import along, subtract

#: The designer's words for the sides: the axis (0 x, 1 y, 2 z) and the outward sign.
WORDS = {"right": (0, 1), "left": (0, -1), "top": (1, 1), "bottom": (1, -1)}
_FACE = re.compile(r"^face\(\s*([+-])\s*([xyz])\s*\)$")


def side_names(dim: int = 2) -> list[str]:
    """The face selectors of a body: the words, then face(+x) ... (face(+z), face(-z) in 3-D)."""
    axes = "xyz"[:dim]
    return list(WORDS) + [f"face({s}{a})" for a in axes for s in "+-"]


def parse_side(text: str, dim: int = 2):
    """(axis, sign) of a selector ``"top"`` or ``"face(+x)"``, None for anything else (and
    for a z face in 2-D)."""
    if text in WORDS:
        return WORDS[text]
    m = _FACE.match(text.replace(" ", ""))
    if not m:
        return None
    axis = "xyz".index(m.group(2))
    if axis >= dim:
        return None
    return axis, 1 if m.group(1) == "+" else -1


def parse_face(name: str, bodies, dim: int = 2):
    """(body, axis, sign) where ``name`` is ``"BODY.SIDE"`` of one of ``bodies`` (names),
    None otherwise (a body's own name is the body, never a face)."""
    if not isinstance(name, str) or name in bodies:
        return None
    body, dot, side = name.rpartition(".")
    if not dot or body not in bodies:
        return None
    parsed = parse_side(side.strip(), dim)
    return None if parsed is None else (body, *parsed)


def face_names(bodies, dim: int = 2) -> list[str]:
    """Every face group name of ``bodies`` (for messages and the nearest name)."""
    return [f"{b}.{s}" for b in bodies for s in side_names(dim)]


def _extreme(body, axis: int, sign: int) -> float:
    minx, miny, maxx, maxy = body.shape.bounds
    return ((maxx, maxy) if sign > 0 else (minx, miny))[axis]


def face_facets(mesh, mechanism, name: str, body_name: str, axis: int, sign: int):
    """Facet indices of the face of body ``body_name`` on side (``axis``, ``sign``) in the
    FEMesh ``mesh`` (its body groups as mesh_mechanism makes them). ValueError naming the
    face where none of the body's outline lies there (a polygon whose extreme is a vertex,
    or a side covered by flexures)."""
    m = mesh.mesh
    depth, dim = mechanism.depth, mesh.dim
    tol = max(1e3 * mechanism.tol, 1e-12)
    body = mechanism.body(body_name)
    if axis == 2:  # the body's top (z = depth) or bottom (z = 0) in 3-D
        facets = m.boundary_facets()
        mid = m.p[:, m.facets[:, facets]].mean(axis=1)
        level = depth if sign > 0 else 0.0
        inside = np.array([body.contains(xy, -tol) for xy in mid[:2].T])
        chosen = facets[(np.abs(mid[2] - level) <= tol) & inside]
    else:
        facets = mesh.boundaries[body_name]
        mid = m.p[:, m.facets[:, facets]].mean(axis=1)
        chosen = facets[np.abs(mid[axis] - _extreme(body, axis, sign)) <= tol]
    if not len(chosen):
        raise ValueError(f"{mechanism.source}: group {name!r}: body {body_name!r} has no face "
                         f"on its {'+' if sign > 0 else '-'}{'xyz'[axis]} side (its outline "
                         "reaches that side at a corner only, or flexures cover it)")
    return np.sort(chosen)


def _segments(mechanism, body_name: str, axis: int, sign: int) -> list:
    """[(a, b)] the pieces of the body's outline on the side (axis < 2) where no flexure
    meets it (as :meth:`Mechanism.outline_centre` cuts them), m."""
    body, tol = mechanism.body(body_name), mechanism.tol
    level = _extreme(body, axis, sign)
    covered = [(p0, p1) for i in range(len(mechanism.flexures))
               for n, p0, p1 in mechanism.footprint(i) if n == body_name]
    out = []
    for part in getattr(body.shape, "geoms", [body.shape]):
        for ring in (part.exterior, *part.interiors):
            xy = np.array(ring.coords)
            for a, b in zip(xy[:-1], xy[1:]):
                if abs(a[axis] - level) > 10 * tol or abs(b[axis] - level) > 10 * tol:
                    continue
                cuts = [(0.0, 1.0)]
                for p0, p1 in covered:
                    cuts = subtract(cuts, along(a, b, p0, p1, tol))
                out += [(a + lo * (b - a), a + hi * (b - a)) for lo, hi in cuts if hi > lo]
    return out


def face_point(mechanism, name: str, body_name: str, axis: int, sign: int) -> tuple:
    """(centroid (x, y), span (dx, dy)) of the face, m: the point the beam model observes,
    holds and loads the face at, and its extent. A z face (3-D) is the whole body seen from
    above: its area centroid and bounding box."""
    body = mechanism.body(body_name)
    if axis == 2:
        c = body.shape.centroid
        minx, miny, maxx, maxy = body.shape.bounds
        return (float(c.x), float(c.y)), (maxx - minx, maxy - miny)
    pieces = _segments(mechanism, body_name, axis, sign)
    lengths = np.array([np.linalg.norm(b - a) for a, b in pieces])
    if not len(pieces) or lengths.sum() <= 0:
        raise ValueError(f"{mechanism.source}: group {name!r}: body {body_name!r} has no face "
                         f"on its {'+' if sign > 0 else '-'}{'xyz'[axis]} side (its outline "
                         "reaches that side at a corner only, or flexures cover it)")
    mids = np.array([(a + b) / 2 for a, b in pieces])
    centre = lengths @ mids / lengths.sum()
    ends = np.array([p for seg in pieces for p in seg])
    span = ends.max(axis=0) - ends.min(axis=0)
    return tuple(centre.tolist()), tuple(float(s) for s in span)


def with_face_points(beams, mechanism, faces: dict):
    """The BeamSpec ``beams`` of ``mechanism`` with each face of ``faces`` {name: (body,
    axis, sign)} a group of its body's rigid block at the face's centroid."""
    from dataclasses import replace

    if not faces:
        return beams
    index = {b.name: i for i, b in enumerate(mechanism.bodies)}
    rigid = list(beams.rigid)
    groups = dict(beams.groups)
    for name, (body, axis, sign) in faces.items():
        i = index[body]
        point, _ = face_point(mechanism, name, body, axis, sign)
        rigid[i] = replace(rigid[i], groups={**rigid[i].groups, name: point})
        groups[name] = i
    return replace(beams, rigid=tuple(rigid), groups=groups)


def named_faces(parts: dict, outputs, bodies, dim: int) -> dict:
    """{face group: (body, axis, sign)} of every face of a body that a model file's
    supports, loads, [analysis] groups (``parts``: its parsed tables) and ``outputs`` name."""
    named = [s.group for s in parts["supports"]] + [load.group for load in parts["loads"]]
    analysis = parts["analysis"]
    named += [analysis.compliance] + ([analysis.harmonic.group] if analysis.harmonic else [])
    named += [g for o in outputs for g in o.groups]
    return {name: face for name in dict.fromkeys(named)
            if (face := parse_face(name, bodies, dim)) is not None}
