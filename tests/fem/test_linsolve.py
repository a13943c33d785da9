"""Sparse direct factorizations (PARDISO SPD / symmetric / general, SuperLU fallback), their
release, and the solution check that tells ill-conditioned from singular systems."""
import gc

import numpy as np
import pytest
import scipy.sparse as sp
import skfem
from flexfem.fem import pardiso
from flexfem.fem.factor import factor
from flexfem.fem import (
    FEMesh,
    Fixed,
    Force,
    Material,
    Model,
    PlaneStress,
    SingularSystemError,
    facets_where,
    linsolve,
    solve_modes,
    solve_static,
)

HAS_PARDISO = linsolve.mkl_pardiso() is not None
STEEL = Material("steel", E=200e9, nu=0.3, rho=7800.0)


def laplacian(n, neumann=False):
    """1-D finite-difference Laplacian (SPD; singular with ``neumann`` ends)."""
    A = sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(n, n)).tolil()
    if neumann:
        A[0, 0] = A[n - 1, n - 1] = 1.0
    return A.tocsr()


@pytest.fixture(params=["pardiso", "fallback"])
def backend(request, monkeypatch):
    if request.param == "pardiso" and not HAS_PARDISO:
        pytest.skip("MKL (a default dependency on x86-64) not installed")
    if request.param == "fallback":
        monkeypatch.setattr(linsolve, "mkl_pardiso", lambda: None)
    return request.param


@pytest.mark.parametrize("kind", ["spd", "symmetric", "general"])
def test_factorization_solves_many_right_hand_sides(backend, kind):
    n = 500
    A = laplacian(n) + sp.diags(np.linspace(0.0, 1.0, n))  # SPD, diagonal not constant
    if kind == "general":
        A = A + sp.diags([0.3], [1], shape=(n, n))  # non-symmetric
    A = A.tocsr()
    rng = np.random.default_rng(0)
    b, B = rng.standard_normal(n), rng.standard_normal((n, 3))
    with factor(A, kind) as solve:
        assert solve.backend in (("mkl-pardiso",) if backend == "pardiso" else ("cholmod", "superlu"))
        assert solve.backend == linsolve.direct_backend(kind)
        x, X = solve(b), solve(B)
    # cond(A) <= ~4 n^2 / pi^2 + ... = 1e5: backward-stable solves, residual ~ eps cond
    assert np.linalg.norm(A @ x - b) <= 1e-10 * np.linalg.norm(b)
    assert X.shape == (n, 3) and np.linalg.norm(A @ X - B) <= 1e-10 * np.linalg.norm(B)
    assert np.allclose(x, sp.linalg.spsolve(A.tocsc(), b), rtol=1e-8, atol=0)


@pytest.mark.skipif(not HAS_PARDISO, reason="MKL (a default dependency on x86-64) not installed")
def test_pardiso_symmetric_indefinite_and_not_positive_definite():
    A = (laplacian(300) - 0.5 * sp.eye(300)).tocsr()  # eigenvalues 2 - 2 cos(k pi / 301) - 0.5
    b = np.ones(300)
    x = linsolve.solve_direct(A, b, kind="symmetric")
    assert np.linalg.norm(A @ x - b) <= 1e-10 * np.linalg.norm(b)
    with pytest.raises(SingularSystemError, match="zero pivot"):
        linsolve.solve_direct(A, b, kind="spd")  # Cholesky meets a negative pivot


@pytest.mark.skipif(not HAS_PARDISO, reason="MKL (a default dependency on x86-64) not installed")
def test_pardiso_memory_is_released():
    A = laplacian(100)
    solve = factor(A, "spd")
    finalizer = solve._finalizer
    assert finalizer.alive
    solve.free()
    assert not finalizer.alive and not np.any(solve._pt)
    solve.free()  # idempotent
    with pytest.raises(RuntimeError, match="freed"):
        solve(np.ones(100))
    # without free(): released when the object is collected
    solve = factor(A, "spd")
    finalizer = solve._finalizer
    del solve
    gc.collect()
    assert not finalizer.alive


def test_bad_kind_and_shape():
    with pytest.raises(ValueError, match="kind = 'lu'"):
        factor(laplacian(4), "lu")
    with pytest.raises(ValueError, match="square"):
        factor(sp.random(3, 4, density=1.0), "general")


def test_singular_matrix_is_refused(backend):
    # Neumann ends: constants are in the null space, and b (not summing to 0) is not in the range
    A = laplacian(400, neumann=True)
    b = np.linspace(1.0, 2.0, 400)
    with pytest.raises(SingularSystemError):
        linsolve.solve_and_check(A, b, kind="spd")


def _cantilever(length, height, ny):
    mesh = skfem.MeshTri.init_tensor(np.linspace(0, length, int(round(ny * length / height)) + 1),
                                     np.linspace(0, height, ny + 1))
    groups = {"fixed": facets_where(mesh, lambda x: np.isclose(x[0], 0.0)),
              "tip": facets_where(mesh, lambda x: np.isclose(x[0], length))}
    return FEMesh(mesh, groups)


def test_slender_flexure_is_solved_not_refused():
    # L / H = 200 (a leaf-spring flexure): cond(K) ~ 1e10, so the direct solve's residual is
    # ~1e-6 ||f|| (round-off of K u), which the former check (1e-8 ||f||) refused
    length, height, thickness, force = 1.0, 0.005, 0.01, 1.0
    model = Model(_cantilever(length, height, 2), STEEL, PlaneStress(thickness), order=2)
    result = solve_static(model, [Fixed("fixed")], [Force("tip", (0.0, -force))], solver="direct")
    inertia = thickness * height ** 3 / 12
    shear = 5 / 6 * STEEL.E / (2 * (1 + STEEL.nu)) * thickness * height
    timoshenko = force * length ** 3 / (3 * STEEL.E * inertia) + force * length / shear
    # P2 with 2 layers: bending is captured to ~1e-4 here (the end-load's local effects are
    # O(H / L)); 1e-3 leaves room for the tip-face averaging
    assert result.mean_displacement("tip")[1] == pytest.approx(-timoshenko, rel=1e-3)
    # reactions balance the load to the residual of the solve
    assert np.allclose(result.reactions["fixed"], [0.0, force], rtol=0, atol=1e-4 * force)


def test_mechanism_with_a_point_hinge_is_refused():
    # two squares that share one vertex: connected (so no rigid-body part is found) but the
    # right square turns freely about the shared vertex: K is singular
    p = np.array([[0, 1, 1, 0, 2, 2, 1], [0, 0, 1, 1, 1, 2, 2]], dtype=float)
    t = np.array([[0, 1, 2], [0, 2, 3], [2, 4, 5], [2, 5, 6]]).T
    mesh = skfem.MeshTri(p, t)
    groups = {"left": facets_where(mesh, lambda x: np.isclose(x[0], 0.0)),
              "top": facets_where(mesh, lambda x: np.isclose(x[1], 2.0))}
    model = Model(FEMesh(mesh, groups), STEEL, PlaneStress(0.01), order=2)
    with pytest.raises(SingularSystemError):
        solve_static(model, [Fixed("left")], [Force("top", (1.0, 0.0))], solver="direct")


def test_modes_with_a_positive_shift_match_the_default():
    # a shift between f1 and f2 makes K - sigma M indefinite (symmetric factorization); the 4
    # eigenvalues nearest to it are still the 4 lowest
    model = Model(_cantilever(1.0, 0.1, 2), STEEL, PlaneStress(0.01), order=2)
    default = solve_modes(model, 4, [Fixed("fixed")])
    shifted = solve_modes(model, 4, [Fixed("fixed")], shift_hz=1.1 * float(default.frequencies_hz[0]))
    # eigsh tol 1e-10 on the shift-inverted eigenvalues: frequencies agree to ~1e-9
    assert np.allclose(np.sort(shifted.frequencies_hz), default.frequencies_hz, rtol=1e-8)


def test_results_name_their_solver():
    model = Model(_cantilever(1.0, 0.1, 2), STEEL, PlaneStress(0.01), order=2)
    result = solve_static(model, [Fixed("fixed")], [Force("tip", (0.0, -1.0))])
    modes = solve_modes(model, 2, [Fixed("fixed")])
    assert result.solver == linsolve.direct_backend("spd")
    assert modes.solver == linsolve.direct_backend("spd")  # negative shift: Cholesky
    assert result.solver in ("mkl-pardiso", "cholmod", "superlu")
    amg = solve_static(model, [Fixed("fixed")], [Force("tip", (0.0, -1.0))], solver="amg")
    assert amg.solver == "pmg-cg"  # P2: p-multigrid CG


@pytest.mark.skipif(not HAS_PARDISO, reason="MKL (a default dependency on x86-64) not installed")
def test_mkl_is_found_without_pypardiso(monkeypatch):
    """The default install has the mkl wheel but not pypardiso: its runtime library is found
    in the environment directly."""
    import sys
    monkeypatch.setitem(sys.modules, "pypardiso", None)  # import pypardiso -> ImportError
    linsolve.mkl_pardiso.cache_clear()
    try:
        assert any("mkl_rt" in p for p in pardiso.mkl_candidates())
        assert linsolve.mkl_pardiso() is not None
        assert linsolve.direct_backend("symmetric") == "mkl-pardiso"
    finally:
        linsolve.mkl_pardiso.cache_clear()
