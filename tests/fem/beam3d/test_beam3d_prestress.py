"""Modes and compliance about a converged nonlinear state: stress stiffening by tension in
both bending planes against the string-beam and beam-column formulas."""
import numpy as np
import pytest

from beam3d_models import straight
from flexfem.fem.beam.spatial import (NodalLoad, Section, compliance3d, solve_beam3d_modes,
                                      solve_beam3d_nonlinear)
from flexfem.fem.beam.supports import NodeFixed


def test_tension_raises_the_bending_frequencies_as_the_string_beam(steel):
    """Pinned-pinned, L = 0.2 m, 1 x 2 mm, 40 el., axial tension T = 6 EI_z / L^2 (dead, at
    the sliding end): omega_n^2 = [(n pi/L)^4 EI + (n pi/L)^2 T] / (rho A) in each bending
    plane, modes about the converged state. Discretisation and rotary inertia: < 1e-3."""
    section = Section.rect(2e-3, 1e-3)
    L, n = 0.2, 40
    model, end = straight(steel, section, length=L, n=n)
    T = 6 * steel.E * section.Iz / L**2
    supports = [NodeFixed(0, ("x", "y", "z", "rx")), NodeFixed(end, ("y", "z"))]
    loads = [NodalLoad(end, fx=T)]
    state = solve_beam3d_nonlinear(model, supports, loads, steps=2).final
    modes = solve_beam3d_modes(model, supports, n=12, about=state, loads=loads)
    rho_A = steel.rho * section.A
    k = np.arange(1, 4) * np.pi / L
    for plane, I in ((1, section.Iz), (2, section.Iy)):
        f = modes.frequencies_hz[np.abs(modes.shapes[:, :, plane]).max(axis=1) > 1e-3 *
                                 np.abs(modes.shapes[:, :, :3]).max(axis=(1, 2))]
        exact = np.sqrt((k**4 * steel.E * I + k**2 * T) / rho_A) / (2 * np.pi)
        assert f[:3] == pytest.approx(exact, rel=1e-3)
    unloaded = solve_beam3d_modes(model, supports, n=1).frequencies_hz[0]
    assert modes.frequencies_hz[0] / unloaded == pytest.approx(np.sqrt(1 + 6 / np.pi**2),
                                                              rel=1e-3)


def test_tension_stiffens_the_tip_as_the_beam_column(steel):
    """Cantilever under dead tension P = EI/L^2 about each axis in turn: the tip's lateral
    compliance about the state is (kL - tanh kL) / (P k), k = sqrt(P / EI) (0.715 of
    L^3/3EI), in the plane of that I."""
    section = Section.rect(2e-3, 1e-3)
    L = 0.1
    model, tip = straight(steel, section, length=L, n=20)
    for dof, I in ((1, section.Iz), (2, section.Iy)):
        P = steel.E * I / L**2
        loads = [NodalLoad(tip, fx=P)]
        state = solve_beam3d_nonlinear(model, [NodeFixed(0)], loads, steps=1).final
        C = compliance3d(model, [NodeFixed(0)], tip, about=state, loads=loads)
        kk = np.sqrt(P / (steel.E * I))
        assert C[dof, dof] == pytest.approx((kk * L - np.tanh(kk * L)) / (P * kk), rel=1e-3)


def test_a_state_under_a_finite_moment_is_refused(steel):
    model, tip = straight(steel, Section.rect(2e-3, 1e-3), length=0.1, n=8)
    loads = [NodalLoad(tip, mz=0.5, fz=1.0)]
    state = solve_beam3d_nonlinear(model, [NodeFixed(0)], loads, steps=4).final
    with pytest.raises(ValueError, match="not symmetric"):
        solve_beam3d_modes(model, [NodeFixed(0)], n=2, about=state, loads=loads)
