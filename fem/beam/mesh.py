"""Beam meshes (nodes, elements, one Section each) for a :class:`~.model.BeamModel`: straight
chains, flexures through a thickness profile, and their unions.

    arm = beam_chain([(0, 0), (0.05, 0)], Section.rect(0.01, 0.5e-3), n_per_segment=20)
    leaf = beam_from_profile((0.05, 0), (0.09, 0), lambda s: 0.5e-3 + s / 100, 0.01, n=20)
    mesh = arm.join(leaf)   # BeamModel(mesh.nodes, mesh.elements, mesh.sections, steel)

Lengths in m.
"""
from dataclasses import dataclass, field
import math

import numpy as np

from ..checks import positive
from .section import Section, rect_sections


@dataclass
class BeamMesh:
    """Nodes (n, 2) m, elements (n_e, 2) node pairs, one Section per element, and
    ``point_nodes``: the node index of each input point (beam_chain) or end (profile)."""

    nodes: np.ndarray
    elements: np.ndarray
    sections: list
    point_nodes: list = field(default_factory=list)

    def join(self, other: "BeamMesh", tol: float = 1e-12) -> "BeamMesh":
        """Union of two meshes, merging nodes closer than ``tol`` (m). The other mesh's
        point_nodes are appended, renumbered."""
        d = point_distances(other.nodes, self.nodes)
        index = d.argmin(axis=1)  # the nearest node, or a new one
        new = ~(d.min(axis=1) <= tol)
        index[new] = len(self.nodes) + np.arange(np.count_nonzero(new))
        return BeamMesh(np.vstack([self.nodes, other.nodes[new]]),
                        np.vstack([self.elements, index[other.elements]]),
                        list(self.sections) + list(other.sections),
                        list(self.point_nodes) + [int(index[k]) for k in other.point_nodes])

    def node_at(self, point, tol: float = 1e-9) -> int:
        """Index of the node at ``point`` (m); ValueError if none within ``tol``."""
        d = point_distances(np.asarray(point, dtype=float)[None, :], self.nodes)[0]
        if d.min() > tol:
            raise ValueError(f"point = {list(point)} is not a node (nearest {d.min():.3g} m)")
        return int(np.argmin(d))


def point_distances(a, b) -> np.ndarray:
    """(len(a), len(b)) distances (m) between points a (k, 2) and b (m, 2): numpy.linalg.norm's
    numbers, coordinate by coordinate (its sum over an axis of length two is ~4x slower)."""
    dx, dy = a[:, 0, None] - b[None, :, 0], a[:, 1, None] - b[None, :, 1]
    return np.sqrt(dx * dx + dy * dy)


def beam_chain(points, sections, n_per_segment) -> BeamMesh:
    """A planar chain of straight beam segments.

    Parameters
    ----------
    points : array_like, shape (k, 2)
        The segments' ends (m), k >= 2.
    sections : Section or sequence of Section
        One section for every segment, or one per segment.
    n_per_segment : int or sequence of int
        Elements per segment (>= 1).

    Returns
    -------
    BeamMesh
        Nodes (m), elements, sections; point j is node ``point_nodes[j]``.
    """
    pts = np.asarray(points, dtype=float)
    if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 2:
        raise ValueError(f"points must be (k >= 2, 2) coordinates, got shape {pts.shape}")
    n_seg = len(pts) - 1
    secs = [sections] * n_seg if isinstance(sections, Section) else list(sections)
    counts = np.broadcast_to(np.asarray(n_per_segment), (n_seg,))
    if len(secs) != n_seg:
        raise ValueError(f"sections: {len(secs)} given for {n_seg} segments")
    if not all(isinstance(c, (int, np.integer)) and c >= 1 for c in counts.tolist()):
        raise ValueError(f"n_per_segment = {n_per_segment!r} must be integers >= 1")
    nodes, sec_list, point_nodes = [pts[0]], [], [0]
    same = np.all(np.abs(pts[1:] - pts[:-1]) <= 1e-8 + 1e-5 * np.abs(pts[1:]), axis=1)  # allclose
    for j in range(n_seg):
        if same[j]:
            raise ValueError(f"points {j} and {j + 1} coincide")
        s = (np.arange(1, int(counts[j]) + 1) / int(counts[j]))[:, None]
        nodes.extend(pts[j] + s * (pts[j + 1] - pts[j]))
        nodes[-1] = pts[j + 1]  # exactly the given point
        sec_list += [secs[j]] * int(counts[j])
        point_nodes.append(len(nodes) - 1)
    n = len(nodes)
    elements = np.column_stack([np.arange(n - 1), np.arange(1, n)])
    return BeamMesh(np.array(nodes), elements, sec_list, point_nodes)


def beam_from_profile(x0, x1, thickness_fn, width: float, n: int,
                      vectorized: bool = False) -> BeamMesh:
    """A straight flexure from ``x0`` to ``x1`` (m) whose in-plane thickness (m) is
    ``thickness_fn(s)``, s the arc length from x0 (m): ``n`` tapered rectangular elements
    of ``width`` (m), each quadratic through the profile's values at its ends and middle
    (a circular notch: 3e-5 compliance error with n = 20). ``vectorized``: thickness_fn
    takes the array of all 2 n + 1 arc lengths at once (one call instead of one a point)."""
    a, b = np.asarray(x0, dtype=float), np.asarray(x1, dtype=float)
    if not (isinstance(n, (int, np.integer)) and n >= 1):
        raise ValueError(f"n = {n!r} must be an integer >= 1")
    length = float(np.linalg.norm(b - a))
    if length == 0:
        raise ValueError("x0 and x1 coincide")
    s = np.linspace(0.0, length, 2 * n + 1)
    if vectorized:
        t = np.asarray(thickness_fn(s), dtype=float)
        if t.shape != s.shape:
            raise ValueError(f"thickness_fn (vectorized) must return one thickness per arc "
                             f"length, shape {s.shape}; got shape {t.shape}")
    else:
        t = np.array([float(thickness_fn(si)) for si in s.tolist()])
    if not (np.isfinite(t).all() and (t > 0).all()):
        raise ValueError(f"thickness_fn must return finite thicknesses > 0; got {t.min()!r}")
    nodes = a + (s[::2] / length)[:, None] * (b - a)
    sections = rect_sections(width, t[0:-1:2], t[2::2], t[1::2])
    elements = np.arange(n)[:, None] + np.arange(2)  # (k, k + 1)
    return BeamMesh(nodes, elements, sections, [0, n])


def profile_chain(starts, ends, arcs, counts, thickness_fn, width: float) -> BeamMesh:
    """Consecutive straight pieces of one flexure, piece i from ``starts[i]`` to ``ends[i]``
    (m; it begins where the one before it ends) at arc length ``arcs[i]`` (m) along the
    flexure, as one chain: on each piece beam_from_profile's ``counts[i]`` elements through
    ``thickness_fn`` (vectorized, of the arc length, m), the same numbers, one node where two
    pieces meet (the earlier piece's). point_nodes: each piece's first and last node."""
    starts, ends = np.asarray(starts, dtype=float), np.asarray(ends, dtype=float)
    counts = np.asarray(counts, dtype=np.int64)
    lengths = np.array([float(np.linalg.norm(b - a)) for a, b in zip(starts, ends)])
    if not (counts >= 1).all() or not (lengths > 0).all():
        raise ValueError("profile_chain: every piece needs a length > 0 and elements >= 1")
    # beam_from_profile's linspace(0, L, 2 n + 1) on each piece: j (L / 2 n), its end L
    piece = np.repeat(np.arange(len(counts)), 2 * counts + 1)
    first = np.concatenate([[0], np.cumsum(2 * counts + 1)[:-1]])
    j = np.arange(len(piece)) - first[piece]
    s = j * (lengths / (2 * counts))[piece]
    s[first + 2 * counts] = lengths
    t = np.asarray(thickness_fn(np.asarray(arcs, dtype=float)[piece] + s), dtype=float)
    if not (np.isfinite(t).all() and (t > 0).all()):
        raise ValueError(f"thickness_fn must return finite thicknesses > 0; got {t.min()!r}")
    node = np.flatnonzero(j % 2 == 0)  # the element ends: a node each, but a piece's first
    node = node[(j[node] > 0) | (piece[node] == 0)]  # (after the first piece: the last end)
    nodes = starts[piece[node]] + (s[node] / lengths[piece[node]])[:, None] \
        * (ends - starts)[piece[node]]
    mid = np.flatnonzero(j % 2 == 1)  # each element's middle, then its ends around it
    sections = rect_sections(width, t[mid - 1], t[mid + 1], t[mid])
    n = int(counts.sum())
    at = np.concatenate([[0], np.cumsum(counts)])
    return BeamMesh(nodes, np.arange(n)[:, None] + np.arange(2), sections,
                    [int(k) for a, b in zip(at[:-1], at[1:]) for k in (a, b)])
