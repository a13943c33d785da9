"""Verification of arc-length continuation (flexfem.fem.arclength): snap-through of the
two-bar von Mises truss, one bar modelled (symmetry) as a plane-stress Q2 strip pinned at
both ends by rigid faces, against the analytic load-deflection curve."""
import numpy as np
import pytest
import skfem
from scipy.optimize import brentq

from flexfem.fem import Material, Model, PlaneStress, RigidFace, solve_nonlinear
from flexfem.fem.mesh import FEMesh, facets_where

E_MOD, T = 200e9, 0.01
STEEL = Material("test steel", E=E_MOD, nu=0.3, rho=7800.0, yield_strength=250e6)
A_HALF, RISE = 1.0, 0.1  # m: half span and rise of the truss (shallow)
L0 = np.hypot(A_HALF, RISE)
H = L0 / 8  # stocky bar: its Euler strain pi^2 H^2 / (12 L0^2) = 1.3 % exceeds the largest
# compressive strain of the snap, RISE^2 / (2 L0^2) = 0.5 %, so the bar snaps, not buckles
EA = E_MOD * H * T


def truss_force(w):
    """Vertical load (N) on one bar's apex at deflection w (m): with stretch s = l / L0, the
    plane-stress St. Venant-Kirchhoff bar force is EA s (s^2 - 1) / 2 (exact in uniaxial
    stress), so P = EA (h - w) (2 h w - w^2) / (2 L0^3); limit load EA h^3 / (3 sqrt(3) L0^3)
    at w = h (1 -+ 1 / sqrt(3))."""
    return EA * (RISE - w) * (2 * RISE * w - w ** 2) / (2 * L0 ** 3)


@pytest.fixture(scope="module")
def bar():
    m0 = skfem.MeshQuad.init_tensor(np.linspace(0, L0, 9), np.linspace(-H / 2, H / 2, 3))
    groups = {"base": facets_where(m0, lambda x: np.isclose(x[0], 0.0)),
              "apex": facets_where(m0, lambda x: np.isclose(x[0], L0))}
    angle = np.arctan2(RISE, A_HALF)
    R = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    return Model(FEMesh(skfem.MeshQuad(R @ m0.p, m0.t), groups), STEEL, PlaneStress(T), order=2)


def test_arc_length_follows_the_snap_through_of_the_von_mises_truss(bar):
    # the load (1.5 x the limit load) is reached only after the snap: arc length follows the
    # path over the maximum and the minimum (-limit load). The rigid end faces block the
    # Poisson contraction at the bar's ends, stiffening it by ~0.35 % (measured): 1 % of
    # max(|P|, P_lim) allowed along the path; the sampled extremes lie below the true ones
    # by ~1.1 (dw / h)^2 = 0.25 % at this arc length: 1 % allowed on the limit loads
    P_lim = EA * RISE ** 3 / (3 * np.sqrt(3) * L0 ** 3)
    P = 1.5 * P_lim
    faces = [RigidFace("base", x=0.0, y=0.0), RigidFace("apex", x=0.0, force=(0.0, -P))]
    result = solve_nonlinear(bar, [], [], steps=6, rigid_faces=faces, control="arc-length")
    w = np.array([-motion["apex"][1] for motion in result.face_motion])
    load = result.load_factors * P
    assert result.load_factors[-1] == 1.0 and w[-1] > 2 * RISE  # snapped through
    assert np.all(np.abs(load - truss_force(w)) <= 0.01 * np.maximum(P_lim, np.abs(load)))
    (k1, lam1, kind1), (k2, lam2, kind2) = result.info["limit_points"]
    assert (kind1, kind2) == ("maximum", "minimum")
    assert lam1 * P == pytest.approx(P_lim, rel=0.01)
    assert lam2 * P == pytest.approx(-P_lim, rel=0.01)
    # between the limit points the equilibrium is unstable (one negative eigenvalue)
    assert all(n == 1 for n in result.negative_eigenvalues[k1 + 1:k2])
    assert all(n == 0 for n in result.negative_eigenvalues[:k1] + result.negative_eigenvalues[k2 + 1:])
    assert w[k1] == pytest.approx(RISE * (1 - 1 / np.sqrt(3)), abs=0.05 * RISE)


def test_unknown_control_is_refused(bar):
    with pytest.raises(ValueError, match="control"):
        solve_nonlinear(bar, [], [], rigid_faces=[RigidFace("base", x=0.0, y=0.0)], control="arc")


def test_a_preload_shifts_the_snap_through_path_by_its_own_load(bar):
    # a constant downward preload P_d on the apex, then the scaled load lambda P: the truss
    # carries P_d + lambda P = truss_force(w), so the limit points move to lambda = (+-P_lim
    # - P_d) / P at the same deflections; the preload stage (load control) ends on the
    # first branch at truss_force(w) = P_d. Tolerances as in the test above.
    P_lim = EA * RISE ** 3 / (3 * np.sqrt(3) * L0 ** 3)
    P_d, P = 0.5 * P_lim, 1.5 * P_lim
    faces = [RigidFace("base", x=0.0, y=0.0), RigidFace("apex", x=0.0, force=(0.0, -P))]
    result = solve_nonlinear(bar, [], [], steps=6, rigid_faces=faces, control="arc-length",
                             preloads=[RigidFace("apex", force=(0.0, -P_d))], preload_steps=2)
    w = np.array([-motion["apex"][1] for motion in result.face_motion])
    end = result.preload_end
    assert end == 2 and list(result.preloading) == [False, True, True] + [False] * (len(w) - 3)
    assert np.all(result.load_factors[:end + 1] == 0.0)
    assert list(result.preload_factors[:end + 1]) == [0.0, 0.5, 1.0]
    assert np.all(result.preload_factors[end:] == 1.0)
    w_d = brentq(lambda x: truss_force(x) - P_d, 0.0, RISE * (1 - 1 / np.sqrt(3)))
    assert w[end] == pytest.approx(w_d, rel=0.01)
    load = P_d + result.load_factors[end:] * P
    assert np.all(np.abs(load - truss_force(w[end:])) <= 0.01 * np.maximum(P_lim, np.abs(load)))
    (k1, lam1, kind1), (k2, lam2, kind2) = result.info["limit_points"]
    assert (kind1, kind2) == ("maximum", "minimum") and end < k1 < k2
    assert lam1 == pytest.approx((P_lim - P_d) / P, abs=0.01 * P_lim / P)
    assert lam2 == pytest.approx((-P_lim - P_d) / P, abs=0.01 * P_lim / P)
    assert result.load_factors[-1] == 1.0 and w[-1] > 2 * RISE
    negative = result.negative_eigenvalues
    assert all(n == 1 for n in negative[k1 + 1:k2])
    assert all(n == 0 for n in negative[:k1] + negative[k2 + 1:])
    # the apex face carries the preload and the scaled load together
    F_y = np.array([f["apex"][1] for f in result.face_reactions])
    assert F_y == pytest.approx(-(result.preload_factors * P_d + result.load_factors * P),
                                rel=1e-6, abs=1e-9 * P)


def test_bad_preloads_are_refused(bar):
    faces = [RigidFace("base", x=0.0, y=0.0), RigidFace("apex", x=0.0)]
    for preload, match in ((RigidFace("apex", y=0.0), "prescribes a coordinate"),
                           (RigidFace("tip", force=(0.0, 1.0)), "names no face"),
                           (RigidFace("apex", force=(1.0, 0.0)), "loads a coordinate"),
                           ("gravity", "unknown load")):
        with pytest.raises(ValueError, match=match):
            solve_nonlinear(bar, [], [], rigid_faces=faces, preloads=[preload])
    with pytest.raises(ValueError, match="preload_steps"):
        solve_nonlinear(bar, [], [], rigid_faces=faces, preload_steps=0)
