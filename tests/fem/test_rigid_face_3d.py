"""Rigid faces in 3-D (flexfem.fem.rigid_face, rigid_face3d): a square prism b x b x L
(L / b = 20) clamped at x = 0 with a rigid tip face, against Euler-Bernoulli / Timoshenko
beam theory and Saint-Venant torsion (J = 0.1406 b^4 for a square: Timoshenko & Goodier,
Theory of Elasticity, the torsion of rectangular bars), the circular arc of pure bending,
and finite differences. Linear: Q2 hexahedra; nonlinear: P2 tetrahedra (six to a brick),
whose tangent assembles 20 times faster."""
import numpy as np
import pytest
import skfem
from scipy.spatial.transform import Rotation

from flexfem.fem import (Fixed, Material, Model, PlaneStress, RigidFace, Solid3D,
                         UnderConstrainedError, solve_nonlinear, solve_static)
from flexfem.fem.boundary import constrained_dofs
from flexfem.fem.compliance import compliance_matrix
from flexfem.fem.mesh import FEMesh, facets_where
from flexfem.fem.rigid_face import ReducedSpace
from flexfem.fem.rigid_face3d import rotation_derivatives

E_MOD, NU = 200e9, 0.3
STEEL = Material("test steel", E=E_MOD, nu=NU, rho=7800.0, yield_strength=250e6)
L, B = 0.2, 0.01
EI, G, A = E_MOD * B ** 4 / 12, E_MOD / (2 * (1 + NU)), B * B
GJ = G * 0.1406 * B ** 4


def prism(nx, n, cell):
    """Prism [0, L] x [-B/2, B/2]^2 of nx x n x n bricks (MeshHex) or 6 tets each (MeshTet);
    groups fixed (x = 0) and tip (x = L), tip centroid (L, 0, 0)."""
    m = cell.init_tensor(np.linspace(0, L, nx + 1), np.linspace(-B / 2, B / 2, n + 1),
                         np.linspace(-B / 2, B / 2, n + 1))
    mesh = FEMesh(m, {"fixed": facets_where(m, lambda x: np.isclose(x[0], 0.0)),
                      "tip": facets_where(m, lambda x: np.isclose(x[0], L))})
    return Model(mesh, STEEL, Solid3D(), order=2)


@pytest.fixture(scope="module")
def hexes():
    return prism(40, 2, skfem.MeshHex)


@pytest.fixture(scope="module")
def tets():
    return prism(20, 2, skfem.MeshTet)


def tip(model, face):
    result = solve_static(model, [Fixed("fixed")], [], rigid_faces=[face])
    return result.face_motion["tip"], result.face_reactions["tip"]


def test_linear_tip_loads_are_beam_theory(hexes):
    # Timoshenko deflection F (L^3/3EI + L/(kappa G A)), end rotation F L^2/2EI (the coupling
    # term), bending M L/EI with deflection M L^2/2EI, torsion M L/GJ. The clamp's and the
    # face's restraint of Poisson contraction and warping stiffen the bar by O(b / L):
    # measured -0.3 % to -0.6 %, torsion -1.6 % (1 % and 2.5 % allowed, as the compliance)
    F, M = 10.0, 2.0
    bend = L ** 3 / (3 * EI) + L / (5 / 6 * G * A)
    q, r = tip(hexes, RigidFace("tip", force=(0.0, F, 0.0)))
    assert q[[1, 5]] == pytest.approx([F * bend, F * L ** 2 / (2 * EI)], rel=0.01)
    q, r = tip(hexes, RigidFace("tip", force=(0.0, 0.0, F)))
    assert q[[2, 4]] == pytest.approx([F * bend, -F * L ** 2 / (2 * EI)], rel=0.01)
    assert r == pytest.approx([0.0, 0.0, F, 0.0, 0.0, 0.0], abs=1e-9 * F)
    q, r = tip(hexes, RigidFace("tip", moment=(M, 0.0, 0.0)))
    assert q[3] == pytest.approx(M * L / GJ, rel=0.025)
    assert np.abs(q[[0, 1, 2, 4, 5]]).max() < 1e-6 * q[3] * L
    q, r = tip(hexes, RigidFace("tip", moment=(0.0, M, 0.0)))
    assert q[[4, 2]] == pytest.approx([M * L / EI, -M * L ** 2 / (2 * EI)], rel=0.01)
    q, r = tip(hexes, RigidFace("tip", moment=(0.0, 0.0, M)))
    assert q[[5, 1]] == pytest.approx([M * L / EI, M * L ** 2 / (2 * EI)], rel=0.01)
    assert r == pytest.approx([0.0, 0.0, 0.0, 0.0, 0.0, M], abs=1e-9 * M)


def test_linear_prescribed_rotation_takes_the_bending_moment(hexes):
    # rotation theta about z held, translations free: pure bending, reaction M = EI theta / L
    # and tip deflection theta L / 2; the other rotations held at 0 take no moment
    theta = 0.01
    q, r = tip(hexes, RigidFace("tip", rotation=(0.0, 0.0, theta)))
    assert r[5] == pytest.approx(EI * theta / L, rel=0.01)
    assert q[1] == pytest.approx(theta * L / 2, rel=0.01)
    assert np.abs(r[:5]).max() < 1e-6 * r[5]
    # about y, with the rotation about x free: the same, bending the other way
    q, r = tip(hexes, RigidFace("tip", rotation=(None, theta, 0.0)))
    assert r[4] == pytest.approx(EI * theta / L, rel=0.01)
    assert q[2] == pytest.approx(-theta * L / 2, rel=0.01)


def test_linear_rigid_face_is_the_compliance_matrix(hexes):
    loads = np.array([3.0, -2.0, 5.0, 0.4, -0.7, 0.9])
    q, r = tip(hexes, RigidFace("tip", force=loads[:3], moment=loads[3:]))
    c = compliance_matrix(hexes, [Fixed("fixed")], "tip")
    assert q == pytest.approx(c.matrix @ loads, rel=1e-8, abs=1e-12)
    assert r == pytest.approx(loads, rel=1e-9)


def test_rotation_derivatives_and_reduced_tangent_are_exact():
    # R(psi) against scipy's rotation; dR, d2R against central differences (h = 1e-6);
    # the face's Jacobian du/dz and the geometric + load-stiffness term against central
    # differences of u(z) and of T(z)^T r - g(z) (r held): what makes Newton quadratic
    rng = np.random.default_rng(0)
    for psi in (np.zeros(3), np.array([1e-7, 0.0, 0.0]), rng.normal(size=3), np.array([0.0, 0.0, 3.0])):
        R, dR, d2R = rotation_derivatives(psi)
        assert np.allclose(R, Rotation.from_rotvec(psi).as_matrix(), atol=1e-14)
        for j, e in enumerate(np.eye(3) * 1e-6):
            plus, minus = rotation_derivatives(psi + e), rotation_derivatives(psi - e)
            assert np.allclose((plus[0] - minus[0]) / 2e-6, dR[j], atol=1e-9)
            assert np.allclose((plus[1] - minus[1]) / 2e-6, d2R[:, j], atol=1e-9)
    model = prism(2, 1, skfem.MeshTet)
    D, xD, _ = constrained_dofs(model, [Fixed("fixed")])
    face = RigidFace("tip", rotation=(None, 0.4, None), force=(1.0, 2.0, -3.0), moment=(5.0, 0.0, -7.0))
    space = ReducedSpace(model, D, xD, [face])
    assert not space.symmetric
    z = rng.normal(size=space.n) * 1e-3
    z[space.slots[0][-2:]] = np.array([0.9, -1.3]) * space.faces[0].ell
    r, lam, h = rng.normal(size=model.n_dofs), 0.7, 1e-7 * space.faces[0].ell
    K = space.geometric_matrix(z, lam, r).toarray()
    T = space.jacobian(z, lam).toarray()
    for k in space.slots[0]:
        e = np.zeros(space.n)
        e[k] = h
        du = (space.displacement(z + e, lam) - space.displacement(z - e, lam)) / (2 * h)
        assert np.abs(du - T[:, k]).max() < 1e-7
        res = [space.jacobian(w, lam).T @ r - space.applied(lam, w) for w in (z + e, z - e)]
        assert np.abs((res[0] - res[1]) / (2 * h) - K[:, k]).max() < 1e-6 * np.abs(K).max()


def test_nonlinear_end_moment_bends_the_prism_into_an_arc(tets):
    # dead moment M = EI theta / L about n = (0, 1, 1)/sqrt 2 (the square's bending is
    # isotropic): the prism rolls into an arc of radius R = L / theta in the plane normal to
    # n, the face's rotation vector theta n, the tip at R sin(theta) e_x + R (1 - cos theta)
    # (n x e_x). Up to 90 degrees; this mesh's bending is 0.6 % stiff (see the linear test),
    # measured: rotation -0.55 % at 15 degrees to -0.24 % at 90, its axis within 2.5e-4 of
    # n, tip within 1.5e-3 L (1 % and 0.3 % L allowed); the face moment is the applied one
    n = np.array([0.0, 1.0, 1.0]) / np.sqrt(2.0)
    theta = np.pi / 2
    face = RigidFace("tip", moment=tuple(EI * theta / L * n))
    result = solve_nonlinear(tets, [Fixed("fixed")], [], steps=6, rigid_faces=[face])
    for lam, motion, force in zip(result.load_factors[1:], result.face_motion[1:],
                                  result.face_reactions[1:]):
        motion, force = motion["tip"], force["tip"]
        angle = lam * theta
        assert motion[3:] == pytest.approx(angle * n, rel=0.01, abs=0.01 * angle)
        R = L / angle
        arc = R * np.sin(angle) * np.eye(3)[0] + R * (1 - np.cos(angle)) * np.cross(n, np.eye(3)[0])
        assert np.abs(motion[:3] - (arc - L * np.eye(3)[0])).max() < 3e-3 * L
        assert force == pytest.approx(np.concatenate([np.zeros(3), lam * EI * theta / L * n]),
                                      abs=1e-6 * EI * theta / L)
    assert result.stable.all()
    displacement, force = result.force_displacement("tip")  # the face's (3,) force per step
    assert displacement.shape == force.shape == (7, 3)
    assert np.abs(force).max() < 1e-6 * EI / L ** 2


def test_arc_length_with_a_dead_face_moment_follows_the_arc(tets):
    # the same dead moment traced by arc-length (its tangent is not symmetric: general
    # factorisation): every state on the analytic path, rotation = load factor x theta n
    n = np.array([0.0, 1.0, 1.0]) / np.sqrt(2.0)
    theta = np.pi / 4
    face = RigidFace("tip", moment=tuple(EI * theta / L * n))
    result = solve_nonlinear(tets, [Fixed("fixed")], [], steps=4, rigid_faces=[face],
                             control="arc-length")
    assert result.load_factors[-1] == pytest.approx(1.0)
    assert len(result.load_factors) > 2 and not result.info["limit_points"]
    for lam, motion in zip(result.load_factors[1:], result.face_motion[1:]):
        assert motion["tip"][3:] == pytest.approx(lam * theta * n, rel=0.01, abs=0.01 * lam * theta)


@pytest.mark.slow
def test_nonlinear_prescribed_rotation_half_turn(tets):
    # rotation theta about z held (8 steps to 180 degrees), translations free: reaction
    # M = EI theta / L, tip on the arc. Measured on 20 elements (each 9 degrees of arc at
    # the end): moment +0.56 % at 22.5 degrees to -0.46 % at 180, tip within 5.1e-3 L (the
    # deflection at 180; see docs/verification.md for the finer mesh): 1 % and 1 % L allowed
    theta = np.pi
    result = solve_nonlinear(tets, [Fixed("fixed")], [], steps=8,
                             rigid_faces=[RigidFace("tip", rotation=(0.0, 0.0, theta))])
    for lam, motion, force in zip(result.load_factors[1:], result.face_motion[1:],
                                  result.face_reactions[1:]):
        motion, force = motion["tip"], force["tip"]
        angle = lam * theta
        arc = L / angle * np.array([np.sin(angle) - angle, 1 - np.cos(angle), 0.0])
        assert np.abs(motion[:3] - arc).max() < 1e-2 * L
        assert force[5] == pytest.approx(EI * angle / L, rel=0.01)


def test_nonlinear_torsion_to_a_quarter_turn(tets):
    # rotation phi about the axis held, 4 steps to 90 degrees (shear strain 5 %, principal
    # Green-Lagrange strain 2.7 %): the torque stays GJ phi / L (the Wagner term, E/2
    # (b^6/90) (phi/L)^3, adds 6e-4) against this mesh's small-angle torque (1 % allowed),
    # and the small-angle torque is Saint-Venant's (P2 tets, 2 x 2 across: +4.1 % measured,
    # 5 % allowed; Q2 hexahedra +1.6 %, see the linear test). Measured: +1e-6 at 22.5
    # degrees to +1.8e-5 at 90, the other moments below 3e-4 of the torque
    phi = np.pi / 2
    q, r = tip(tets, RigidFace("tip", rotation=(1e-3, 0.0, 0.0)))
    stiffness = r[3] / 1e-3
    assert stiffness == pytest.approx(GJ / L, rel=0.05)
    result = solve_nonlinear(tets, [Fixed("fixed")], [], steps=4,
                             rigid_faces=[RigidFace("tip", rotation=(phi, 0.0, 0.0))])
    for lam, force in zip(result.load_factors[1:], result.face_reactions[1:]):
        force = force["tip"]
        assert force[3] == pytest.approx(stiffness * lam * phi, rel=0.01)
        assert np.abs(force[[4, 5]]).max() < 1e-3 * force[3]
    assert result.strain_valid.all()


@pytest.mark.slow
def test_tangent_compliance_at_a_bent_state_is_the_nonlinear_solve():
    # state: dead moment bending the prism by 60 degrees about z plus a force along z; the
    # 6 x 6 tangent compliance there against forward differences of solve_nonlinear with each
    # load component raised by 1e-4 of its scale (force EI/L^2, moment EI/L); rotations
    # compared as the spatial rotation vector of R_new R_old^T. Measured: 1.8e-5 of the largest
    # entry (in units of L^2/EI, L/EI, 1/EI); 2e-4 allowed. The dead moment's load stiffness
    # makes the matrix strongly non-symmetric here (C[3, 4] = -0.46, C[4, 3] = +0.87 L/EI),
    # and the differences agree with it
    model = prism(10, 2, skfem.MeshTet)
    M, F = EI * (np.pi / 3) / L, 0.3 * EI / L ** 2
    loads = np.array([0.0, 0.0, F, 0.0, 0.0, M])

    def solve(loads):
        face = RigidFace("tip", force=tuple(loads[:3]), moment=tuple(loads[3:]))
        return solve_nonlinear(model, [Fixed("fixed")], [], steps=4, tol=1e-11,
                               rigid_faces=[face], check_stability=False)

    state = solve(loads)
    c = compliance_matrix(model, [Fixed("fixed")], "tip", state=state).matrix
    q0 = state.face_motion[-1]["tip"]
    scale = np.array([EI / L ** 2] * 3 + [EI / L] * 3)
    fd = np.zeros((6, 6))
    for j in range(6):
        step = np.zeros(6)
        step[j] = 1e-4 * scale[j]
        q = solve(loads + step).face_motion[-1]["tip"]
        turn = Rotation.from_rotvec(q[3:]) * Rotation.from_rotvec(q0[3:]).inv()
        fd[:, j] = np.concatenate([q[:3] - q0[:3], turn.as_rotvec()]) / step[j]
    units = np.concatenate([np.full(3, L), np.ones(3)])[:, None] / scale[None, :]  # m / N, ...
    assert np.abs((c - fd) / units).max() < 2e-4 * np.abs(c / units).max()


def test_bad_faces_name_the_problem(hexes):
    plate = FEMesh(skfem.MeshQuad.init_tensor(np.linspace(0, 1, 3), np.linspace(0, 0.1, 2)), {})
    plate = plate.with_groups(boundaries={"fixed": facets_where(plate.mesh, lambda x: x[0] < 1e-9),
                                          "tip": facets_where(plate.mesh, lambda x: x[0] > 1 - 1e-9)})
    flat = Model(plate, STEEL, PlaneStress(0.01), order=2)
    with pytest.raises(ValueError, match=r"force = \(1.0, 0.0\) is 2-D input; a 3-D face takes"):
        solve_static(hexes, [Fixed("fixed")], [], rigid_faces=[RigidFace("tip", force=(1.0, 0.0))])
    with pytest.raises(ValueError, match="rotation = 0.1 is 2-D input"):
        solve_nonlinear(hexes, [Fixed("fixed")], [], rigid_faces=[RigidFace("tip", rotation=0.1)])
    with pytest.raises(ValueError, match="is on a 2-D model but its rotation"):
        solve_static(flat, [Fixed("fixed")], [], rigid_faces=[RigidFace("tip", rotation=(0, 0, 1))])
    with pytest.raises(ValueError, match="mixes 2-D and 3-D"):
        RigidFace("tip", rotation=(0.0, 0.0, 1.0), force=(1.0, 0.0))
    with pytest.raises(ValueError, match="rotation.*has 2 components"):
        RigidFace("tip", rotation=(0.0, 1.0))
    with pytest.raises(ValueError, match="moment"):
        RigidFace("tip", moment=(1.0, float("nan"), 0.0))
    with pytest.raises(ValueError, match="prescribes rotation_z and applies a load"):
        RigidFace("tip", rotation=(None, None, 0.1), moment=(0.0, 0.0, 1.0))
    with pytest.raises(UnderConstrainedError, match="of 6 rigid-body modes"):
        solve_static(hexes, [], [], rigid_faces=[RigidFace("tip", force=(0.0, 1.0, 0.0))])
    # a face that fits both: x held, all else free and unloaded
    assert RigidFace("tip", x=0.0).dim is None
