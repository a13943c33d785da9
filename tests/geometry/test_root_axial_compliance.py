"""A root's axial compliance (flexfem.reduced.layout.axial_root_compliance) against the
quantity it models: a sharp-cornered leaf pulled between two blocks, in flexfem's 2-D
plane-stress continuum on a converged mesh (the fit's own specimen: nu = 0.3, l/t = 10,
blocks 2 H long; docs/beam_validation.md, "Root extension and the roots' axial
compliance")."""
import numpy as np
import pytest

from flexfem.fem import Fixed as ContinuumFixed
from flexfem.fem import Force, Material, Model, PlaneStress, solve_static
from flexfem.fem.beam import BeamModel, Section, beam_chain
from flexfem.fem.beam.supports import NodeFixed
from flexfem.fem.beam.compliance import compliance
from flexfem.reduced.layout import profile_beam
from flexfem.geometry.hinge_profiles import mesh_hinge_specimen

E, NU, W = 200e9, 0.3, 5e-3
STEEL = Material("steel", E, NU, 7800.0)
T = 1e-3          # the leaf's thickness (m)
LEAF = 10 * T     # its length


def _continuum_extension(H, hinge_elements, size_factor=0.5):
    """Extension (m/N) of the leaf between two blocks H tall and 2 H long, plane stress: the
    near block's end clamped, a unit pull spread over the far block's end, its mean
    displacement; P2 triangles T / (hinge_elements / size_factor) in the leaf."""
    mesh = mesh_hinge_specimen(LEAF, T, "leaf", block_height=H, block_length=2 * H,
                               hinge_elements=hinge_elements, size_factor=size_factor)
    model = Model(mesh, STEEL, PlaneStress(W), order=2)
    res = solve_static(model, [ContinuumFixed("fixed")], [Force("tip", (1.0, 0.0))])
    return float(res.mean_displacement("tip")[0])


def _beam_extension(H):
    """The same as the beam model builds it (the fit's specimen): the leaf with its root
    extensions into blocks H tall (their elements carry axial_root_compliance), the blocks
    as Timoshenko beams from the extensions' ends."""
    leaf = profile_beam((0.0, 0.0), (LEAF, 0.0), lambda s: np.full_like(s, T), W, (), 8,
                        blocks=(H, H), vectorized=True)
    a, z = (tuple(leaf.nodes[n]) for n in leaf.point_nodes)
    near = beam_chain([(-2 * H, 0.0), a], Section.rect(W, H), 4)
    far = beam_chain([z, (LEAF + 2 * H, 0.0)], Section.rect(W, H), 4)
    mesh = near.join(leaf, tol=1e-12).join(far, tol=1e-12)
    model = BeamModel(mesh.nodes, mesh.elements, mesh.sections, STEEL, shear=True)
    C = compliance(model, [NodeFixed(mesh.node_at((-2 * H, 0.0)))],
                   mesh.node_at((LEAF + 2 * H, 0.0)))
    return float(C[0, 0])


@pytest.mark.parametrize("height", [1.5, 5.0, 20.0, 40.0])
def test_a_leaf_pulled_between_blocks_has_the_continuums_extension(height):
    """Independent truth: the 2-D plane-stress continuum (P2, 16 triangles across the leaf;
    32 across changes it by < 0.05 %). With the roots' axial compliance the beam's extension
    is within 1 % of it, the accuracy the docs give (docs/beam_validation.md: "the leaf's
    extension within 1 %"; measured +0.3, -0.5, -0.4, -0.2 % at H/t = 1.5, 5, 20, 40), where
    the bare beam (no root extension) is 1.4, 9.7, 19 and 23 % stiff: the check tells a
    wrong root compliance (0.1 / (E w) a root is 1.2-1.4 % of these extensions)."""
    H = height * T
    continuum = _continuum_extension(H, 8)
    assert _beam_extension(H) == pytest.approx(continuum, rel=0.01)


@pytest.mark.xfail(strict=True, reason=(
    "axial_root_compliance (reduced/layout.py, AXIAL_ROOT) meets its documented 0.03 "
    "/ (E w) a root only on the specimen's default mesh (4 triangles across the leaf: "
    "-0.017 at H/t = 20); on a converged mesh its residual is -0.038 (-0.040 extrapolated; "
    "-0.037 at H/t = 5): the fit needs redoing on a converged mesh"))
def test_the_root_axial_compliance_at_h_over_t_20_is_the_continuums():
    """Independent truth: the 2-D plane-stress continuum on a converged mesh (P2, 32
    triangles across the leaf: 8 and 16 across give residuals -0.031 and -0.036; the
    corner's singularity converges as h^1.1, so another 0.002 remains). The root's axial
    compliance the beam carries, axial_root_compliance(20 t, t) = 1.60 / (E w), is that of
    the continuum within 0.03 / (E w) a root, the accuracy its fit documents
    (docs/beam_validation.md, "Root extension and the roots' axial compliance"): the
    residual (beam - continuum) E w / 2 of the whole extension, both roots alike."""
    H = 20 * T
    residual = (_beam_extension(H) - _continuum_extension(H, 16)) * E * W / 2
    assert abs(residual) < 0.03
