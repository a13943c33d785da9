"""The DBMA's input member where its pad bears on it, as a 2-D patch condensed onto beam nodes.

    sup = member_superelement(p, layout, sx, nodes)   # a flexfem.fem.beam.Superelement

An input member is as deep (a) as its span from the pad to the first hinge row, and its pad
bears on part of its inner face: a 2-D elasticity problem, which no beam rule reproduces
(docs/beam_validation_dbma.md, "DBMA: the input member's patch"). So the member over |y| <= y_cut and its pad
are a plane-stress patch (:mod:`flexfem.reduced.patch2d`), joined to the member's beams at the two
cuts by beam sections and to the actuator's end cap at the pad's face (held along x over the
face, as the continuum holds it), and condensed onto those three nodes. The cuts lie half a
member depth beyond the pad's edges (or halfway to the inner arms' centre lines, where that
is nearer): there the member is a beam again, and a cut adds no stiffness of its own (the
outputs move by less than 1e-3 for cuts from 0.3 a beyond the edges to near the first
hinges). The condensed matrices are computed once per member shape in a process (~1.5 ms) and
scale with E, d and rho: a sweep of the hinges or the arms' length reuses them.
"""
import functools

import numpy as np

from ..fem.beam import Superelement
from .patch2d import TensorPatch, cell_edges, held_face, section
from ..geometry.dbma.drawing import DBMALayout
from ..geometry.dbma.params import DBMAParams

# Q2 cells across the member's depth (and as tall), halved GRADING times towards the pad's
# re-entrant corners (x = 0, y = +-pad_height / 2), where the stress is singular: ~700 DOFs,
# the DBMA's outputs within 2.5e-3 of the converged patch, 8 uniform cells' within 3.4e-3
# (tests/studies/dbma/test_dbma_beam_model.py)
MEMBER_CELLS, GRADING = 3, 2
MIRROR = np.tile([-1.0, 1.0, -1.0], 3)  # x -> -x: u and theta change sign, v does not


def member_cut(p: DBMAParams, layout: DBMALayout) -> float:
    """|y| (m) of the cuts where the member's beams begin: half a member depth beyond the
    pad's edges, or halfway to the inner arms' centre lines where that is nearer (the first
    hinge lies h / 2 beyond them: a sweep of the hinges keeps the cut, and the patch)."""
    edge = layout.pad_height / 2
    return edge + min(p.a / 2, (layout.arm_gap + p.c / 2 - edge) / 2)


def member_superelement(p: DBMAParams, layout: DBMALayout, sx: int, nodes) -> Superelement:
    """The patch of the right (``sx`` = 1) or left (-1) input member on ``nodes`` = (the
    lower cut's, the upper cut's, the pad face's) beam nodes, at (x_c, -+member_cut) on the
    member's centre line and on the pad's face at y = 0."""
    K, M = _unit_patch(p.a, member_cut(p, layout), layout.pad_height, layout.pad_depth,
                       p.nu, MEMBER_CELLS, GRADING)
    if sx < 0:
        K, M = (MIRROR[:, None] * X * MIRROR[None, :] for X in (K, M))
    return Superelement(tuple(nodes), K * p.E * p.d, M * p.rho * p.d)


@functools.lru_cache(maxsize=256)
def _unit_patch(a: float, y_cut: float, pad_height: float, pad_depth: float, nu: float,
                cells: int, grading: int) -> tuple:
    """(K, M) of the right member's patch per unit E, width and density: the member's inner
    face at x = 0, its pad in -pad_depth <= x <= 0, |y| <= pad_height / 2."""
    h = pad_height / 2
    xs = cell_edges([-pad_depth, 0.0, a], a / cells, (0.0,), grading)
    ys = cell_edges([-y_cut, -h, h, y_cut], a / cells, (-h, h), grading)
    patch = TensorPatch(xs, ys, nu, keep=lambda x, y: (x > 0) | (np.abs(y) < h))
    joints = [section((0.0, -y_cut), (a, -y_cut)), section((0.0, y_cut), (a, y_cut)),
              held_face((-pad_depth, -h), (-pad_depth, h))]
    K, M = patch.condensed(joints)
    for X in (K, M):
        X.setflags(write=False)
    return K, M
