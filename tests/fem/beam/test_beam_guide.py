"""Parallel leaf-spring guide: parasitic shortening 3/5 delta^2 / L, displacement control,
rigid links, and the tangent compliance against finite differences of nonlinear solves."""
import numpy as np
import pytest

from beam_models import parallel_guide
from flexfem.fem.beam import (BeamModel, NodalLoad, RigidLink, Section, beam_chain, compliance,
                              solve_beam_nonlinear, solve_beam_static)
from flexfem.fem.beam.supports import NodeFixed, NodePrescribed

L, W, T, GAP = 0.05, 0.01, 0.5e-3, 0.03


@pytest.mark.parametrize("ratio", [0.02, 0.05, 0.1])
def test_parasitic_shortening(steel, ratio):
    """Stage moved sideways by delta (free axially and in rotation): each fixed-guided leaf
    shortens by 3/5 delta^2 / L; higher order terms ~ (delta / L)^2 relative."""
    model, supports, stage = parallel_guide(steel, L, W, T, GAP, n=50)
    delta = ratio * L
    res = solve_beam_nonlinear(model, supports + [NodePrescribed(stage, "y", delta)], steps=10)
    shortening = -res.final.q[stage, 0]
    # measured: 0.99996, 1.0029, 1.0115
    assert shortening / (0.6 * delta**2 / L) == pytest.approx(1.0, abs=max(1e-3, 1.5 * ratio**2))
    assert abs(res.final.q[stage, 2]) < 0.1 * delta / L    # the stage barely rotates


def test_displacement_control_matches_prescribed(steel):
    """control=(stage, 'y', delta) with a unit force finds the same state as a prescribed
    delta, the load factor equal to the prescribed run's reaction; near-linear stiffness
    24 EI / L^3 at small stroke."""
    model, supports, stage = parallel_guide(steel, L, W, T, GAP, n=20)
    delta = 0.002
    pres = solve_beam_nonlinear(model, supports + [NodePrescribed(stage, "y", delta)], steps=5)
    ctrl = solve_beam_nonlinear(model, supports, [NodalLoad(stage, fy=1.0)], steps=5,
                                control=(stage, "y", delta))
    assert ctrl.final.q == pytest.approx(pres.final.q, abs=1e-12)
    assert ctrl.load_factors[-1] == pytest.approx(pres.final.reactions[stage][1], rel=1e-8)
    k_lin = 24 * steel.E * W * T**3 / 12 / L**3
    assert ctrl.load_factors[-1] / (k_lin * delta) == pytest.approx(1.0, abs=2e-3)


def test_rigid_link_equals_stiff_beam(steel):
    """The rigid-link stage against the stage modelled as a 1000x thicker beam: same tip
    compliance to ~1e-3 (the stiff beam's own compliance)."""
    model, supports, stage = parallel_guide(steel, L, W, T, GAP, n=20)
    a = beam_chain([(0, 0), (L, 0)], Section.rect(W, T), 20)
    b = beam_chain([(0, GAP), (L, GAP)], Section.rect(W, T), 20)
    s = beam_chain([(L, 0), (L, GAP / 2), (L, GAP)], Section.rect(W, 1000 * T), 1)
    g = a.join(b).join(s)
    stiff = BeamModel(g.nodes, g.elements, g.sections, steel)
    mid = g.node_at((L, GAP / 2))
    C_link = compliance(model, supports, stage)
    C_beam = compliance(stiff, [NodeFixed((0, g.node_at((0, GAP))))], mid)
    assert C_beam[1, 1] == pytest.approx(C_link[1, 1], rel=1e-3)
    assert C_beam[2, 2] == pytest.approx(C_link[2, 2], rel=1e-3)
    assert C_link[1, 1] == pytest.approx(L**3 / (24 * steel.E * W * T**3 / 12), rel=1e-3)


def test_tangent_compliance_matches_finite_differences(steel):
    """compliance(about=state) = d(stage motion)/d(load) at a deflected state."""
    model, supports, stage = parallel_guide(steel, L, W, T, GAP, n=20)
    F = np.array([2.0, 30.0, 0.05])
    load = lambda f: [NodalLoad(stage, f[0], f[1], m=f[2])]
    state = solve_beam_nonlinear(model, supports, load(F), steps=5).final
    assert state.q[stage, 1] > 0.1 * L                    # large stroke
    C = compliance(model, supports, stage, about=state, loads=load(F))
    h = np.array([1e-3, 1e-2, 1e-5])
    fd = np.zeros((3, 3))
    for j in range(3):
        dF = np.zeros(3)
        dF[j] = h[j]
        up = solve_beam_nonlinear(model, supports, load(F + dF), steps=5).final.q[stage]
        down = solve_beam_nonlinear(model, supports, load(F - dF), steps=5).final.q[stage]
        fd[:, j] = (up - down) / (2 * h[j])
    assert C == pytest.approx(fd, rel=1e-4, abs=1e-6 * np.abs(fd).max())
    assert C == pytest.approx(C.T, rel=1e-8, abs=1e-12)
    # the axial compliance of the deflected guide is far above the straight one's
    C0 = compliance(model, supports, stage)
    assert C[0, 0] > 10 * C0[0, 0]


def test_linear_guide_static(steel):
    model, supports, stage = parallel_guide(steel, L, W, T, GAP, n=10)
    res = solve_beam_static(model, supports, [NodalLoad(stage, fy=1.0)])
    k = 24 * steel.E * W * T**3 / 12 / L**3
    assert res.q[stage, 1] == pytest.approx(1 / k, rel=1e-3)
    total = res.reactions[0] + res.reactions[model.n_nodes - 2 - 10]
    assert total[:2] == pytest.approx([0.0, -1.0], abs=1e-9)


def test_load_on_a_rigid_link_slave(steel):
    """A dead force on the end of a rigid arm at the tip equals the same force on an arm
    modelled as a much stiffer beam, at large rotation too (the arm turns with the tip)."""
    mesh = beam_chain([(0, 0), (0.1, 0)], Section.rect(0.01, 1e-3), 20)
    arm = (0.1, 0.02)
    linked = BeamModel(np.vstack([mesh.nodes, [arm]]), mesh.elements, mesh.sections, steel,
                       rigid_links=[RigidLink(20, (21,))])
    g = mesh.join(beam_chain([(0.1, 0), arm], Section.rect(0.01, 0.1), 1))
    beam = BeamModel(g.nodes, g.elements, g.sections, steel)
    loads = [NodalLoad(21, fx=-5.0, fy=20.0)]
    a = solve_beam_nonlinear(linked, [NodeFixed(0)], loads, steps=5).final
    b = solve_beam_nonlinear(beam, [NodeFixed(0)], loads, steps=5).final
    assert a.q[20, 2] > 0.5                                     # large rotation
    assert a.q[[20, 21]] == pytest.approx(b.q[[20, 21]], rel=1e-5, abs=1e-9)
    assert a.reactions[0] == pytest.approx(b.reactions[0], rel=1e-5)
