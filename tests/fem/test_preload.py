"""Verification of preloads in the nonlinear solver (flexfem.fem.preload): a cantilever column
under a constant axial preload P and a scaled lateral tip load H (plane stress, Q2, L/h = 40).
Below the cantilever's Euler load the initial lateral stiffness is the beam-column closed
form; above it the straight column has negative lateral stiffness and arc-length control
traces the path through the limit point of H to the buckled branch, against the elastica."""
import math

import numpy as np
import pytest
import skfem
from scipy.integrate import solve_bvp

from flexfem.fem import (Fixed, Force, Material, Model, PlaneStress, RigidFace, Solid3D,
                         solve_nonlinear)
from flexfem.fem.mesh import FEMesh, facets_where

L, H, T = 1.0, 0.025, 0.01  # m: L / H = 40
E_MOD = 200e9  # Pa
EI = E_MOD * T * H ** 3 / 12  # N m^2
P_EULER = math.pi ** 2 * EI / (4 * L ** 2)  # N: the cantilever's buckling load
STEEL = Material("test steel", E=E_MOD, nu=0.3, rho=7800.0, yield_strength=250e6)


@pytest.fixture(scope="module")
def column():
    m = skfem.MeshQuad.init_tensor(np.linspace(0, L, 41), np.linspace(-H / 2, H / 2, 3))
    groups = {"base": facets_where(m, lambda x: np.isclose(x[0], 0.0)),
              "tip": facets_where(m, lambda x: np.isclose(x[0], L))}
    return Model(FEMesh(m, groups), STEEL, PlaneStress(T), order=2)


def lateral_stiffness(P):
    """Tip lateral stiffness (N/m) of a cantilever under axial compression P (N) below its
    Euler load: (E I / L^3) u^3 / (tan u - u), u = L sqrt(P / E I) (the beam-column tip
    deflection H (tan u - u) / (P k); Timoshenko & Gere, Theory of Elastic Stability, 1961,
    Sec. 1.3); 3 E I / L^3 at P = 0, negative for pi / 2 < u < pi."""
    u = L * math.sqrt(P / EI)
    return EI / L ** 3 * u ** 3 / (math.tan(u) - u)


def elastica_tip_load(P, alpha, guess=None):
    """(H (N), tip deflection (m), solution) of the inextensible elastica of the cantilever
    under the axial compression P and the lateral tip force H at tip rotation alpha (rad):
    E I phi'' = -H cos phi - P sin phi, phi(0) = 0, phi(L) = alpha, phi'(L) = 0, H unknown."""
    s = np.linspace(0, L, 101)
    y, p = ((np.vstack([alpha * s / L, np.full_like(s, alpha / L)]), [0.0]) if guess is None
            else (guess.sol(s), guess.p))
    def rhs(_, y, p):
        return np.vstack([y[1], -(p[0] * np.cos(y[0]) + P * np.sin(y[0])) / EI])

    sol = solve_bvp(rhs, lambda a, b, p: np.array([a[0], b[0] - alpha, b[1]]), s, y, p=p,
                    tol=1e-10)
    assert sol.success
    fine = np.linspace(0, L, 2001)
    return float(sol.p[0]), float(np.trapezoid(np.sin(sol.sol(fine)[0]), fine)), sol


def elastica_limit(P, alphas):
    """(H (N), tip deflection (m)) where H is least along the elastica (P above the Euler
    load), refined by a parabola through the three samples around the least sampled H."""
    guess, samples = None, []
    for alpha in alphas:
        h, d, guess = elastica_tip_load(P, alpha, guess)
        samples.append((h, d))
    h, d = np.array(samples).T
    k = int(np.argmin(h))
    a2, a1, a0 = np.polyfit(alphas[k - 1:k + 2], h[k - 1:k + 2], 2)
    alpha = -a1 / (2 * a2)
    h_min, d_min, _ = elastica_tip_load(P, alpha)
    return h_min, d_min


@pytest.mark.parametrize("ratio", [0.0, 0.5, 0.9])
def test_axial_preload_softens_the_lateral_stiffness_as_the_beam_column(column, ratio):
    # the preload (a nodal Force) is applied first and held; the lateral load is small
    # (tip deflection ~ L / 10^4): its secant stiffness is the initial one. Shear and the
    # clamp's Poisson constraint stiffen the plane-stress column by ~0.2 % (L / h = 40)
    P = ratio * P_EULER
    k = lateral_stiffness(P) if P else 3 * EI / L ** 3
    F = 1e-4 * L * k
    result = solve_nonlinear(column, [Fixed("base")], [Force("tip", (0.0, F))], steps=2,
                             preloads=[Force("tip", (-P, 0.0))] if P else [])
    preloaded = result.mean_displacement("tip", result.preload_end)
    shortening, lateral = -preloaded[0], result.mean_displacement("tip")[1] - preloaded[1]
    assert F / lateral == pytest.approx(k, rel=0.01)
    # the tip carries the held preload and the scaled load (applied loads of a free group)
    assert result.force_displacement("tip")[1][-1] == pytest.approx([-P, F], abs=1e-9 * F)
    assert shortening == pytest.approx(P * L / (E_MOD * H * T), rel=0.01, abs=1e-12)
    assert result.preload_end == (2 if P else 0) and all(result.stable)


def test_arc_length_passes_the_limit_point_of_a_column_preloaded_beyond_buckling(column):
    # P = 1.1 x the Euler load, held; the scaled tip force pulls against the straight
    # column's negative stiffness. The path (rigid tip face, plane sections) starts with the
    # beam-column slope, H reaches a least value (the limit point, a maximum of the load
    # factor) at a tip deflection of ~0.33 L and then falls back towards the buckled state;
    # the column is unstable (one negative eigenvalue) before the limit point, stable after.
    P = 1.1 * P_EULER
    k = lateral_stiffness(P)
    h_lim, d_lim = elastica_limit(P, np.linspace(0.3, 0.8, 11))
    H_full = 2.0 * h_lim  # the load factor peaks at ~0.5
    faces = [RigidFace("tip", force=(0.0, H_full))]
    result = solve_nonlinear(column, [Fixed("base")], [], steps=8, rigid_faces=faces,
                             preloads=[RigidFace("tip", force=(-P, 0.0))], control="arc-length",
                             stop_when=lambda lam, u, faces: faces["tip"][1] > 1.3 * d_lim)
    end = result.preload_end
    lam = result.load_factors[end:]
    dy = np.array([m["tip"][1] for m in result.face_motion[end:]])
    assert result.info["stopped"] and dy[-1] > 1.3 * d_lim
    assert lam[1] * H_full / (dy[1] - dy[0]) == pytest.approx(k, rel=0.02)
    (step, lam_max, kind), = result.info["limit_points"]
    assert kind == "maximum"
    assert lam_max * H_full == pytest.approx(h_lim, rel=0.02)
    assert dy[step - end] == pytest.approx(d_lim, rel=0.1)  # the path is flat there
    negative = result.negative_eigenvalues
    assert negative[end] == 1  # the preloaded straight column is already unstable
    assert all(n == 1 for n in negative[end:step])
    assert all(n == 0 for n in negative[step + 1:])
    # every state of the path against the elastica at the same tip rotation
    for motion, lam_k in zip(result.face_motion[end + 2::3], result.load_factors[end + 2::3]):
        h, d, _ = elastica_tip_load(P, motion["tip"][2])
        assert lam_k * H_full == pytest.approx(h, abs=0.02 * abs(h_lim))


def test_a_3d_dead_moment_preload_is_the_same_total_moment(steel):
    # a 3-D prism with a rigid tip face: a dead moment about y (bending ~30 degrees) held, then
    # a dead moment about z scaled. The end state depends on the total moment only, so it is
    # that of both moments applied together; the preload's load stiffness (a dead moment on a
    # rotating face is not symmetric) keeps Newton quadratic. Measured: rotations equal to
    # 4e-10 rad; 5 iterations a step (13 to 16 without the preload's load stiffness)
    length, b = 0.2, 0.01
    m = skfem.MeshTet.init_tensor(np.linspace(0, length, 11), np.linspace(-b / 2, b / 2, 2),
                                  np.linspace(-b / 2, b / 2, 2))
    mesh = FEMesh(m, {"fixed": facets_where(m, lambda x: np.isclose(x[0], 0.0)),
                      "tip": facets_where(m, lambda x: np.isclose(x[0], length))})
    model = Model(mesh, steel, Solid3D(), order=2)
    M = steel.E * b ** 4 / 12 * (np.pi / 6) / length  # N m: about 30 degrees of bending
    held = solve_nonlinear(model, [Fixed("fixed")], [], steps=3,
                           rigid_faces=[RigidFace("tip", moment=(0.0, 0.0, M))],
                           preloads=[RigidFace("tip", moment=(0.0, M, 0.0))])
    both = solve_nonlinear(model, [Fixed("fixed")], [], steps=6,
                           rigid_faces=[RigidFace("tip", moment=(0.0, M, M))])
    q_held, q_both = held.face_motion[-1]["tip"], both.face_motion[-1]["tip"]
    assert np.abs(q_held[3:]).max() > 0.5  # rad: a large rotation
    assert q_held == pytest.approx(q_both, abs=1e-7 * length)
    assert held.face_reactions[-1]["tip"] == pytest.approx([0, 0, 0, 0, M, M], abs=1e-6 * M)
    assert max(held.iterations) <= 5
