"""Stress tensors at points and as nodal fields, against exact polynomial solutions that the
quadratic elements reproduce exactly (so the tolerances are round-off, not discretisation)."""
import meshio
import numpy as np
import pytest

from meshes import beam_2d, beam_3d
from flexfem.fem import (Model, PlaneStress, Prescribed, Solid3D, facets_where,
                         solve_nonlinear, solve_static)
from flexfem.fem.export import write_result
from flexfem.fem.stress import nonlinear_stress, nonlinear_stress_at

L, H = 1.0, 0.1
KAPPA = 1e-3  # curvature of the pure-bending field (1/m)


def bending_field(nu, dim):
    """Pure bending about z: u = (k x y, -k/2 (x^2 + nu (y^2 - z^2)), -k nu y z); exact
    linear-elastic solution (plane stress in 2-D) with sigma_xx = E k y, all else zero."""
    def ux(p):
        return KAPPA * p[0] * p[1]

    def uy(p):
        z2 = p[2] ** 2 if dim == 3 else 0.0
        return -0.5 * KAPPA * (p[0] ** 2 + nu * (p[1] ** 2 - z2))

    def uz(p):
        return -KAPPA * nu * p[1] * p[2]
    return ux, uy, uz


def bent(steel, mesh, formulation):
    model = Model(mesh, steel, formulation, order=2)
    ux, uy, uz = bending_field(steel.nu, mesh.dim)
    extra = {"z": uz} if mesh.dim == 3 else {}
    supports = [Prescribed(g, x=ux, y=uy, **extra) for g in ("fixed", "tip")]
    return solve_static(model, supports, [])


def interior_points(dim, n=25, seed=1):
    rng = np.random.default_rng(seed)
    pts = rng.uniform(0, 1, (n, dim)) * ([L, H, H][:dim])
    # plus a mesh-independent corner and points on the boundary
    return np.vstack([pts, [[0.0, 0.0, 0.0][:dim], [L, H, H][:dim], [0.5 * L, H, 0.0][:dim]]])


@pytest.mark.parametrize("quads", [False, True])
def test_stress_at_reproduces_pure_bending_2d(steel, quads):
    result = bent(steel, beam_2d(L, H, 0.03, quads=quads), PlaneStress(0.01))
    pts = interior_points(2)
    sig = result.stress_at(pts)
    assert sig.shape == (len(pts), 2, 2)
    scale = steel.E * KAPPA * H  # largest stress, Pa
    exact = steel.E * KAPPA * pts[:, 1]
    # P2 holds the quadratic field exactly: round-off only (cond ~ 1e6 at this mesh)
    assert np.allclose(sig[:, 0, 0], exact, rtol=0, atol=1e-8 * scale)
    assert np.allclose(sig[:, 1, 1], 0.0, atol=1e-8 * scale)
    assert np.allclose(sig[:, 0, 1], 0.0, atol=1e-8 * scale)
    assert np.allclose(sig[:, 0, 1], sig[:, 1, 0], rtol=0, atol=0)
    # the L2 projection onto linear fields holds a linear stress exactly too
    nodal = result.nodal_stress
    assert nodal.shape == (result.model.mesh.mesh.p.shape[1], 2, 2)
    y = result.model.mesh.mesh.p[1]
    assert np.allclose(nodal[:, 0, 0], steel.E * KAPPA * y, rtol=0, atol=1e-8 * scale)
    assert result.stress_at(pts, full=True).shape == (len(pts), 3, 3)


@pytest.mark.parametrize("hexes", [False, True])
def test_stress_at_reproduces_pure_bending_3d(steel, hexes):
    result = bent(steel, beam_3d(L, H, H, 0.05, hexes=hexes), Solid3D())
    pts = interior_points(3)
    sig = result.stress_at(pts)
    scale = steel.E * KAPPA * H
    expected = np.zeros((len(pts), 3, 3))
    expected[:, 0, 0] = steel.E * KAPPA * pts[:, 1]
    assert np.allclose(sig, expected, rtol=0, atol=1e-7 * scale)
    y = result.model.mesh.mesh.p[1]
    assert np.allclose(result.nodal_stress[:, 0, 0], steel.E * KAPPA * y, atol=1e-7 * scale)


def test_a_point_off_the_body_is_named(steel):
    result = bent(steel, beam_2d(L, H, 0.05), PlaneStress(0.01))
    with pytest.raises(ValueError, match=r"points\[1\] = \[1\.5, 0\.05\] m lies in no element"):
        result.stress_at([(0.5, 0.05), (1.5, 0.05)])
    # just outside the edge y = H, by far more than round-off
    with pytest.raises(ValueError, match=r"points\[0\]"):
        result.stress_at([(0.5, H * (1 + 1e-6))])
    with pytest.raises(ValueError, match="points"):
        result.stress_at([(0.5, 0.05, 0.0)])


@pytest.mark.parametrize("suffix", [".vtu", ".xdmf"])
def test_stress_tensor_is_exported(steel, suffix, tmp_path):
    result = bent(steel, beam_2d(L, H, 0.05), PlaneStress(0.01))
    m = meshio.read(write_result(result, tmp_path / f"s{suffix}"))
    tensor = np.asarray(m.point_data["stress"]).reshape(-1, 3, 3)
    assert np.allclose(tensor, result.nodal_stress_full, rtol=1e-12, atol=0)


def test_nonlinear_stresses_of_a_homogeneous_stretch(steel, tmp_path):
    """Uniaxial stretch lambda_x = 1 + e of a St. Venant-Kirchhoff plane-stress strip: the
    deformation is homogeneous (held exactly by P2) with S_yy = 0, so E_yy = -lam* E_xx /
    (lam* + 2 mu), S_xx = (lam* + 2 mu) E_xx + lam* E_yy, sigma_xx = F_xx S_xx / F_yy."""
    mesh = beam_2d(L, H, 0.05)
    mesh = mesh.with_groups({"bottom": facets_where(mesh.mesh, lambda x: np.isclose(x[1], 0.0))})
    model = Model(mesh, steel, PlaneStress(0.01), order=2)
    e = 0.05
    supports = [Prescribed("fixed", x=0.0), Prescribed("bottom", y=0.0),
                Prescribed("tip", x=e * L)]
    result = solve_nonlinear(model, supports, [], steps=2)
    lam, mu = model.lame
    Exx = ((1 + e) ** 2 - 1) / 2
    Eyy = -lam * Exx / (lam + 2 * mu)
    Sxx = (lam + 2 * mu) * Exx + lam * Eyy
    Fyy = np.sqrt(1 + 2 * Eyy)
    cauchy_xx = (1 + e) * Sxx / Fyy
    pts = interior_points(2, n=10)
    at = nonlinear_stress_at(result, pts)
    nodal = nonlinear_stress(result)
    # Newton converged to tol 1e-8 on the residual: stresses to ~1e-7 relative
    for value in (at, nodal):
        assert np.allclose(value["second_piola_kirchhoff"][:, 0, 0], Sxx, rtol=1e-6)
        assert np.allclose(value["cauchy"][:, 0, 0], cauchy_xx, rtol=1e-6)
        assert np.allclose(value["cauchy"][:, 1, 1], 0.0, atol=1e-6 * Sxx)
    assert cauchy_xx > (1 + e) * Sxx  # the two measures differ by more than the tolerance
    for suffix in (".vtu", ".xdmf"):
        m = meshio.read(write_result(result, tmp_path / f"nl{suffix}"))
        written = np.asarray(m.point_data["stress_cauchy"]).reshape(-1, 3, 3)
        assert np.allclose(written[:, 0, 0], cauchy_xx, rtol=1e-6)
        pk2 = np.asarray(m.point_data["stress_second_piola_kirchhoff"]).reshape(-1, 3, 3)
        assert np.allclose(pk2[:, 0, 0], Sxx, rtol=1e-6)
