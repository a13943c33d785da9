"""Cantilever natural frequencies: Euler-Bernoulli (beta_n L) for a slender beam, the
Timoshenko frequency equation (solved here numerically) for a thick one."""
import numpy as np
import pytest

from beam_theory import timoshenko_cantilever_hz
from beam_models import cantilever
from flexfem.fem.beam import (BeamModel, NodalLoad, RigidLink, Section, beam_chain,
                              solve_beam_modes, solve_beam_nonlinear)
from flexfem.fem.beam.supports import NodeFixed

BETA_L = np.array([1.8751041, 4.6940911, 7.8547574])


def bending_modes(modes):
    """Frequencies of the modes that move in y (bending), ascending."""
    return modes.frequencies_hz[modes.effective_mass_fraction[:, 1] > 1e-6]


def test_slender_cantilever_euler_bernoulli(steel):
    L, w, t = 0.1, 0.01, 1e-3          # L / t = 100: shear and rotary inertia ~1e-4
    model, _ = cantilever(steel, L, w, t, n=30)
    modes = solve_beam_modes(model, [NodeFixed(0)], n=3)
    A, I = w * t, w * t**3 / 12
    f_eb = BETA_L**2 / (2 * np.pi * L**2) * np.sqrt(steel.E * I / (steel.rho * A))
    # rotary inertia lowers f_n by ~ (beta_n t)^2 / 24 / L^2 relative: < 3e-4 here
    assert modes.frequencies_hz == pytest.approx(f_eb, rel=5e-4)
    assert modes.total_mass == pytest.approx(steel.rho * A * L, rel=1e-12)
    # mass-normalised shapes, the first mode's effective mass 61.3 % of the total
    assert modes.effective_mass_fraction[0, 1] == pytest.approx(0.6131, abs=1e-3)


@pytest.mark.parametrize("n", [20, 40])
def test_thick_cantilever_timoshenko(steel, n):
    L, w, h = 1.0, 0.1, 0.2            # L / h = 5
    model, _ = cantilever(steel, L, w, h, n=n, shear=True)
    modes = solve_beam_modes(model, [NodeFixed(0)], n=6)
    f_ref = np.array(timoshenko_cantilever_hz(steel.E, steel.nu, steel.rho, w * h,
                                              w * h**3 / 12, L, 3))
    tol = {20: 3e-3, 40: 1e-3}[n]  # measured: n = 20: 1.3e-5, 3.5e-4, 1.9e-3; n = 40: 3e-6, 9e-5, 4.8e-4
    assert bending_modes(modes)[:3] == pytest.approx(f_ref, rel=tol)
    # shear and rotary inertia matter here: Euler-Bernoulli is 2.4 % .. 19 % higher
    f_eb = BETA_L**2 / (2 * np.pi * L**2) * np.sqrt(steel.E * h**2 / 12 / steel.rho)
    assert np.all(f_eb / f_ref > 1.02)


def test_tip_mass_and_rigid_link(steel):
    """A rigid tip block of mass m on a massless-ish cantilever: f = sqrt(3EI/(L^3 m))/2pi
    (tip mass >> beam mass); the block held by a rigid link with its mass at its centre."""
    L, w, t, m = 0.1, 0.01, 1e-3, 5.0
    mesh = beam_chain([(0, 0), (L, 0)], Section.rect(w, t), 10)
    nodes = np.vstack([mesh.nodes, [(L, 0.0)]])    # the block's centre at the tip
    model = BeamModel(nodes, mesh.elements, mesh.sections, steel,
                      rigid_links=[RigidLink(11, (10,))], point_masses={11: (m, 0.0)})
    f = solve_beam_modes(model, [NodeFixed(0)], n=1).frequencies_hz[0]
    k = 3 * steel.E * w * t**3 / 12 / L**3
    m_eff = m + 33 / 140 * steel.rho * w * t * L       # Rayleigh's beam mass correction
    assert f == pytest.approx(np.sqrt(k / m_eff) / (2 * np.pi), rel=1e-3)


def test_tension_stiffening_simply_supported(steel):
    """Modes about a tensioned state (the co-rotational tangent): a simply supported beam
    under tension T has omega_n^2 = [(n pi / L)^4 EI + (n pi / L)^2 T] / (rho A)."""
    L, w, t, tension = 0.1, 0.01, 1e-3, 100.0          # T L^2 / EI = 6
    model, end = cantilever(steel, L, w, t, n=40)
    supports = [NodeFixed(0, ("x", "y")), NodeFixed(end, ("y",))]
    loads = [NodalLoad(end, fx=tension)]
    state = solve_beam_nonlinear(model, supports, loads, steps=1).final
    modes = solve_beam_modes(model, supports, n=3, about=state, loads=loads)
    f = modes.frequencies_hz      # the axial mode is at ~12.6 kHz
    A, I = w * t, w * t**3 / 12
    k = np.arange(1, 4) * np.pi / L
    f_ref = np.sqrt((k**4 * steel.E * I + k**2 * tension) / (steel.rho * A)) / (2 * np.pi)
    assert f == pytest.approx(f_ref, rel=2e-3)
    unloaded = solve_beam_modes(model, supports, n=1).frequencies_hz[0]
    assert f[0] / unloaded == pytest.approx(np.sqrt(1 + tension / (k[0]**2 * steel.E * I)),
                                            rel=2e-3)


def test_timoshenko_reference_tends_to_euler_bernoulli():
    """The reference solver itself: for L/h = 200 it gives beta_n L within the shear and
    rotary-inertia correction ~ (beta_n h / L)^2 (< 2e-4)."""
    E, nu, rho, w, h, L = 200e9, 0.3, 7800.0, 0.01, 0.005, 1.0
    f = np.array(timoshenko_cantilever_hz(E, nu, rho, w * h, w * h**3 / 12, L, 3))
    beta_L = np.sqrt(2 * np.pi * f * L**2 / np.sqrt(E * h**2 / 12 / rho))
    assert beta_L == pytest.approx(BETA_L, rel=2e-4)
