"""Convergence orders of P1 and P2 triangles on an exact elasticity solution.

Exact solution: Timoshenko & Goodier, Theory of Elasticity (3rd ed., section 21), the plane-stress
cantilever 0 <= x <= L, -c <= y <= c of unit thickness loaded by a shear force P at x = 0 and
built in at x = L. Its displacement field is a cubic polynomial that satisfies Navier's equations
with zero body force, so prescribing it on the whole boundary (function-valued Prescribed) makes
it the exact solution of the discrete problem's continuous counterpart.
"""
import numpy as np
import pytest
import skfem
from flexfem.fem import (
    FEMesh,
    Model,
    PlaneStress,
    Prescribed,
    gmsh_session,
    mesh_from_gmsh,
    solve_static,
)
from skfem.helpers import ddot

L, C, P = 1.0, 0.25, 1e4  # length (m), half depth (m), end load (N per m of thickness)


def timoshenko_goodier_displacement(x, y, E, nu):
    """(u, v) in m of the end-loaded plane-stress cantilever (T&G eqs. in section 21)."""
    I = 2 * C**3 / 3
    G = E / (2 * (1 + nu))
    u = (-P * x**2 * y / (2 * E * I) - nu * P * y**3 / (6 * E * I) + P * y**3 / (6 * G * I)
         + (P * L**2 / (2 * E * I) - P * C**2 / (2 * G * I)) * y)
    v = (nu * P * x * y**2 / (2 * E * I) + P * x**3 / (6 * E * I) - P * L**2 * x / (2 * E * I)
         + P * L**3 / (3 * E * I))
    return u, v


def timoshenko_goodier_strain(x, y, E, nu):
    """Strain tensor components (eps_xx, eps_yy, eps_xy) of that field, from its stresses
    sigma_xx = -P x y / I, sigma_yy = 0, tau_xy = -P (c^2 - y^2) / (2 I)."""
    I = 2 * C**3 / 3
    G = E / (2 * (1 + nu))
    sxx = -P * x * y / I
    txy = -P * (C**2 - y**2) / (2 * I)
    return sxx / E, -nu * sxx / E, txy / (2 * G)


def coarse_mesh(size):
    with gmsh_session() as gmsh:
        gmsh.model.occ.addRectangle(0, -C, 0, L, 2 * C)
        gmsh.model.occ.synchronize()
        gmsh.option.setNumber("Mesh.MeshSizeMax", size)
        gmsh.model.mesh.generate(2)
        return mesh_from_gmsh(gmsh).mesh


def errors(mesh, material, order):
    """(h, L2 displacement error, energy-norm error), both relative to the exact field's norms."""
    E, nu = material.E, material.nu
    model = Model(FEMesh(mesh, {"boundary": mesh.boundary_facets()}), material, PlaneStress(1.0), order)
    exact = Prescribed("boundary", x=lambda p: timoshenko_goodier_displacement(p[0], p[1], E, nu)[0],
                       y=lambda p: timoshenko_goodier_displacement(p[0], p[1], E, nu)[1])
    u = solve_static(model, [exact], []).u
    lam, mu = model.lame
    basis = skfem.Basis(mesh, model.basis.elem, intorder=2 * order + 4)  # exact for the errors

    @skfem.Functional
    def l2(w):
        ue = timoshenko_goodier_displacement(w.x[0], w.x[1], E, nu)
        return (w["uh"][0] - ue[0]) ** 2 + (w["uh"][1] - ue[1]) ** 2, ue[0] ** 2 + ue[1] ** 2

    def energy(w, error):
        exx, eyy, exy = timoshenko_goodier_strain(w.x[0], w.x[1], E, nu)
        eps = np.array([[exx, exy], [exy, eyy]])
        if error:
            grad = w["uh"].grad
            eps = 0.5 * (grad + np.swapaxes(grad, 0, 1)) - eps
        return 2 * mu * ddot(eps, eps) + lam * (eps[0, 0] + eps[1, 1]) ** 2

    uh = basis.interpolate(u)
    e_l2 = skfem.Functional(lambda w: l2.form(w)[0]).assemble(basis, uh=uh)
    n_l2 = skfem.Functional(lambda w: l2.form(w)[1]).assemble(basis, uh=uh)
    e_en = skfem.Functional(lambda w: energy(w, True)).assemble(basis, uh=uh)
    n_en = skfem.Functional(lambda w: energy(w, False)).assemble(basis, uh=uh)
    h = mesh.params().max()
    return h, np.sqrt(e_l2 / n_l2), np.sqrt(e_en / n_en)


def observed_rates(material, order, levels):
    mesh = coarse_mesh(0.125)
    rows = []
    for _ in range(levels):
        rows.append(errors(mesh, material, order))
        mesh = mesh.refined()
    h, l2, en = np.array(rows).T
    # uniform refinement halves h exactly: rate = log2(e_k / e_k+1)
    return np.log2(l2[:-1] / l2[1:]), np.log2(en[:-1] / en[1:]), l2, en


def test_p1_rates(steel):
    l2_rate, en_rate, l2, en = observed_rates(steel, 1, 4)
    # a priori estimates for a smooth solution: ||e||_L2 ~ h^2, ||e||_energy ~ h (Ciarlet);
    # on the finest pair the pre-asymptotic terms are O(h) smaller: within 0.2
    assert l2_rate[-1] == pytest.approx(2.0, abs=0.2)
    assert en_rate[-1] == pytest.approx(1.0, abs=0.2)
    assert np.all(np.diff(l2) < 0) and np.all(np.diff(en) < 0)


def test_p2_rates(steel):
    l2_rate, en_rate, l2, en = observed_rates(steel, 2, 3)
    # quadratic elements on a cubic solution: L2 ~ h^3, energy ~ h^2
    assert l2_rate[-1] == pytest.approx(3.0, abs=0.2)
    assert en_rate[-1] == pytest.approx(2.0, abs=0.2)
    # and P2 beats P1 by far on the same mesh
    assert en[0] < 0.5 * observed_rates(steel, 1, 1)[3][0]


def test_prescribed_quadratic_field_is_reproduced_exactly(steel):
    """A field in the P2 space with zero divergence of stress is reproduced to round-off."""
    mesh = coarse_mesh(0.25)
    model = Model(FEMesh(mesh, {"boundary": mesh.boundary_facets()}), steel, PlaneStress(1.0), 2)
    # u = (x y, -x^2/2 - nu y^2/2): pure bending, sigma_xx = E y constant in x: div sigma = 0
    nu = steel.nu
    field = Prescribed("boundary", x=lambda p: p[0] * p[1], y=lambda p: -(p[0] ** 2 + nu * p[1] ** 2) / 2)
    u = solve_static(model, [field], []).u
    x, y = model.basis.doflocs
    ux, uy = model.basis.split_indices()
    assert np.allclose(u[ux], (x * y)[ux], atol=1e-12)
    assert np.allclose(u[uy], (-(x**2 + nu * y**2) / 2)[uy], atol=1e-12)


@pytest.mark.slow
@pytest.mark.parametrize("order, levels", [(1, 6), (2, 5)])
def test_rates_in_the_asymptotic_range(steel, order, levels):
    l2_rate, en_rate, _, _ = observed_rates(steel, order, levels)
    # two more refinements: the O(h) pre-asymptotic part shrinks 4x, the rates are within 0.05
    assert l2_rate[-1] == pytest.approx(order + 1, abs=0.05)
    assert en_rate[-1] == pytest.approx(order, abs=0.05)
