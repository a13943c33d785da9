"""Verification of the harmonic response (flexfem.fem.harmonic) on a slender cantilever
(L / H = 50, plane stress, Q2) loaded at the tip: static limit, single-mode resonance and
half-power bandwidth, modal superposition against the direct complex solve."""
import numpy as np
import pytest
import skfem

from flexfem.fem import (Fixed, Force, Material, Model, PlaneStress, solve_modes,
                         solve_static)
from flexfem.fem.harmonic import Rayleigh, solve_harmonic
from flexfem.fem.mesh import FEMesh, facets_where

L, H, T = 1.0, 0.02, 0.01  # m
STEEL = Material("test steel", E=200e9, nu=0.3, rho=7800.0, yield_strength=250e6)

SUPPORTS, LOADS = [Fixed("fixed")], [Force("tip", (0.0, -1.0))]


@pytest.fixture(scope="module")
def beam():
    m = skfem.MeshQuad.init_tensor(np.linspace(0, L, 51), np.linspace(0, H, 3))
    mesh = FEMesh(m, {"fixed": facets_where(m, lambda x: np.isclose(x[0], 0.0)),
                      "tip": facets_where(m, lambda x: np.isclose(x[0], L))})
    model = Model(mesh, STEEL, PlaneStress(T), order=2)
    return model, solve_modes(model, 2, SUPPORTS).frequencies_hz


def test_static_limit_is_the_static_solve(beam):
    # the residual-flexibility term makes the modal sum exact at 0 Hz, to the round-off of two
    # factorizations of K (each ~5e-9 from a refined dense solve; eps cond(K) ~ 8e-8 for
    # L / H = 50; without the term the error is that of the modes left out, ~1e-3); the
    # direct complex LU (no refinement) likewise
    model, _ = beam
    static = solve_static(model, SUPPORTS, LOADS).u
    modal = solve_harmonic(model, SUPPORTS, LOADS, 0.0, damping=0.02, n_modes=3).u[0]
    direct = solve_harmonic(model, SUPPORTS, LOADS, [0.0], method="direct").u[0]
    scale = np.abs(static).max()
    assert np.abs(modal - static).max() < 1e-8 * scale
    assert np.abs(direct - static).max() < 1e-6 * scale
    # the functional mean equals the static result's mean displacement
    mean = solve_static(model, SUPPORTS, LOADS).mean_displacement("tip")
    assert np.allclose(solve_harmonic(model, SUPPORTS, LOADS, 0.0, n_modes=3)
                       .mean_displacement("tip")[0], mean, rtol=1e-8, atol=1e-8 * abs(mean).max())


def test_undamped_response_flips_phase_at_the_first_resonance(beam):
    # single mode near f1: u ~ phi1 p1 / (w1^2 - w^2): in phase with the load below, in
    # anti-phase above, and 1 / |1 - (f / f1)^2| times the modal static part; at f = 0.99 f1
    # and 1.01 f1 the other modes add < 1e-3 of the response (measured), so 1 % holds
    model, f = beam
    frf = solve_harmonic(model, SUPPORTS, LOADS, [0.99 * f[0], 1.01 * f[0]], n_modes=10).frf("tip", "y")
    static = solve_static(model, SUPPORTS, LOADS).mean_displacement("tip")[1]
    assert np.sign(frf.response.real).tolist() == [np.sign(static), -np.sign(static)]
    assert np.abs(frf.response.imag).max() == 0.0
    # the first mode carries ~97 % of a cantilever tip's static deflection (Euler-Bernoulli:
    # 8 / (beta_1 L)^4 / (1 / 3) = 0.971); 2 % allowed for the continuum and the 1 % above
    gain = frf.amplitude * np.abs(1 - np.array([0.99, 1.01]) ** 2) / abs(static)
    assert gain == pytest.approx(0.971, rel=0.02)


def test_damped_resonance_peak_and_half_power_bandwidth(beam):
    # a single lightly damped mode: displacement peak at f1 sqrt(1 - 2 zeta^2), half-power
    # bandwidth 2 zeta f1 (to O(zeta^2) = 1e-4, plus the other modes' background, measured
    # 1.2e-4); sampled every 1e-4 f1 and interpolated: 1e-4 on the peak, 1 % on the width
    model, f = beam
    zeta = 0.01
    frequencies = np.linspace(0.9, 1.1, 2001) * f[0]
    result = solve_harmonic(model, SUPPORTS, LOADS, frequencies, damping=zeta, n_modes=10)
    frf = result.frf("tip", 1)
    assert frf.peaks() == pytest.approx([f[0] * np.sqrt(1 - 2 * zeta ** 2)], rel=1e-4)
    assert frf.bandwidth(f[0]) == pytest.approx(2 * zeta * f[0], rel=0.01)
    # the phase passes -90 degrees relative to the load's sense at resonance
    k = np.argmin(np.abs(frequencies - f[0]))
    static_sign = np.sign(frf.response[0].real)
    assert np.angle(frf.response[k] * static_sign) == pytest.approx(-np.pi / 2, abs=0.02)


def test_modal_superposition_matches_the_direct_solve(beam):
    # Rayleigh damping (zeta1 = 2 %) is diagonal in the modes, so modal and direct solve the
    # same equations up to the truncated modes' dynamic part, ~(f / f11)^2 of their small
    # static share (measured 3e-6 relative); 1e-4 allowed, from 0 to 1.5 f2
    model, f = beam
    damping = Rayleigh(0.0, 2 * 0.02 / (2 * np.pi * f[0]))
    frequencies = np.linspace(0, 1.5, 31) * f[1]
    modal = solve_harmonic(model, SUPPORTS, LOADS, frequencies, damping, n_modes=10)
    direct = solve_harmonic(model, SUPPORTS, LOADS, frequencies, damping, method="direct")
    assert np.abs(modal.u - direct.u).max() < 1e-4 * np.abs(direct.u).max()
    assert modal.info["damping_ratios"][0] == pytest.approx(0.02)


def test_bad_arguments(beam):
    model, _ = beam
    with pytest.raises(ValueError, match="frequencies_hz"):
        solve_harmonic(model, SUPPORTS, LOADS, [-1.0])
    with pytest.raises(ValueError, match="method"):
        solve_harmonic(model, SUPPORTS, LOADS, [1.0], method="fft")
    with pytest.raises(ValueError, match="damping"):
        solve_harmonic(model, SUPPORTS, LOADS, [1.0], damping=0.02, method="direct")
    with pytest.raises(ValueError, match="damping"):
        solve_harmonic(model, SUPPORTS, LOADS, [1.0], damping=[0.1, 0.2], n_modes=3)
    with pytest.raises(ValueError, match="alpha"):
        Rayleigh(alpha=-1.0)
    result = solve_harmonic(model, SUPPORTS, LOADS, [1.0], n_modes=2)
    with pytest.raises(ValueError, match="component"):
        result.frf("tip", "z")
