"""Linear spatial beam: the 6x6 tip compliance of a cantilever against beam theory, the
torsion constant of a rectangle, rigid links, and the planar model on an in-plane frame."""
import numpy as np
import pytest

from beam3d_models import closed_form_tip_compliance, straight
from flexfem.fem import beam as planar
from flexfem.fem.beam.spatial import (Beam3DModel, NodalLoad, RigidLink, Section,
                                      SingularBeamError, compliance3d, rect_torsion_constant,
                                      solve_beam3d_nonlinear, solve_beam3d_static)
from flexfem.fem.beam.supports import NodeFixed


@pytest.mark.parametrize("shear", [False, True])
def test_cantilever_tip_compliance_is_beam_theory(steel, shear):
    """Cubic (IIE) elements are exact for end loads: every entry to round-off."""
    section = Section.rect(5e-3, 2e-3)
    model, tip = straight(steel, section, length=0.1, n=4, shear=shear)
    C = compliance3d(model, [NodeFixed(0)], node=tip)
    ref = closed_form_tip_compliance(steel, section, 0.1, shear=shear)
    assert np.allclose(C, ref, rtol=1e-10, atol=1e-10 * np.abs(ref).max())


def test_skew_cantilever_compliance_transforms_as_a_tensor(steel):
    """Along an arbitrary direction with an arbitrary section orientation: C = Q C_loc Q^T,
    Q = blockdiag(frame, frame)."""
    section = Section.rect(3e-3, 1e-3)
    model, tip = straight(steel, section, length=0.08, n=3, direction=(1.0, 2.0, -0.5),
                          orientation=(0.3, -1.0, 2.0))
    frame = model.frames[0]
    Q = np.kron(np.eye(2), frame)
    ref = Q @ closed_form_tip_compliance(steel, section, 0.08) @ Q.T
    C = compliance3d(model, [NodeFixed(0)], node=tip)
    assert np.allclose(C, ref, rtol=1e-9, atol=1e-9 * np.abs(ref).max())
    assert np.allclose(frame.T @ frame, np.eye(3))


def test_rect_torsion_constant_limits():
    """Square: J = 0.1406 a^4 (Timoshenko & Goodier, table of k1: 0.141); thin strip:
    J -> b t^3 / 3 (1 - 0.630 t / b)."""
    assert rect_torsion_constant(1.0, 1.0) == pytest.approx(0.14058, rel=1e-4)
    assert rect_torsion_constant(1e-3, 20e-3) == pytest.approx(
        20e-3 * 1e-9 / 3 * (1 - 0.630 * 1e-3 / 20e-3), rel=1e-4)


def test_rigid_arm_adds_torsion_to_the_deflection(steel):
    """A rigid arm of length d along y at the tip, loaded by F_z at its end: w = F L^3 /
    3EIy + F d^2 L / GJ, r_x = F d L / GJ."""
    section = Section.rect(2e-3, 2e-3)
    L, d, F = 0.1, 0.03, 1.0
    nodes = np.vstack([np.linspace(0.0, L, 11)[:, None] * [1.0, 0.0, 0.0], [[L, d, 0.0]]])
    elements = np.column_stack([np.arange(10), np.arange(1, 11)])
    model = Beam3DModel(nodes, elements, section, steel, rigid_links=[RigidLink(10, 11)])
    res = solve_beam3d_static(model, [NodeFixed(0)], [NodalLoad(11, fz=F)])
    G = steel.E / (2 * (1 + steel.nu))
    w = F * L**3 / (3 * steel.E * section.Iy) + F * d**2 * L / (G * section.J)
    assert res.u[11, 2] == pytest.approx(w, rel=1e-10)
    assert res.q[10, 3] == pytest.approx(F * d * L / (G * section.J), rel=1e-10)
    assert res.reactions[0] == pytest.approx([0, 0, -F, -F * d, F * L, 0], abs=1e-9)


def _frames(steel):
    """A portal frame in the x-y plane with a rigid beam on top (a link), both models."""
    t, w = 1e-3, 5e-3
    mesh = planar.beam_chain([(0.0, 0.0), (0.0, 0.06), (0.04, 0.06), (0.04, 0.0)],
                             planar.Section.rect(w, t), [12, 8, 12])
    ends = mesh.point_nodes
    nodes2 = np.vstack([mesh.nodes, [[0.02, 0.08]]])
    link = (len(nodes2) - 1, (ends[1], ends[2]))
    m2 = planar.BeamModel(nodes2, mesh.elements, mesh.sections, steel,
                          rigid_links=[planar.RigidLink(*link)])
    nodes3 = np.column_stack([nodes2, np.zeros(len(nodes2))])
    m3 = Beam3DModel(nodes3, mesh.elements, Section.rect(w, t), steel,
                     rigid_links=[RigidLink(*link)])
    return m2, m3, ends, link[0]


def test_planar_model_agrees_on_an_in_plane_frame(steel):
    """Linear and large-rotation solves of the same frame: the spatial model's in-plane
    motion equals the planar model's (same element in plane) and nothing leaves the
    plane."""
    m2, m3, ends, top = _frames(steel)
    base = (ends[0], ends[3])
    lin2 = planar.solve_beam_static(m2, [NodeFixed(base)], [planar.NodalLoad(top, fx=5.0)])
    lin3 = solve_beam3d_static(m3, [NodeFixed(base)], [NodalLoad(top, fx=5.0)])
    assert np.allclose(lin3.q[:, [0, 1, 5]], lin2.q, rtol=0, atol=1e-9 * np.abs(lin2.q).max())
    big = dict(fx=150.0, fy=-60.0)
    nl2 = planar.solve_beam_nonlinear(m2, [NodeFixed(base)],
                                      [planar.NodalLoad(top, m=0.2, **big)], steps=10)
    nl3 = solve_beam3d_nonlinear(m3, [NodeFixed(base)], [NodalLoad(top, mz=0.2, **big)], steps=10)
    q2, q3 = nl2.final.q, nl3.final.q
    assert np.abs(q2[:, 2]).max() > 0.3  # rad: a large-rotation state
    assert np.allclose(q3[:, [0, 1, 5]], q2, rtol=0, atol=1e-8 * np.abs(q2).max())
    assert np.abs(q3[:, [2, 3, 4]]).max() < 1e-12
    assert nl3.final.reactions[base[0]][[0, 1, 5]] == pytest.approx(
        nl2.final.reactions[base[0]], rel=1e-7, abs=1e-9)


def test_a_mechanism_and_a_vertical_column_are_handled(steel):
    """Supports that leave a motion free are named; an element along global z gets local z
    = global x by default, so its bending planes are still defined."""
    model, tip = straight(steel, Section.rect(2e-3, 1e-3), length=0.1, n=4)
    with pytest.raises(SingularBeamError, match="mechanism"):
        compliance3d(model, [NodeFixed(0, ("x", "y", "z"))], node=tip)
    column, top = straight(steel, Section.rect(2e-3, 1e-3), length=0.1, n=4,
                           direction=(0.0, 0.0, 1.0))
    assert column.frames[0][:, 2] == pytest.approx([1.0, 0.0, 0.0])
    C = compliance3d(column, [NodeFixed(0)], node=top)
    section = Section.rect(2e-3, 1e-3)
    # local y = z x x = global y: a force along global y bends about I_z
    assert C[1, 1] == pytest.approx(0.1**3 / (3 * steel.E * section.Iz), rel=1e-10)
    assert C[0, 0] == pytest.approx(0.1**3 / (3 * steel.E * section.Iy), rel=1e-10)


def test_tapered_cantilever_tip_compliance_is_the_unit_load_integral(steel):
    """depth_y = t0 (1 - 0.6 s/L), depth_z = w, 16 linearly tapered elements: C_yy =
    int (L - s)^2 / E I_z(s), C_zz the same with I_y(s), C_rx = int 1 / G J(s) (scipy
    quad). The element's stiffness is its exact flexibility's inverse: measured 1.4e-12 and
    3.1e-12 (the interpolated element before: 3e-6 at 16 elements)."""
    from scipy.integrate import quad
    L, t0, w, n = 0.05, 1e-3, 4e-3, 16
    t = lambda s: t0 * (1 - 0.6 * s / L)
    s = np.linspace(0.0, L, n + 1)
    sections = [Section.rect(w, t(a), thickness_end=t(b)) for a, b in zip(s[:-1], s[1:])]
    nodes = s[:, None] * [1.0, 0.0, 0.0]
    model = Beam3DModel(nodes, [(i, i + 1) for i in range(n)], sections, steel)
    C = compliance3d(model, [NodeFixed(0)], node=n)
    E, G = steel.E, steel.E / (2 * (1 + steel.nu))
    cyy = quad(lambda x: (L - x) ** 2 / (E * w * t(x) ** 3 / 12), 0, L, epsabs=0)[0]
    czz = quad(lambda x: (L - x) ** 2 / (E * t(x) * w**3 / 12), 0, L, epsabs=0)[0]
    crx = quad(lambda x: 1 / (G * rect_torsion_constant(t(x), w)), 0, L, epsabs=0)[0]
    assert C[1, 1] == pytest.approx(cyy, rel=1e-10)
    assert C[2, 2] == pytest.approx(czz, rel=1e-10)
    assert C[3, 3] == pytest.approx(crx, rel=1e-8)
