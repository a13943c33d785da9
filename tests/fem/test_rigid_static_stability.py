"""Rigid faces in the linear static solve, stress at any nonlinear step, supports check and
prestress of the modal solve, stability and strain validity of nonlinear steps. Slender
cantilevers and strips, L / H = 50, plane stress, Q2."""
import numpy as np
import pytest
import skfem

from flexfem.fem import (Fixed, Force, Material, Model, PlaneStress, Prescribed, RigidFace,
                         UnderConstrainedError, solve_modes, solve_nonlinear, solve_static)
from flexfem.fem.mesh import FEMesh, facets_where

L, H, T = 1.0, 0.02, 0.01  # m
E_MOD = 200e9  # Pa
EI = E_MOD * T * H ** 3 / 12  # N m^2
STEEL = Material("test steel", E=E_MOD, nu=0.3, rho=7800.0, yield_strength=250e6)


def strip(nx, ny, length=L, height=H, y0=0.0):
    """Structured quadrilateral [0, length] x [y0, y0 + height] (m), groups fixed (x = 0),
    tip (x = length)."""
    m = skfem.MeshQuad.init_tensor(np.linspace(0, length, nx + 1),
                                   np.linspace(y0, y0 + height, ny + 1))
    return FEMesh(m, {"fixed": facets_where(m, lambda x: np.isclose(x[0], 0.0)),
                      "tip": facets_where(m, lambda x: np.isclose(x[0], length))})


@pytest.fixture(scope="module")
def beam():
    return Model(strip(50, 2), STEEL, PlaneStress(T), order=2)


def test_linear_moment_on_rigid_face_matches_beam_theory(beam):
    # pure bending: theta = M L / EI, c_y = M L^2 / (2 EI); the continuum departs by the
    # clamp's boundary layer, O(H / L) of one element layer: measured 0.05 %, 0.5 % allowed
    M = 1.0
    result = solve_static(beam, [Fixed("fixed")], [], rigid_faces=[RigidFace("tip", moment=M)])
    c_x, c_y, theta = result.face_motion["tip"]
    assert theta == pytest.approx(M * L / EI, rel=5e-3)
    assert c_y == pytest.approx(M * L ** 2 / (2 * EI), rel=5e-3)
    assert abs(c_x) < 1e-9 * c_y
    # the free face carries exactly the applied load; the clamp reacts no force
    assert np.allclose(result.face_reactions["tip"], [0.0, 0.0, M], atol=1e-8 * M / L)
    assert np.abs(result.reactions["fixed"]).max() < 1e-6 * M / L
    # the same face with the rotation prescribed reacts the same moment (to the solve's 1e-6)
    driven = solve_static(beam, [Fixed("fixed")], [], rigid_faces=[RigidFace("tip", rotation=theta)])
    assert driven.face_reactions["tip"][2] == pytest.approx(M, rel=1e-6)
    assert driven.face_motion["tip"][1] == pytest.approx(c_y, rel=1e-6)


def test_linear_rigid_face_is_the_small_load_limit_of_the_nonlinear_one(beam):
    # theta = 7.5e-4 rad: the nonlinear correction is O(theta) relative, 1e-3 allowed
    face = RigidFace("tip", moment=1.0, force=(0.0, -2.0))
    linear = solve_static(beam, [Fixed("fixed")], [], rigid_faces=[face])
    large = solve_nonlinear(beam, [Fixed("fixed")], [], steps=1, rigid_faces=[face])
    q_lin, q_nl = linear.face_motion["tip"], large.face_motion[-1]["tip"]
    assert np.allclose(q_lin[1:], q_nl[1:], rtol=1e-3)


def test_stress_at_step_is_the_final_stress_at_the_last_step(beam):
    result = solve_nonlinear(beam, [Fixed("fixed")], [Force("tip", (0.0, -50.0))], steps=2)
    nodal, element = result.stress_at_step(-1)
    assert np.array_equal(nodal, result.von_mises_nodal)
    assert np.array_equal(element, result.von_mises_element_max)
    half_nodal, half_element = result.stress_at_step(1)
    # small deflection (2 % of L): the stress at half load is half, to 5 %
    assert half_element.max() == pytest.approx(0.5 * element.max(), rel=0.05)
    assert np.all(result.stress_at_step(0)[1] == 0.0)
    with pytest.raises(ValueError, match="step"):
        result.stress_at_step(3)


def test_modes_refuse_an_unsupported_disconnected_piece():
    a, b = strip(10, 2, 0.2), strip(10, 2, 0.2, y0=0.1)
    p = np.hstack([a.mesh.p, b.mesh.p])
    t = np.hstack([a.mesh.t, b.mesh.t + a.mesh.p.shape[1]])
    m = skfem.MeshQuad(p, t)
    held = facets_where(m, lambda x: np.isclose(x[0], 0.0) & (x[1] < 0.05))
    model = Model(FEMesh(m, {"fixed": held}), STEEL, PlaneStress(T), order=2)
    with pytest.raises(UnderConstrainedError, match="part 2"):
        solve_modes(model, 4, [Fixed("fixed")])


def pinned_half(length=L, nx=50):
    """Half of a pinned-pinned strip of ``length``: x held on the mid-span section 'fixed'
    (symmetry), y held on the pinned end 'tip', whose x is free for an axial load."""
    return (Model(strip(nx, 2, length / 2), STEEL, PlaneStress(T), order=2),
            [Prescribed("fixed", x=0.0), Prescribed("tip", y=0.0)])


def test_tension_raises_the_first_frequency_as_the_string_beam_formula():
    # pinned-pinned Euler-Bernoulli beam under axial tension P: f1^2 = f0^2 (1 + P / P_E),
    # P_E = pi^2 EI / L^2, exact for the linearised prestress. Shear and rotary inertia
    # shift f0 and P_E alike by ~(H / L)^2 pi^2 = 4e-3 and cancel in the ratio: 0.2 %
    model, supports = pinned_half()
    P = np.pi ** 2 * EI / L ** 2
    free = solve_modes(model, 1, supports).frequencies_hz[0]
    state = solve_static(model, supports, [Force("tip", (P, 0.0))])
    tense = solve_modes(model, 1, supports, prestress=state).frequencies_hz[0]
    assert tense / free == pytest.approx(np.sqrt(2.0), rel=2e-3)
    # the consistent tangent at the nonlinear state agrees (axial strain 1e-4 changes it by
    # that order)
    large = solve_nonlinear(model, supports, [Force("tip", (P, 0.0))], steps=1)
    assert solve_modes(model, 1, supports, prestress=(large, 1)).frequencies_hz[0] == \
        pytest.approx(tense, rel=1e-3)
    # compression at P_E / 2: f1^2 = f0^2 / 2; here the ratio feels the continuum's lower
    # buckling load (shear, ~pi^2 E H^2 / (12 kappa G L^2) = 1e-3, and the mesh) twice as
    # strongly as in tension: measured -0.2 %, 0.5 % allowed
    state = solve_static(model, supports, [Force("tip", (-P / 2, 0.0))])
    soft = solve_modes(model, 1, supports, prestress=state).frequencies_hz[0]
    assert soft / free == pytest.approx(np.sqrt(0.5), rel=5e-3)


def test_straight_leaf_far_beyond_euler_load_is_flagged_unstable(beam):
    # fixed-free leaf, P_E = pi^2 EI / (4 L^2); kept straight by the symmetric mesh and
    # load, the reduced tangent has one negative eigenvalue per buckling load (2n - 1)^2 P_E
    # below the load: 1 at 3.3 P_E and 6.7 P_E, 2 at 10 P_E (9 P_E < 10 P_E < 25 P_E)
    P_E = np.pi ** 2 * EI / (4 * L ** 2)
    result = solve_nonlinear(beam, [Fixed("fixed")], [Force("tip", (-10 * P_E, 0.0))], steps=3)
    assert result.negative_eigenvalues == [0, 1, 1, 2]
    assert result.stable.tolist() == [True, False, False, False]
    assert np.abs(result.path("tip")[:, 1]).max() < 1e-9 * L  # straight
    below = solve_nonlinear(beam, [Fixed("fixed")], [Force("tip", (-0.5 * P_E, 0.0))], steps=1)
    assert below.stable.all()
    # axial strain P / (E A) = 8.2e-4: valid
    assert result.strain_valid.all()
    assert result.max_strain[-1] == pytest.approx(10 * P_E / (E_MOD * H * T), rel=0.05)


def test_absurd_stretch_is_flagged_beyond_the_strain_limit():
    # a square block stretched to 4.36 x its length: Green-Lagrange strain (4.36^2 - 1) / 2
    # = 9 (900 %), far beyond the 5 % validity limit of St. Venant-Kirchhoff
    model = Model(strip(4, 2, 0.02, 0.02), STEEL, PlaneStress(T), order=2)
    face = RigidFace("tip", x=0.02 * 3.36, y=0.0, rotation=0.0)
    result = solve_nonlinear(model, [Fixed("fixed")], [], steps=10, rigid_faces=[face])
    assert result.max_strain[-1] > 9.0 * 0.9
    assert not result.strain_valid[-1] and result.strain_valid[0]
    with pytest.raises(ValueError, match="strain_limit"):
        solve_nonlinear(model, [Fixed("fixed")], [], steps=1, rigid_faces=[face], strain_limit=0)
