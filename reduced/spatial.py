"""A planar beam model lifted into 3-D: the same nodes (in the plane z = 0), elements, rigid
links and sections, with the out-of-plane properties of a part of uniform thickness (the
drawing extruded by ``out_of_plane``).

    model = lifted_model(planar, out_of_plane=p.d)    # a Beam3DModel
"""
from dataclasses import replace

import numpy as np

from ..fem.beam.groups import BeamGroup
from ..fem.beam.spatial import Beam3DModel, RigidLink, Section, rect_torsion_constant


def spatial_sections(planar_model, out_of_plane: float) -> list:
    """One spatial Section per planar element: a rectangle of depth ``out_of_plane`` keeps
    its taper (another depth: the rectangle rebuilt at that depth); a general one (a root
    extension: A, Iz) keeps A and Iz, with t = (12 Iz / w)^(1/3) for Iy = t w^3 / 12, the
    Saint-Venant J and Az = (Ay / A) t w. The planar stiffness factors (a notch's 2-D
    correction, a root's axial compliance) act on the in-plane bending, shear and axial
    stiffness, and the axial one on the bending about the local y axis too: there each
    slice of the width is pulled or pushed along the axis, and a slice enters its block as
    the planar section does (docs/beam_validation_3d.md, "The strong axis's roots"); the
    mass factors (0 on a root extension) on the mass."""
    w = out_of_plane
    out = []
    for sec in planar_model.sections:
        f = sec.factors
        factors = (f[0], f[1], f[2], f[2])
        if sec.depth_z is not None and sec.Iy is not None and sec.J is not None:
            rect = sec
            if sec.depth_z != w:
                t0, t1, tm, _ = sec.taper or (sec.depth_y, sec.depth_y, np.nan, w)
                rect = Section.rect(w, t0, t1 if sec.taper else None,
                                    None if np.isnan(tm) else tm)
            out.append(replace(rect, factors=factors, mass_factor=sec.mass_factor))
            continue
        t = (12.0 * sec.Iz / w) ** (1.0 / 3.0)
        Az = None if sec.Ay is None else sec.Ay / sec.A * t * w
        out.append(replace(sec, Iy=t * w**3 / 12.0, J=rect_torsion_constant(t, w), Az=Az,
                           depth_y=None, depth_z=None, factors=factors))
    return out


def lifted_model(planar, out_of_plane: float, point_masses=None) -> Beam3DModel:
    """The spatial model of ``planar`` (a BeamModel) extruded by ``out_of_plane`` (m): its
    nodes at z = 0, its rigid links as spatial ones, :func:`spatial_sections`, and
    ``point_masses`` {node: (m, J_x, J_y, J_z)} (default none), and the planar model's groups
    (a group that stands for a face of some extent spans the depth too)."""
    if planar.superelements:
        raise ValueError("lifted_model: the planar model has superelements, which have no "
                         "out-of-plane part; lift a model without them")
    nodes = np.column_stack([planar.nodes, np.zeros(planar.n_nodes)])
    rigid = [RigidLink(k.master, k.slaves) for k in planar.rigid_links]
    groups = {name: BeamGroup(g.nodes, (*g.span, out_of_plane if any(g.span) else 0.0))
              for name, g in planar.groups.items()}
    return Beam3DModel(nodes, planar.elements, spatial_sections(planar, out_of_plane),
                       planar.material, rigid_links=rigid, point_masses=point_masses or {},
                       groups=groups, shear=planar.shear)
