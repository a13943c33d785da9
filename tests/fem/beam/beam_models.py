"""Beam models the beam-model tests share."""
import numpy as np

from flexfem.fem.beam import BeamModel, RigidLink, Section, beam_chain
from flexfem.fem.beam.supports import NodeFixed


def cantilever(material, length=0.1, width=0.01, thickness=1e-3, n=20, shear=False):
    """Straight cantilever along +x from the origin: (model, tip node)."""
    mesh = beam_chain([(0.0, 0.0), (length, 0.0)], Section.rect(width, thickness), n)
    return BeamModel(mesh.nodes, mesh.elements, mesh.sections, material, shear=shear), n


def parallel_guide(material, length=0.05, width=0.01, thickness=0.5e-3, gap=0.03, n=50):
    """Two leaves along +x at y = 0 and y = gap, clamped at x = 0; a rigid stage joins the
    free ends, its master node at (length, gap / 2). Returns (model, supports, stage node)."""
    a = beam_chain([(0.0, 0.0), (length, 0.0)], Section.rect(width, thickness), n)
    b = beam_chain([(0.0, gap), (length, gap)], Section.rect(width, thickness), n)
    g = a.join(b)
    nodes = np.vstack([g.nodes, [(length, gap / 2)]])
    stage = len(nodes) - 1
    links = [RigidLink(stage, (g.point_nodes[1], g.point_nodes[3]))]
    model = BeamModel(nodes, g.elements, g.sections, material, rigid_links=links)
    return model, [NodeFixed((g.point_nodes[0], g.point_nodes[2]))], stage
