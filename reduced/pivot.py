"""Reduced beam model of a flexure pivot (:class:`flexfem.geometry.flexure_pivot.PivotGeometry`):
a single leaf or a cross-spring pivot whose leaves cross without touching.

    model, info = pivot_beam_model(PivotGeometry("cross", 0.05, 0.5e-3), width=0.01, material=m)
    info["hub"], info["base"]      # the hub's master node, the clamped leaf roots
    model.groups                   # "fixed" (the leaf roots) and "hub": the 2-D model's groups

Each leaf is a straight beam from its base root to its hub end (width ``width`` out of the
plane, thickness t in it); the leaves of a cross-spring pivot share no node (interleaved, as in
the real part and the 2-D model), or one at the crossing with ``joined``. The hub is a rigid
body (master node on the centroid of the leaves' hub ends: where the 2-D model's RigidFace
acts). Root extension: the 2-D pivot model with ``block_length = 0`` clamps the leaf end faces
themselves (rigid blocks), where beam theory is exact, so the default extension is 0 there;
with elastic blocks (``block_length > 0``) the common ROOT_EXTENSION (0.38 x t per root,
:mod:`flexfem.reduced.layout`) applies. Lengths in m.
"""
import math

import numpy as np

from ..fem.beam import BeamModel, RigidLink, Section, beam_chain
from .layout import ROOT_EXTENSION, check_root_extension
from ..geometry.flexure_pivot import PivotGeometry


def pivot_beam_model(g: PivotGeometry, width: float, material, n_per_leaf: int = 20,
                     root_extension: float | None = None, shear: bool = False) -> tuple:
    """(BeamModel, info) of pivot ``g``; info: "hub" (master node), "base" (clamped nodes),
    "leaves" [(first, last element)]; the model's groups "fixed" (the base roots) and "hub" (its
    master), the 2-D model's names. root_extension: x t per root (None: 0 with rigid blocks,
    ROOT_EXTENSION with elastic ones)."""
    if root_extension is None:
        root_extension = 0.0 if g.block_length == 0 else ROOT_EXTENSION
    ext = check_root_extension(root_extension) * g.t
    section = Section.rect(width, g.t)
    nodes, elements, sections, base, tips, spans = [], [], [], [], [], []
    n0 = 0
    for angle in g.leaf_angles:
        d = np.array([math.cos(angle), math.sin(angle)])
        h = 0.5 * g.L + ext
        mid = [np.zeros(2)] if g.joined else []
        pts = [-h * d] + mid + [h * d]
        count = n_per_leaf if not mid else [n_per_leaf // 2] * 2
        chain = beam_chain(pts, section, count)
        spans.append((len(sections), len(sections) + len(chain.sections)))
        nodes.append(chain.nodes)
        elements.append(chain.elements + n0)
        sections += list(chain.sections)
        base.append(n0 + chain.point_nodes[0])
        tips.append(n0 + chain.point_nodes[-1])
        n0 += len(chain.nodes)
    all_nodes = np.vstack(nodes)
    elements = np.vstack(elements)
    if g.joined:  # merge the crossing nodes of the two leaves
        a, b = [int(np.argmin(np.linalg.norm(n, axis=1))) for n in nodes]
        b += len(nodes[0])
        elements[elements == b] = a
    links = []
    if len(tips) == 1:
        hub = tips[0]
    else:
        hub = len(all_nodes)
        all_nodes = np.vstack([all_nodes, all_nodes[tips].mean(axis=0)[None, :]])
        links = [RigidLink(hub, tuple(tips))]
    model = BeamModel(all_nodes, elements, sections, material, shear=shear, rigid_links=links,
                      groups={"fixed": base, "hub": [hub]})
    return model, {"hub": hub, "base": base, "leaves": spans}
