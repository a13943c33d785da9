"""Verification of the geometrically nonlinear solver (flexfem.fem.nonlinear) and of rigid
faces (flexfem.fem.rigid_face) on slender cantilevers (L/H = 50, plane stress, Q2)."""
import numpy as np
import pytest
import skfem
from flexfem.fem import (
    Fixed,
    Force,
    Material,
    Model,
    PlaneStress,
    Solid3D,
    solve_static,
)
from flexfem.fem.mesh import FEMesh, facets_where
from flexfem.fem.nonlinear import NonConvergenceError, solve_nonlinear
from flexfem.fem.rigid_face import RigidFace
from flexfem.fem.static import UnderConstrainedError
from scipy.integrate import solve_bvp

L, H, T = 1.0, 0.02, 0.01  # m: slender, L / H = 50
E_MOD = 200e9  # Pa
EI = E_MOD * T * H ** 3 / 12  # N m^2
STEEL = Material("test steel", E=E_MOD, nu=0.3, rho=7800.0, yield_strength=250e6)


def beam_mesh(nx, ny, length=L, height=H):
    """Structured [0, length] x [0, height] quadrilateral mesh (m) with boundary groups
    fixed (x = 0) and tip (x = length)."""
    m = skfem.MeshQuad.init_tensor(np.linspace(0, length, nx + 1), np.linspace(0, height, ny + 1))
    return FEMesh(m, {"fixed": facets_where(m, lambda x: np.isclose(x[0], 0.0)),
                      "tip": facets_where(m, lambda x: np.isclose(x[0], length))})


@pytest.fixture(scope="module")
def beam():
    # 25 x 2 biquadratic elements: at theta = pi/2 the arc moment is within 0.1 % of the
    # 100 x 4 mesh's (docs/nonlinear.md), far inside the tolerances below
    return Model(beam_mesh(25, 2), STEEL, PlaneStress(T), order=2)


def elastica_tip(alpha):
    """(vertical, horizontal) tip deflection / L of the inextensible elastica under a dead
    transverse tip load, alpha = P L^2 / EI: EI theta'' = -P cos(theta), theta(0) = 0,
    theta'(L) = 0 (Bisshopp & Drucker 1945: 0.30172, 0.05643 at alpha = 1)."""
    def rhs(s, y):
        return np.vstack([y[1], -alpha * np.cos(y[0]), np.sin(y[0]), np.cos(y[0])])

    s = np.linspace(0, 1, 201)
    guess = np.zeros((4, s.size))
    guess[3] = s
    sol = solve_bvp(rhs, lambda a, b: np.array([a[0], b[1], a[2], a[3]]), s, guess, tol=1e-10)
    assert sol.status == 0
    return sol.y[2, -1], 1 - sol.y[3, -1]


def test_elastica_reference_matches_published():
    v, h = elastica_tip(1.0)
    assert abs(v - 0.30172) < 1e-5 and abs(h - 0.05643) < 1e-5


def test_small_load_reproduces_linear_solve():
    # tip deflection delta = 1e-4 l: the first geometric correction is the axial shortening,
    # of order delta^2 / l, i.e. relative order delta / l = 1e-4 beside the deflection.
    length = 0.2
    beam = Model(beam_mesh(20, 2, length, H), STEEL, PlaneStress(T), order=2)
    P = 1e-4 * 3 * EI / length ** 2
    diffs = []
    for scale in (1.0, 10.0):
        loads = [Force("tip", (0.0, -scale * P))]
        linear = solve_static(beam, [Fixed("fixed")], loads)
        result = solve_nonlinear(beam, [Fixed("fixed")], loads, steps=1)
        diffs.append(np.abs(result.u[-1] - linear.u).max() / np.abs(linear.u).max())
    assert diffs[0] < 1e-4
    # ... and that difference grows like the load (order load^1): x10 load, x10 difference
    assert 7 < diffs[1] / diffs[0] < 13


def test_rigid_face_rotation_rolls_the_beam_into_a_circular_arc(beam):
    # Pure bending of the inextensible Euler-Bernoulli beam: tip centroid on the arc
    # x = L sin(t)/t, y = L (1 - cos t)/t, moment EI t / L. The continuum departs from it by
    # the centre-line stretch and the material nonlinearity, both O(eps^2) with
    # eps = t H / (2 L) <= 0.063 at t = 2 pi (<= 4e-3), and by the boundary layers at the
    # clamp and the rigid face, O(H / L) = 0.02 in the moment and below in the position:
    # 0.5 % of L and 2 % of the moment hold with margin, while a wrong rotation kinematics
    # would miss by O(1).
    result = solve_nonlinear(beam, [Fixed("fixed")], [], steps=8,
                             rigid_faces=[RigidFace("tip", rotation=2 * np.pi)])
    assert np.allclose(result.load_factors, np.linspace(0, 1, 9))
    for k in range(1, 9):
        theta = 2 * np.pi * result.load_factors[k]
        tip = np.array([L, H / 2]) + result.mean_displacement("tip", k)
        arc = np.array([L * np.sin(theta) / theta, H / 2 + L * (1 - np.cos(theta)) / theta])
        assert np.abs(tip - arc).max() < 5e-3 * L, (theta, tip, arc)
        moment = result.face_reactions[k]["tip"][2]
        assert abs(moment / (EI * theta / L) - 1) < 0.02, (theta, moment)
        # pure bending: no force; the root holds none either (to Newton's tolerance)
        assert np.abs(result.reactions[k]["fixed"]).max() < 1e-5 * moment / L
        assert result.face_motion[k]["tip"][2] == pytest.approx(theta)
    # full circle: the tip is back at the root
    assert np.abs(result.mean_displacement("tip") - np.array([-L, 0.0])).max() < 5e-3 * L


def test_applied_moment_on_free_rigid_face_bends_to_the_arc(beam):
    # load control of the same pure bending: M = EI t / L rotates the free face by t
    # (to the same 2 % as the moment above)
    theta = np.pi / 2
    result = solve_nonlinear(beam, [Fixed("fixed")], [], steps=4,
                             rigid_faces=[RigidFace("tip", moment=EI * theta / L)])
    assert result.face_motion[-1]["tip"][2] == pytest.approx(theta, rel=0.02)
    c = result.face_motion[-1]["tip"]
    assert c[0] == pytest.approx(L * np.sin(theta) / theta - L, abs=5e-3 * L)
    assert c[1] == pytest.approx(L * (1 - np.cos(theta)) / theta, abs=5e-3 * L)


@pytest.mark.parametrize("alpha", [1.0, 3.0])
def test_tip_load_follows_the_elastica(beam, alpha):
    # dead tip load P = alpha EI / L^2 (tip deflections 30 % and 60 % of L); the elastica
    # neglects shear and stretch, O((H / L)^2) = 4e-4 of the deflection, and the clamp's
    # boundary layer; the 25 x 2 mesh is within 4.3e-4 L, a 100 x 4 mesh within 1e-4 L
    # (docs/nonlinear.md): 2e-3 L
    P = alpha * EI / L ** 2
    result = solve_nonlinear(beam, [Fixed("fixed")], [Force("tip", (0.0, -P))], steps=5)
    v, h = elastica_tip(alpha)
    tip = result.mean_displacement("tip")
    assert tip[1] == pytest.approx(-v * L, abs=2e-3 * L)
    assert tip[0] == pytest.approx(-h * L, abs=2e-3 * L)
    displacement, force = result.force_displacement("tip")
    assert np.allclose(force[:, 1], -P * result.load_factors)
    assert np.allclose(displacement[-1], tip)


def test_reactions_balance_the_loads_at_every_step(beam):
    # the residual at free DOFs is below tol * reference force, so the reactions plus the
    # applied loads sum to zero to about sqrt(n) * tol of the load: 1e-5 leaves margin
    P = 2.0 * EI / L ** 2
    face = RigidFace("tip", force=(0.3 * P, -P))
    result = solve_nonlinear(beam, [Fixed("fixed")], [], steps=4, rigid_faces=[face])
    for k, lam in enumerate(result.load_factors):
        total = result.reactions[k]["fixed"] + lam * np.array(face.force)
        assert np.abs(total).max() < 1e-5 * P
    # the face's generalised force is the applied one; its moment about the current centroid
    # is the (zero) applied moment, to Newton's tolerance
    _, force = result.force_displacement("tip")
    assert abs(result.face_reactions[-1]["tip"][2]) < 1e-5 * P * L
    assert np.allclose(force[-1], face.force, rtol=1e-6, atol=1e-6 * P)


def test_displacement_control_gives_the_load_control_reaction(beam):
    # the same equilibrium reached by prescribing the displacement the load produced: the
    # face's reaction equals the load to Newton's tolerance
    P = 2.0 * EI / L ** 2
    loaded = solve_nonlinear(beam, [Fixed("fixed")], [], steps=4,
                             rigid_faces=[RigidFace("tip", force=(0.0, -P))])
    y_tip = loaded.face_motion[-1]["tip"][1]
    driven = solve_nonlinear(beam, [Fixed("fixed")], [], steps=4,
                             rigid_faces=[RigidFace("tip", y=y_tip)])
    assert driven.face_reactions[-1]["tip"][1] == pytest.approx(-P, rel=1e-5)
    assert driven.face_motion[-1]["tip"][2] == pytest.approx(loaded.face_motion[-1]["tip"][2],
                                                             rel=1e-5)


def test_bending_stress_is_the_curvature_stress(beam):
    # pure bending to t = pi/2: surface stress E kappa H / 2 with kappa = t / L. The Cauchy
    # stress lambda1 S / lambda2 exceeds E eps by about (1.5 + nu) eps = 2.8 % at the surface
    # (eps = 0.016): 6 %. The outermost 3-point Gauss points lie at (1 + sqrt(3/5)) / 2 of
    # the half-height (2 elements through the thickness)
    theta = np.pi / 2
    result = solve_nonlinear(beam, [Fixed("fixed")], [], steps=4,
                             rigid_faces=[RigidFace("tip", rotation=theta)])
    expected = E_MOD * theta / L * H / 2
    assert result.max_von_mises == pytest.approx(expected, rel=0.06)
    gauss = (1 + np.sqrt(3 / 5)) / 2
    assert result.max_von_mises_element == pytest.approx(gauss * expected, rel=0.06)
    y = result.max_von_mises_location[1]
    assert np.isclose(y, 0.0) or np.isclose(y, H)


def test_large_load_in_one_step_raises_nonconvergence(beam):
    P = 20.0 * EI / L ** 2  # linear tip deflection 6.7 L: one Newton step cannot get there
    with pytest.raises(NonConvergenceError) as info:
        solve_nonlinear(beam, [Fixed("fixed")], [Force("tip", (0.0, -P))], steps=1,
                        max_iterations=6, min_step=1.0)
    error = info.value
    assert isinstance(error, ValueError)
    assert error.load_factor == 0.0 and error.attempted == 1.0
    assert 0 < len(error.residual_history) <= 6
    assert "more steps" in str(error) and "min_step" in str(error)


def test_step_cutting_recovers_where_one_step_fails(beam):
    # alpha = 3 in one step fails (the predictor overshoots); halving it converges
    P = 3.0 * EI / L ** 2
    result = solve_nonlinear(beam, [Fixed("fixed")], [Force("tip", (0.0, -P))], steps=1,
                             max_iterations=8)
    assert result.load_factors[-1] == 1.0
    assert result.info["step_cuts"] >= 1
    assert len(result.load_factors) > 2


def test_bad_arguments_raise_valueerror(beam):
    with pytest.raises(ValueError, match="steps"):
        solve_nonlinear(beam, [Fixed("fixed")], [], steps=0)
    with pytest.raises(ValueError, match="tol"):
        solve_nonlinear(beam, [Fixed("fixed")], [], tol=2.0)
    with pytest.raises(ValueError, match="prescribes rotation"):
        RigidFace("tip", rotation=0.1, moment=1.0)
    with pytest.raises(ValueError, match="force"):
        RigidFace("tip", force=(1.0,))
    with pytest.raises(ValueError, match="one constraint"):
        solve_nonlinear(beam, [Fixed("tip")], [], rigid_faces=[RigidFace("tip", rotation=0.1)])
    with pytest.raises(UnderConstrainedError):
        solve_nonlinear(beam, [], [], rigid_faces=[RigidFace("tip", rotation=0.1)])
    with pytest.raises(UnderConstrainedError):
        solve_nonlinear(beam, [], [Force("tip", (0.0, 1.0))])


def test_rigid_face_alone_can_clamp(beam):
    # a rigid face with every coordinate prescribed is a support: a zero motion is a clamp,
    # and the result equals the Fixed root's for a small load (the root face is rigid in
    # both, up to the Poisson contraction a Fixed root also blocks: to 1e-3)
    P = 1e-4 * 3 * EI / L ** 3
    load = [Force("tip", (0.0, -P))]
    clamp = RigidFace("fixed", rotation=0.0, x=0.0, y=0.0)
    by_face = solve_nonlinear(beam, [], load, steps=1, rigid_faces=[clamp])
    by_fixed = solve_nonlinear(beam, [Fixed("fixed")], load, steps=1)
    a, b = by_face.mean_displacement("tip"), by_fixed.mean_displacement("tip")
    assert a[1] == pytest.approx(b[1], rel=1e-3)
    assert by_face.face_reactions[-1]["fixed"][1] == pytest.approx(P, rel=1e-6)


def test_three_dimensional_small_load_matches_linear():
    m = skfem.MeshHex.init_tensor(np.linspace(0, 0.2, 9), np.linspace(0, 0.02, 2),
                                  np.linspace(0, 0.02, 2))
    mesh = FEMesh(m, {"fixed": facets_where(m, lambda x: np.isclose(x[0], 0.0)),
                      "tip": facets_where(m, lambda x: np.isclose(x[0], 0.2))})
    model = Model(mesh, STEEL, Solid3D(), order=1)
    loads = [Force("tip", (0.0, -10.0, 0.0))]
    linear = solve_static(model, [Fixed("fixed")], loads)
    result = solve_nonlinear(model, [Fixed("fixed")], loads, steps=1)
    delta = np.abs(linear.u).max()
    # relative difference of order delta / L (see the 2-D test)
    assert np.abs(result.u[-1] - linear.u).max() / delta < 10 * delta / 0.2
    amg = solve_nonlinear(model, [Fixed("fixed")], loads, steps=1, solver="amg")
    assert np.allclose(amg.u[-1], result.u[-1], rtol=0, atol=1e-6 * delta)


@pytest.mark.slow
def test_arc_converges_under_refinement():
    # 50 x 2 and 100 x 4 Q2 meshes agree on the quarter-circle moment to 0.05 %, and both
    # are within 2e-4 L of the inextensible arc (centre-line shortening, O(eps^2))
    theta = np.pi / 2
    moments = []
    for nx, ny in ((50, 2), (100, 4)):
        model = Model(beam_mesh(nx, ny), STEEL, PlaneStress(T), order=2)
        result = solve_nonlinear(model, [Fixed("fixed")], [], steps=4,
                                 rigid_faces=[RigidFace("tip", rotation=theta)])
        c = result.face_motion[-1]["tip"]
        assert abs(c[0] - (L * np.sin(theta) / theta - L)) < 2e-4 * L
        assert abs(c[1] - L * (1 - np.cos(theta)) / theta) < 2e-4 * L
        moments.append(result.face_reactions[-1]["tip"][2])
    assert moments[0] == pytest.approx(moments[1], rel=5e-4)
