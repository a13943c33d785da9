"""Spatial (6-DOF) beam model of the eight-bar flexure suspension, for out-of-plane modes.

    model, info = eightbar_beam3d_model(EightBarFlexureParams())

Built from the planar beam model of the same parameters
(:func:`flexfem.geometry.eightbar.beam.eightbar_beam_model`): the same nodes (in the plane
z = 0), elements, rigid links, clamps and link masses, with the out-of-plane properties
added: every section becomes the t x w rectangle of its in-plane depth t (tapered as the
planar element's through the root fillets) and the out-of-plane width w = ``thickness``,
with I_y = t w^3 / 12 and the Saint-Venant J. Links: the planar model's mass and polar
inertia J_z, and J_x, J_y of the link's plate (union of its bars and hubs, thickness w)
about its centroid.
"""
import numpy as np

from ...fem.beam3d import Beam3DModel, RigidLink, Section, rect_torsion_constant
from ..beam_layout import ROOT_EXTENSION, link_moments
from .beam import eightbar_beam_model
from .flexure import EightBarFlexureParams, eightbar_layout


def link_plate_inertia(parts, link: str, out_of_plane: float, rho: float) -> tuple:
    """(mass kg, centroid (2,) m, J_x, J_y kg m^2) of ``link``'s plate (the union of its
    rectangles, :func:`..beam_layout.link_moments`) about in-plane axes through its
    centroid."""
    A, Sx, Sy, Ixx, Iyy = link_moments(parts, link)
    c = np.array([Sx / A, Sy / A])
    m = rho * out_of_plane * A
    thick = m * out_of_plane**2 / 12.0
    jx = rho * out_of_plane * (Iyy - A * c[1] ** 2) + thick  # about x: y^2 and z^2
    jy = rho * out_of_plane * (Ixx - A * c[0] ** 2) + thick
    return float(m), c, float(jx), float(jy)


def spatial_sections(planar_model, out_of_plane: float) -> list:
    """One spatial Section per planar element: a rectangular one keeps its taper (depth t
    along local y, ``out_of_plane`` along z); a general one (a root extension: A, I) keeps
    A and I_z = I, with t = (12 I / w)^(1/3) for I_y = t w^3 / 12 and the Saint-Venant J.
    Shear areas kappa A (the planar model's, mid-length) in y and kappa w t in z if the
    planar model has shear."""
    shear, w = planar_model.shear, out_of_plane
    out = []
    for (rect, _, t0, t1, A, I, _, kappa, tm) in planar_model.section_table:
        if rect:
            out.append(Section.rect(t0, w, shear=shear, depth_y_end=t1,
                                    depth_y_mid=None if np.isnan(tm) else tm))
            continue
        t = (12.0 * I / w) ** (1.0 / 3.0)
        out.append(Section(A=A, Iy=t * w**3 / 12.0, Iz=I, J=rect_torsion_constant(t, w),
                           Ay=kappa * A if shear else None,
                           Az=kappa * t * w if shear else None))
    return out


def eightbar_beam3d_model(params: EightBarFlexureParams, n_per_flexure: int = 24,
                          root_extension: float = ROOT_EXTENSION, shear: bool = True) -> tuple:
    """(Beam3DModel, info) of the suspension in its drawn pose; info as the planar model's
    (eightbar_beam_model): "end_effector", "ground", "masters", "flexures"."""
    planar, info = eightbar_beam_model(params, n_per_flexure, root_extension, shear)
    w = params.thickness
    layout = eightbar_layout(params)
    rho = planar.material.rho
    masses = {}
    for link in layout.links:
        m, c, jx, jy = link_plate_inertia(layout.parts, link, w, rho)
        at = [k for k in planar.point_masses if np.allclose(planar.nodes[k], c, atol=1e-12)]
        if len(at) != 1:
            raise ValueError(f"link {link!r}: no single mass node at its centroid {c}")
        m_planar, jz = planar.point_masses[at[0]]
        masses[at[0]] = (m_planar, jx, jy, jz)
    nodes = np.column_stack([planar.nodes, np.zeros(planar.n_nodes)])
    links = [RigidLink(k.master, k.slaves) for k in planar.rigid_links]
    model = Beam3DModel(nodes, planar.elements, spatial_sections(planar, w), planar.material,
                        rigid_links=links, point_masses=masses)
    return model, info
