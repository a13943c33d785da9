"""Large deflection against the elastica (independent shooting solve) and Mattiasson's table;
a tip moment 2 pi EI / L rolls a cantilever into a full circle."""
import numpy as np
import pytest

from beam_theory import elastica_tip
from beam_models import cantilever
from flexfem.fem.beam import NodalLoad, solve_beam_nonlinear
from flexfem.fem.beam.supports import NodeFixed

# Mattiasson (1981), IJNME 17, 145-153, table 1: P L^2 / EI -> (u/L, v/L); the tip
# rotation at 10 printed as 1.38918 in the issue is not the elastica's: see MATTIASSON_ROT.
MATTIASSON = {1.0: (0.05643, 0.30172), 10.0: (0.55500, 0.81061)}
MATTIASSON_ROT = {1.0: 0.46135}


@pytest.mark.parametrize("k", [1.0, 10.0])
def test_reference_elastica_matches_mattiasson(k):
    u, v, theta = elastica_tip(k)
    assert u == pytest.approx(MATTIASSON[k][0], abs=1e-5)
    assert v == pytest.approx(MATTIASSON[k][1], abs=1e-5)
    if k in MATTIASSON_ROT:
        assert theta == pytest.approx(MATTIASSON_ROT[k], abs=1e-5)


@pytest.mark.parametrize("k", [1.0, 10.0])
def test_cantilever_tip_load_matches_elastica(steel, k):
    L, w, t = 0.1, 0.01, 1e-3
    EI = steel.E * w * t**3 / 12
    model, tip = cantilever(steel, L, w, t, n=50)
    res = solve_beam_nonlinear(model, [NodeFixed(0)], [NodalLoad(tip, fy=k * EI / L**2)], steps=10)
    u, v, theta = elastica_tip(k)
    q = res.final.q[tip]
    assert -q[0] / L == pytest.approx(u, rel=1e-3)
    assert q[1] / L == pytest.approx(v, rel=1e-3)
    assert q[2] == pytest.approx(theta, rel=1e-3)
    # equilibrium: the root reaction balances the dead tip load and its moment
    R = res.final.reactions[0]
    P = k * EI / L**2
    assert R[:2] == pytest.approx([0.0, -P], abs=1e-8 * P)
    assert R[2] == pytest.approx(-P * (L + q[0]), rel=1e-8)


def test_tip_moment_rolls_a_full_circle(steel):
    L, w, t = 0.1, 0.01, 1e-3
    EI = steel.E * w * t**3 / 12
    model, tip = cantilever(steel, L, w, t, n=40)
    res = solve_beam_nonlinear(model, [NodeFixed(0)], [NodalLoad(tip, m=2 * np.pi * EI / L)],
                               steps=8)
    q = res.final.q[tip]
    assert np.hypot(L + q[0], q[1]) < 1e-9 * L          # the tip is back at the root
    assert q[2] == pytest.approx(2 * np.pi, rel=1e-9)
    # pure bending: no axial force, the same moment everywhere, stress = M c / I
    assert np.abs(res.final.axial_force).max() < 1e-6 * (EI / L**2)
    assert res.final.end_moments == pytest.approx(np.full((40, 2), 2 * np.pi * EI / L), rel=1e-8)
    assert res.final.max_stress == pytest.approx(2 * np.pi * EI / L * (t / 2) / (w * t**3 / 12),
                                                 rel=1e-8)
    # half-way, a semicircle of radius L / pi: the elements are its chords (a regular
    # 80-gon of side L / 40), so the tip is a diameter 2 R' = (L / 40) / sin(pi / 80) above
    # the root, 2.6e-4 more than the arc's 2 L / pi
    half = res.states[4]
    assert res.load_factors[4] == pytest.approx(0.5)
    diameter = (L / 40) / np.sin(np.pi / 80)
    assert half.q[tip, :2] + [L, 0.0] == pytest.approx([0.0, diameter], abs=1e-9 * L)
    assert diameter / (2 * L / np.pi) - 1 == pytest.approx(2.57e-4, rel=1e-2)
