"""How big a model file's mesh will be, before gmsh is asked for it (fem/budget.py decides
whether it fits the machine).

From the loaded geometry, without meshing: each curve's node count from its length and the
element sizes at its ends (gmsh interpolates the size linearly along a curve: the nodes are
L ln(h1/h0) / (h1 - h0)), and each surface's (volume's) elements at the largest size on its
boundary: no element is larger, so A / (sqrt(3)/4 h_max^2) triangles (V / (h_max^3 / 8.5)
tetrahedra) is a lower bound for a uniform-size region, and areas come from OpenCASCADE where
it made the entity (its bounding box otherwise, an upper bound). An element size that is not
a positive finite length well above round-off (1e-9 of the model) is refused outright: gmsh
would silently mesh coarser, or never finish. Lengths in m.
"""
import math

import numpy as np

from ...fem.budget import NODES_PER_ELEMENT, TETRAHEDRA_PER_CUBE, TRIANGLE


def _length(gmsh, curve: int) -> float:
    try:
        return float(gmsh.model.occ.getMass(1, curve))
    except Exception:  # noqa: BLE001 - a built-in kernel curve: measure it by sampling
        lo, hi = gmsh.model.getParametrizationBounds(1, curve)
        u = np.linspace(lo[0], hi[0], 33)
        xyz = np.asarray(gmsh.model.getValue(1, curve, u)).reshape(-1, 3)
        return float(np.linalg.norm(np.diff(xyz, axis=0), axis=1).sum())


def _measure(gmsh, dim: int, tag: int) -> float:
    try:
        return float(gmsh.model.occ.getMass(dim, tag))
    except Exception:  # noqa: BLE001 - a built-in kernel entity: its bounding box
        box = gmsh.model.getBoundingBox(dim, tag)
        return float(np.prod([max(box[3 + k] - box[k], 0.0) for k in range(dim)]))


def _curves_of(gmsh, dim: int, tag: int) -> set:
    """The curves bounding a surface, or a volume's surfaces (a recursive getBoundary of a
    volume returns its points only)."""
    faces = [tag] if dim == 2 else [abs(t) for _, t in gmsh.model.getBoundary(
        [(3, tag)], combined=False, oriented=False)]
    return {abs(t) for f in faces for _, t in gmsh.model.getBoundary(
        [(2, f)], combined=False, oriented=False)}


def _nodes_along(length: float, h0: float, h1: float) -> float:
    if abs(h1 - h0) <= 1e-12 * max(h0, h1):
        return length / h0
    return length * math.log(h1 / h0) / (h1 - h0)


def estimate_geometry_mesh(gmsh, dim: int, order: int, size_factor: float = 1.0,
                           size_max: float | None = None, what: str = "the geometry") -> dict:
    """{"elements", "nodes", "dofs"} expected of meshing the loaded geometry; ValueError naming
    ``what`` for an element size gmsh cannot honour."""
    box = gmsh.model.getBoundingBox(-1, -1)
    diag = math.dist(box[:3], box[3:])
    if not 1e-6 <= diag <= 10.0:
        raise ValueError(f"{what}: the geometry is {diag:.4g} m across; lengths are in m (a "
                         "flexure mechanism is 1 um to 10 m)")
    points = gmsh.model.getEntities(0)
    given = gmsh.model.mesh.getSizes(points) if points else []
    cap = min(size_max or math.inf, diag)
    size = {tag: min(float(lc) if lc > 0 else diag, cap) * size_factor
            for (_, tag), lc in zip(points, given)}
    smallest = min(size.values(), default=cap * size_factor)
    if not (math.isfinite(smallest) and smallest > 1e-9 * diag):
        raise ValueError(f"{what}: an element size of {smallest:.3g} m on a model "
                         f"{diag:.3g} m across cannot be meshed (gmsh honours sizes down to "
                         "~1e-9 of the model); check the sizes and lengths (m) that set it")
    nodes_1d, largest = 0.0, {}
    for _, curve in gmsh.model.getEntities(1):
        ends = [abs(t) for _, t in gmsh.model.getBoundary([(1, curve)], recursive=False)]
        h = [size.get(p, cap * size_factor) for p in ends] or [cap * size_factor]
        nodes_1d += _nodes_along(_length(gmsh, curve), min(h), max(h))
        largest[curve] = max(h)
    elements = nodes_1d
    for _, tag in gmsh.model.getEntities(dim):
        h = max((largest.get(c, cap * size_factor) for c in _curves_of(gmsh, dim, tag)),
                default=cap * size_factor)
        cell = TRIANGLE * h * h if dim == 2 else h ** 3 / TETRAHEDRA_PER_CUBE
        elements += _measure(gmsh, dim, tag) / cell
    nodes = NODES_PER_ELEMENT[(dim, order)] * elements
    return {"elements": int(min(elements, 1e18)), "nodes": int(min(nodes, 1e18)),
            "dofs": int(min(dim * nodes, 1e18))}


def _polyline(gmsh, curve: int, samples: int = 9) -> np.ndarray:
    lo, hi = gmsh.model.getParametrizationBounds(1, curve)
    u = np.linspace(lo[0], hi[0], samples)
    return np.asarray(gmsh.model.getValue(1, curve, u)).reshape(-1, 3)[:, :2]


def _crossing(p: np.ndarray, others: np.ndarray, tol: float) -> np.ndarray:
    """Which of the segments ``others`` (k, 2, 2) cross segment ``p`` (2, 2) at an interior
    point; segments sharing an end with ``p`` (adjacent pieces of an outline) excepted."""
    def orient(a, b, c):
        return (b[..., 0] - a[..., 0]) * (c[..., 1] - a[..., 1]) - \
            (b[..., 1] - a[..., 1]) * (c[..., 0] - a[..., 0])

    shared = np.linalg.norm(p[:, None, None, :] - others[None, :, :, :], axis=-1).min(
        axis=(0, 2)) <= tol
    q0, q1 = others[:, 0], others[:, 1]
    d1, d2 = orient(q0, q1, p[0]), orient(q0, q1, p[1])
    d3, d4 = orient(p[0], p[1], q0), orient(p[0], p[1], q1)
    return ~shared & (d1 * d2 < 0) & (d3 * d4 < 0)


def check_outlines(gmsh, what: str = "the geometry") -> None:
    """ValueError naming ``what`` where a plane surface's boundary crosses itself or a hole
    touches its outline (a dimension set so that the drawing turns inside out: a negative or
    vanishing length): gmsh would mesh it for minutes before failing."""
    if gmsh.model.getDimension() != 2:
        return
    box = gmsh.model.getBoundingBox(-1, -1)
    tol = 1e-9 * math.dist(box[:3], box[3:])
    points = gmsh.model.getEntities(0)
    xyz = np.array([gmsh.model.getValue(0, tag, []) for _, tag in points]).reshape(-1, 3)
    for i in range(len(xyz)):
        close = np.flatnonzero(np.linalg.norm(xyz[i + 1:] - xyz[i], axis=1) <= tol)
        if close.size:
            raise ValueError(f"{what}: points {points[i][1]} and "
                             f"{points[i + 1 + close[0]][1]} of the drawing coincide: a "
                             "dimension vanishes or is negative")
    for _, surface in gmsh.model.getEntities(2):
        curves = sorted({abs(t) for _, t in gmsh.model.getBoundary([(2, surface)],
                                                                   oriented=False)})
        pieces = []
        for c in curves:
            line = _polyline(gmsh, c)
            if np.linalg.norm(line[-1] - line[0]) <= tol and np.ptp(line, axis=0).max() <= tol:
                raise ValueError(f"{what}: curve {c} of surface {surface} has no length; a "
                                 "dimension of the drawing vanishes")
            pieces += [(c, line[k:k + 2]) for k in range(len(line) - 1)]
        owner = np.array([c for c, _ in pieces])
        segments = np.array([seg for _, seg in pieces])
        for i in range(len(pieces) - 1):  # one vectorised row a piece: O(n) Python steps
            hit = _crossing(segments[i], segments[i + 1:], tol) & (owner[i + 1:] != owner[i])
            if hit.any():
                raise ValueError(f"{what}: the outline of surface {surface} crosses itself "
                                 f"(curves {owner[i]} and {owner[i + 1 + hit.argmax()]}): a "
                                 "dimension of the drawing is negative or too small for the "
                                 "shapes around it")
