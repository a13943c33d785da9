"""A planar beam model lifted into 3-D (flexfem.geometry.spatial_beam): a leaf's roots keep
their planar compliance in the plane, and about the strong axis each slice of the leaf's
width enters its block as the planar root does (its axial compliance)."""
import numpy as np
import pytest
from flexfem.fem.beam import BeamModel
from flexfem.fem.beam3d import Fixed, compliance3d
from flexfem.fem.materials import Material
from flexfem.geometry.beam_layout import ROOT_EXTENSION, axial_root_compliance, profile_beam
from flexfem.geometry.spatial_beam import lifted_model

E, L, T, W, H = 200e9, 5e-3, 0.5e-3, 8e-3, 6e-3  # leaf length, thickness, width; block height


def test_a_leafs_roots_keep_the_axial_compliance_about_the_strong_axis():
    """A cantilevered leaf with its two root extensions (blocks H tall at both ends): the tip's
    rotation compliance is L + 2 e over E I in the plane (e = 0.38 t, the root's bending)
    and L + 2 alpha t over E I_y about the strong axis (alpha the planar root's axial
    compliance: each slice of the width pulled as the planar root), the extension's too."""
    mesh = profile_beam((0.0, 0.0), (L, 0.0), lambda s: np.full_like(s, T), W, (), 8,
                        blocks=(H, H), vectorized=True)
    planar = BeamModel(mesh.nodes, mesh.elements, mesh.sections,
                       Material("steel", E, 0.3, 7800.0), shear=True)
    model = lifted_model(planar, W)
    first, last = mesh.point_nodes
    C = compliance3d(model, [Fixed(first)], last)
    alpha = axial_root_compliance(H, T)
    Iz, Iy = W * T ** 3 / 12, T * W ** 3 / 12
    assert C[5, 5] == pytest.approx((L + 2 * ROOT_EXTENSION * T) / (E * Iz), rel=1e-10)
    assert C[4, 4] == pytest.approx((L + 2 * alpha * T) / (E * Iy), rel=1e-10)
    assert C[0, 0] == pytest.approx((L + 2 * alpha * T) / (E * W * T), rel=1e-10)
