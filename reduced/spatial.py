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
    """One spatial Section per planar element: a rectangular one keeps its taper (depth t
    along local y, ``out_of_plane`` along z); a general one (a root extension: A, I) keeps
    A and I_z = I, with t = (12 I / w)^(1/3) for I_y = t w^3 / 12 and the Saint-Venant J.
    Shear areas kappa A (the planar model's, mid-length) in y and kappa w t in z if the
    planar model has shear. The planar stiffness factors (a notch's 2-D correction, a root's
    axial compliance) act on the in-plane bending, shear and axial stiffness, and the axial
    one on the bending about the local y axis too: there each slice of the width is pulled
    or pushed along the axis, and a slice enters its block as the planar section does
    (docs/beam_validation_3d.md, "The strong axis's roots"); the mass factors (0 on a root extension) on
    the mass."""
    shear, w = planar_model.shear, out_of_plane
    out = []
    for (rect, _, t0, t1, A, I, _, kappa, tm, bending, axial,
         mass) in planar_model.section_table:
        if rect:  # Section.rect's shear area is 5/6 of the rectangle's
            sec = Section.rect(w, t0, shear=shear, thickness_end=t1,
                               thickness_mid=None if np.isnan(tm) else tm)
            out.append(replace(sec, factors=(bending, kappa / (5.0 / 6.0), axial, axial),
                               mass_factor=mass))
            continue
        t = (12.0 * I / w) ** (1.0 / 3.0)
        out.append(Section(A=A, Iy=t * w**3 / 12.0, Iz=I, J=rect_torsion_constant(t, w),
                           Ay=kappa * A if shear else None,
                           Az=kappa * t * w if shear else None,
                           factors=(bending, 1.0, axial, axial), mass_factor=mass))
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
                       groups=groups)
