"""The spatial beam beside flexfem's 3-D continuum model of a leaf flexure of the eight-
bar's proportions (20 x 0.3 x 6 mm, aluminium): where beam theory holds and where the
clamped ends' warping restraint (Vlasov), which Saint-Venant torsion leaves out, stiffens
the leaf."""
import numpy as np
import pytest
import skfem

from flexfem.fem import Fixed as ContinuumFixed
from flexfem.fem import Material, Model, Solid3D
from flexfem.fem.beam.spatial import Beam3DModel, Section, compliance3d
from flexfem.fem.beam.supports import NodeFixed
from flexfem.fem.compliance import compliance_matrix
from flexfem.fem.mesh import FEMesh, facets_where

ALU = Material("aluminium", E=68.9e9, nu=0.33, rho=2700.0)
L, T, W = 0.02, 0.3e-3, 6e-3


@pytest.mark.slow
def test_leaf_compliance_beside_the_3d_continuum():
    """Tip compliance, root clamped, tip face rigid (40 x 2 x 12 Q2 hexahedra; 40 x 4 x 16
    changes it by < 0.2 %). Axial and out-of-plane bending (shear included): within 1.5 %
    (the clamp's Poisson restraint, O(t/L)). In-plane bending of this 20:1 wide leaf: the
    restrained anticlastic curvature stiffens it by between 1 and 1/(1 - nu^2) (measured
    +3.6 %). Torsion: the beam is more compliant by Vlasov's factor for warping restrained
    at both ends, 1 / (1 - 2 tanh(lambda L/2) / (lambda L)) - 1 = 16.8 % (lambda^2 = GJ /
    E Gamma, Gamma = w^3 t^3 / 144), within 2 % (measured 17.8 %)."""
    m = skfem.MeshHex.init_tensor(np.linspace(0, L, 41), np.linspace(-T / 2, T / 2, 3),
                                  np.linspace(-W / 2, W / 2, 13))
    mesh = FEMesh(m, {"fixed": facets_where(m, lambda x: np.isclose(x[0], 0.0)),
                      "tip": facets_where(m, lambda x: np.isclose(x[0], L))})
    cont = compliance_matrix(Model(mesh, ALU, Solid3D(), order=2), [ContinuumFixed("fixed")],
                             "tip").matrix
    nodes = np.linspace(0.0, L, 21)[:, None] * [1.0, 0.0, 0.0]
    section = Section.rect(W, T)
    beam = Beam3DModel(nodes, [(i, i + 1) for i in range(20)], section, ALU, shear=True)
    ratio = np.diag(compliance3d(beam, [NodeFixed(0)], 20)) / np.diag(cont) - 1
    assert np.abs(ratio[[0, 2, 4]]).max() <= 0.015
    assert 0 < ratio[1] < 1 / (1 - ALU.nu**2) - 1
    G = ALU.E / (2 * (1 + ALU.nu))
    lam = np.sqrt(G * section.J / (ALU.E * W**3 * T**3 / 144))
    vlasov = 1 / (1 - 2 * np.tanh(lam * L / 2) / (lam * L)) - 1
    assert ratio[3] == pytest.approx(vlasov, abs=0.02)
