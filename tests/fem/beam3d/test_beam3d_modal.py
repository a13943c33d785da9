"""Cantilever natural frequencies of the spatial beam: bending in both planes (Euler-
Bernoulli, beta_n L), axial and torsional (quarter-wave rods)."""
import numpy as np
import pytest

from beam3d_models import straight
from flexfem.fem.beam.spatial import Beam3DModel, RigidLink, Section, solve_beam3d_modes
from flexfem.fem.beam.supports import NodeFixed

BETA_L = np.array([1.8751041, 4.6940911, 7.8547574])


def _kind(modes):
    """Which motion dominates each mode: 'y', 'z' (bending), 'x' (axial) or 'rx'."""
    s = modes.shapes
    parts = {"x": s[:, :, 0], "y": s[:, :, 1], "z": s[:, :, 2], "rx": s[:, :, 3]}
    scale = {"x": 1.0, "y": 1.0, "z": 1.0, "rx": 1e-3}  # rotation of a mm-size section
    norms = {k: np.linalg.norm(v, axis=1) * scale[k] for k, v in parts.items()}
    return [max(norms, key=lambda k: norms[k][i]) for i in range(len(modes.frequencies_hz))]


def test_cantilever_frequencies_in_all_four_families(steel):
    """L = 0.2 m, 1 x 2 mm section (L/t >= 100), 40 elements. Rotary inertia (in the
    model, not in Euler-Bernoulli) lowers bending mode n by ~ (beta_n h)^2 / 24: at most
    2.6e-4 (mode 3 about y), hence the 5e-4 tolerance. Bending: beta_n^2 sqrt(EI / (rho A
    L^4)) / 2 pi about each axis; axial: (2k - 1) / 4L sqrt(E / rho); torsion: (2k - 1) / 4L
    sqrt(G J / (rho Ip)); linear bar elements: +6e-5, +6e-4 on these, 1e-3 allowed."""
    L, b, h = 0.2, 1e-3, 2e-3
    section = Section.rect(h, b)
    model, _ = straight(steel, section, length=L, n=40)
    modes = solve_beam3d_modes(model, [NodeFixed(0)], n=40)
    kinds = np.array(_kind(modes))
    f = modes.frequencies_hz
    E, rho = steel.E, steel.rho
    G = E / (2 * (1 + steel.nu))
    bend = lambda I: BETA_L**2 / (2 * np.pi * L**2) * np.sqrt(E * I / (rho * section.A))
    assert f[kinds == "y"][:3] == pytest.approx(bend(section.Iz), rel=5e-4)
    assert f[kinds == "z"][:3] == pytest.approx(bend(section.Iy), rel=5e-4)
    k = np.array([1, 2])
    axial = (2 * k - 1) / (4 * L) * np.sqrt(E / rho)
    torsion = (2 * k - 1) / (4 * L) * np.sqrt(G * section.J / (rho * section.Ip))
    assert f[kinds == "x"][:2] == pytest.approx(axial, rel=1e-3)
    assert f[kinds == "rx"][:2] == pytest.approx(torsion, rel=1e-3)
    assert modes.total_mass == pytest.approx(steel.rho * section.A * L, rel=1e-12)
    # the first bending mode in y carries 61.3 % of the mass in y, none in z
    first_y = np.flatnonzero(kinds == "y")[0]
    assert modes.effective_mass_fraction[first_y] == pytest.approx([0, 0.6131, 0], abs=1e-3)


def test_point_mass_on_a_rigid_arm_matches_the_closed_form(steel):
    """A light cantilever with a point mass m on a rigid arm: bending-torsion coupled
    lowest mode ~ sqrt(k / m), k the arm end's stiffness 1 / (L^3/3EIy + d^2 L / GJ)
    (the beam's own mass 0.3 % of m)."""
    section = Section.rect(2e-3, 2e-3)
    L, d, m = 0.1, 0.03, 1.0
    nodes = np.vstack([np.linspace(0.0, L, 11)[:, None] * [1.0, 0.0, 0.0], [[L, d, 0.0]]])
    elements = np.column_stack([np.arange(10), np.arange(1, 11)])
    model = Beam3DModel(nodes, elements, section, steel, rigid_links=[RigidLink(10, 11)],
                        point_masses={11: (m, 0.0, 0.0, 0.0)})
    modes = solve_beam3d_modes(model, [NodeFixed(0)], n=3)
    G = steel.E / (2 * (1 + steel.nu))
    k = 1.0 / (L**3 / (3 * steel.E * section.Iy) + d**2 * L / (G * section.J))
    f_z = np.sqrt(k / m) / (2 * np.pi)
    f_z_modes = modes.frequencies_hz[modes.effective_mass_fraction[:, 2] > 0.5]
    # beam mass 3.1 g against 1 kg: it lowers f by ~ 0.24 * 3.1e-3 / 2 (Rayleigh)
    assert f_z_modes[0] == pytest.approx(f_z, rel=1e-3)
