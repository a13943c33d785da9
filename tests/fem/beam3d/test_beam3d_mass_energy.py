"""Mass properties (inertia.py) and strain energy (energy.py) of spatial beam models against
closed forms: a prismatic bar's rigid-body inertia, a cantilever's work of its tip load."""
import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from beam3d_models import straight
from flexfem.fem.beam.spatial import NodalLoad, Section, solve_beam3d_static
from flexfem.fem.beam.supports import NodeFixed
from flexfem.fem.beam.spatial.energy import element_energies, strain_energy_share
from flexfem.fem.beam.spatial.inertia import mass_properties


def test_a_bar_s_mass_centroid_and_inertia_tensor(steel):
    """A 0.1 m bar of 2 x 5 mm along (1, 2, 2)/3, 10 elements, and a point mass on its tip:
    m = rho A L + m_p; centroid on the axis; about the bar's centroid J = rho A L^3 / 12
    (I - e e^T) plus the section's rho L (I_p, I_y, I_z) about its local x, y, z (exact: the
    consistent mass reproduces rigid-body motion); the point mass by parallel axes."""
    d = np.array([1.0, 2.0, 2.0]) / 3.0
    section = Section.rect(5e-3, 2e-3)
    L, mp = 0.1, 0.02
    model, tip = straight(steel, section, length=L, n=10, direction=d,
                          point_masses={10: (mp, 1e-6, 2e-6, 3e-6)})
    m_bar = steel.rho * section.A * L
    m, c, J = mass_properties(model)
    assert m == pytest.approx(m_bar + mp, rel=1e-12)
    assert c == pytest.approx((m_bar * L / 2 + mp * L) / m * d, rel=1e-12)
    frame = model.frames[0]  # columns: local x, y, z
    local = np.diag([section.Ip, section.Iy, section.Iz]) * steel.rho * L
    J_bar = m_bar * L**2 / 12 * (np.eye(3) - np.outer(d, d)) + frame @ local @ frame.T
    arm = lambda r: r @ r * np.eye(3) - np.outer(r, r)
    J_ref = (J_bar + m_bar * arm(L / 2 * d - c) + np.diag([1e-6, 2e-6, 3e-6])
             + mp * arm(L * d - c))
    assert J == pytest.approx(J_ref, rel=1e-10, abs=1e-12 * np.abs(J_ref).max())
    m_el, c_el, _ = mass_properties(model, range(5))  # the first half: no point mass
    assert m_el == pytest.approx(m_bar / 2, rel=1e-12)
    assert c_el == pytest.approx(L / 4 * d, rel=1e-12)


def test_element_energies_add_up_to_the_work_of_the_tip_load(steel):
    """Cantilever 0.1 m, 2 x 5 mm, with shear, under a tip force (F_y, F_z) and torque M_x:
    the elements' strain energies sum to half the loads' work, F . u_tip / 2 (to round-off),
    and the root half stores 7/8 of the bending energy, (L^3 - (L/2)^3) / L^3 of M^2 / 2EI
    with M linear, plus half the torsion and shear energy."""
    section = Section.rect(5e-3, 2e-3)
    model, tip = straight(steel, section, length=0.1, n=20, shear=True)
    load = NodalLoad(tip, fy=0.3, fz=-0.2, mx=0.01)
    state = solve_beam3d_static(model, [NodeFixed(0)], [load])
    rot = Rotation.from_matrix(state.R).as_rotvec()
    shape = np.hstack([state.u, rot])[None]
    e = element_energies(model, shape)[0]
    work = 0.5 * load.vector(6) @ shape[0, tip]
    assert e.sum() == pytest.approx(work, rel=1e-10)
    E, G, L = steel.E, steel.E / (2 * (1 + steel.nu)), 0.1
    bend = sum(F**2 * L**3 / (6 * E * I) for F, I in ((0.3, section.Iz), (0.2, section.Iy)))
    other = 0.01**2 * L / (2 * G * section.J) + (0.3**2 + 0.2**2) * L / (2 * G * section.Ay)
    assert bend + other == pytest.approx(work, rel=1e-10)
    root = strain_energy_share(model, shape, range(10))[0]
    assert root == pytest.approx((7 / 8 * bend + other / 2) / work, rel=1e-9)
    with pytest.raises(ValueError, match="DOFs"):
        element_energies(model, np.zeros((1, 5)))
