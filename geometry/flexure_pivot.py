"""Geometry and mesh of flexure pivots in the plane: a cross-spring pivot and a single leaf.

Cross-spring pivot: two leaves of free length L and thickness t cross at their midpoints (the
origin) at ``crossing_angle``, leaf 1 rising at +angle/2 and leaf 2 falling at -angle/2 from
the x-axis, between a base block (x < 0) and a hub block (x > 0) whose faces meet each leaf end
square. Single leaf ("beam" pivot): one leaf along the x-axis from x = -L/2 to L/2.

In a real cross-spring pivot the leaves lie in different layers (interleaved across the width)
and never touch. In the plane they overlap at the crossing; here they are drawn as separate
surfaces that share no curve and are meshed independently, so the overlapping leaves do not
interact, as in the real pivot, and a plane-stress model of thickness w gives each leaf its width
w. ``joined=True`` instead fuses them at the crossing: the monolithic "cartwheel" pivot, which
linear beam theory makes four times stiffer (8 E I / L against 2 E I / L).

``block_length = 0`` draws no blocks: the leaf end faces are then the groups "fixed" (base ends)
and "hub" (hub ends), and the blocks are rigid (a Fixed support and a RigidFace), as beam theory
assumes. ``block_length > 0`` adds elastic blocks (a monolithic part) whose outer faces are
"fixed" and "hub"; their re-entrant corners at the leaf roots are sharp, so stresses there are
singular. Subdomains: "leaves", "leaf_1", "leaf_2" (cross only) and "blocks". Lengths in m.
"""
import math
import numbers
from dataclasses import dataclass

import numpy as np

from ..fem.checks import positive
from ..fem.gmsh_session import gmsh_session
from ..fem.mesh import FEMesh, mesh_from_gmsh

KINDS = ("cross", "single")


@dataclass(frozen=True)
class PivotGeometry:
    """kind: "cross" or "single"; L: free leaf length (m); t: leaf thickness in the plane (m,
    <= L / 5); crossing_angle: angle between the two leaves (rad, in [pi/6, 5 pi/6], cross
    only); block_length: depth of the base and hub blocks (m, >= 0; 0 = rigid blocks, not
    drawn); joined: fuse the leaves at the crossing (cross only)."""

    kind: str
    L: float
    t: float
    crossing_angle: float = math.pi / 2
    block_length: float = 0.0
    joined: bool = False

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"kind = {self.kind!r} must be one of {KINDS}")
        positive("L", self.L)
        positive("t", self.t)
        if not self.t <= 0.2 * self.L:
            raise ValueError(f"t = {self.t!r} m must be <= L / 5 = {0.2 * self.L!r} m (a leaf)")
        if not (isinstance(self.crossing_angle, numbers.Real)
                and math.pi / 6 <= self.crossing_angle <= 5 * math.pi / 6):
            raise ValueError(f"crossing_angle = {self.crossing_angle!r} rad must be in "
                             "[pi/6, 5 pi/6]")
        if not (isinstance(self.block_length, numbers.Real) and math.isfinite(self.block_length)
                and self.block_length >= 0):
            raise ValueError(f"block_length = {self.block_length!r} m must be >= 0")
        if self.joined and self.kind != "cross":
            raise ValueError("joined = True needs kind = 'cross'")

    @property
    def leaf_angles(self) -> tuple:
        """Angles (rad) of the leaves from the x-axis."""
        if self.kind == "single":
            return (0.0,)
        return (0.5 * self.crossing_angle, -0.5 * self.crossing_angle)

    def leaf_corners(self, k: int) -> np.ndarray:
        """(4, 2) corners of leaf k (m): root -t/2, root +t/2, tip +t/2, tip -t/2 sides."""
        b = self.leaf_angles[k]
        d, n = np.array([math.cos(b), math.sin(b)]), np.array([-math.sin(b), math.cos(b)])
        h, r = 0.5 * self.L, 0.5 * self.t
        return np.array([-h * d - r * n, -h * d + r * n, h * d + r * n, h * d - r * n])


def base_block_outline(g: PivotGeometry) -> np.ndarray:
    """(m, 2) counter-clockwise outline of the base block (m); its edges between the leaf
    roots are the leaves' root faces. Empty when block_length = 0."""
    if g.block_length == 0:
        return np.zeros((0, 2))
    if g.kind == "single":
        c = g.leaf_corners(0)
        x0, y = c[0, 0] - g.block_length, 0.25 * g.L
        return np.array([c[0], c[1], [c[1, 0], y], [x0, y], [x0, -y], [c[0, 0], -y]])
    c1, c2 = g.leaf_corners(0), g.leaf_corners(1)
    # right face: root of leaf 1 (rising), inner face, root of leaf 2 (falling)
    right = [c1[0], c1[1], c2[0], c2[1]]
    x0 = min(p[0] for p in right) - g.block_length
    return np.array(right + [[x0, c2[1][1]], [x0, c1[0][1]]])


def draw_pivot(gmsh, g: PivotGeometry) -> None:
    """Build the pivot in the open gmsh session (OpenCASCADE, bottom-up so that the leaves
    share their end curves with the blocks but not their sides with each other)."""
    occ = gmsh.model.occ
    points, lines = {}, {}

    def point(p):
        key = (round(float(p[0]) / g.t * 1e6), round(float(p[1]) / g.t * 1e6))
        if key not in points:
            points[key] = occ.addPoint(float(p[0]), float(p[1]), 0.0)
        return points[key]

    def polygon(pts):
        tags = [point(p) for p in pts]
        loop = []
        for a, b in zip(tags, tags[1:] + tags[:1]):
            if (b, a) in lines:
                loop.append(-lines[(b, a)])
            else:
                lines.setdefault((a, b), occ.addLine(a, b))
                loop.append(lines[(a, b)])
        return occ.addPlaneSurface([occ.addCurveLoop(loop)])

    leaves = [polygon(g.leaf_corners(k)) for k in range(len(g.leaf_angles))]
    blocks = []
    base = base_block_outline(g)
    if len(base):
        blocks = [polygon(base), polygon((base * [-1.0, 1.0])[::-1])]
    if g.joined:
        out, _ = occ.fragment([(2, leaves[0])], [(2, leaves[1])] + [(2, b) for b in blocks])
        occ.synchronize()
        ids = [t for _, t in out]
        leaves = [t for t in ids if _is_leaf(gmsh, g, t)]
        blocks = [t for t in ids if t not in leaves]
    occ.synchronize()
    gmsh.model.addPhysicalGroup(2, leaves, name="leaves")
    if g.kind == "cross" and not g.joined:
        for k, tag in enumerate(leaves, start=1):
            gmsh.model.addPhysicalGroup(2, [tag], name=f"leaf_{k}")
    if blocks:
        gmsh.model.addPhysicalGroup(2, blocks, name="blocks")
    for name, sign in (("fixed", -1.0), ("hub", 1.0)):
        curves = _end_curves(gmsh, g, sign)
        if not curves:
            raise RuntimeError(f"pivot geometry: no curve found for group {name!r}")
        gmsh.model.addPhysicalGroup(1, curves, name=name)


def _is_leaf(gmsh, g, tag) -> bool:
    x, y, _ = gmsh.model.occ.getCenterOfMass(2, tag)
    return abs(x) < 0.5 * g.L * math.cos(0.5 * g.crossing_angle) - 1e-9


def _end_curves(gmsh, g: PivotGeometry, sign: float) -> list:
    """Curves of the base (sign -1) or hub (sign +1) end: the blocks' outer faces, or the
    leaf end faces when there are no blocks."""
    eps = 1e-3 * g.t
    if g.block_length > 0:
        base = base_block_outline(g)
        x = sign * (-base[:, 0].min())
        ents = gmsh.model.getEntitiesInBoundingBox(x - eps, -g.L, -eps, x + eps, g.L, eps, 1)
        return [t for _, t in ents]
    found = []
    for k in range(len(g.leaf_angles)):
        c = g.leaf_corners(k)
        end = c[:2] if sign < 0 else c[2:]
        lo, hi = end.min(axis=0) - eps, end.max(axis=0) + eps
        ents = gmsh.model.getEntitiesInBoundingBox(lo[0], lo[1], -eps, hi[0], hi[1], eps, 1)
        found += [t for _, t in ents]
    return found


def mesh_pivot(g: PivotGeometry, elements_through_thickness: int = 2,
               block_size_factor: float = 4.0) -> FEMesh:
    """Triangle mesh of the pivot: element size t / elements_through_thickness in the leaves,
    block_size_factor times that at the blocks' far corners. Groups: see :func:`draw_pivot`."""
    if not (isinstance(elements_through_thickness, (int, np.integer))
            and elements_through_thickness >= 1):
        raise ValueError(f"elements_through_thickness = {elements_through_thickness!r} must be "
                         "an integer >= 1")
    positive("block_size_factor", block_size_factor)
    fine = g.t / elements_through_thickness
    with gmsh_session("flexure_pivot") as gmsh:
        draw_pivot(gmsh, g)
        gmsh.model.mesh.setSize(gmsh.model.getEntities(0), fine)
        if g.block_length > 0:
            base = base_block_outline(g)
            far = np.abs(base[:, 0]).max()
            coarse = max(fine, min(block_size_factor * fine, g.block_length))
            for _, tag in gmsh.model.getEntities(0):
                x, _, _ = gmsh.model.getValue(0, tag, [])
                if abs(abs(x) - far) < 1e-6 * g.L:
                    gmsh.model.mesh.setSize([(0, tag)], coarse)
        for key in ("Mesh.MeshSizeExtendFromBoundary", "Mesh.MeshSizeFromCurvature"):
            gmsh.option.setNumber(key, 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 1)
        gmsh.option.setNumber("Mesh.Algorithm", 6)
        gmsh.model.mesh.generate(2)
        return mesh_from_gmsh(gmsh)
