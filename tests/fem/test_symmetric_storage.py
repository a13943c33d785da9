"""The stiffness and mass kept as their upper triangles (fem/symmetric.py, Model.stiffness_upper,
Model.mass_upper) act as the full symmetric matrices, and the solves that read them give the
results of the full matrices."""
import numpy as np
import pytest
import scipy.sparse as sp
import skfem
from flexfem.fem import FEMesh, Fixed, Material, Model, Solid3D, facets_where, linsolve, solve_modes
from flexfem.fem.assembly import elasticity_stiffness
from flexfem.fem.factor import factor
from flexfem.fem.model import scalar_element
from flexfem.fem.symmetric import symmetric_from_upper, symmetric_matvec, upper

HAS_PARDISO = linsolve.mkl_pardiso() is not None
STEEL = Material("steel", E=200e9, nu=0.3, rho=7800.0)


def _symmetric(n=50, seed=0):
    rng = np.random.default_rng(seed)
    B = sp.random(n, n, density=0.1, random_state=rng)
    return (B + B.T + sp.diags(rng.standard_normal(n))).tocsr()


def test_full_matrix_and_products_from_the_upper_triangle():
    A = _symmetric()
    U = upper(A)
    assert linsolve._is_upper(U)
    assert abs(symmetric_from_upper(U) - A).max() == 0
    x = np.random.default_rng(1).standard_normal((50, 3))
    assert np.allclose(symmetric_matvec(U, x[:, 0]), A @ x[:, 0], rtol=1e-14, atol=1e-14)
    assert np.allclose(symmetric_matvec(U, x), A @ x, rtol=1e-14, atol=1e-14)


def test_restriction_of_an_upper_triangle_acts_as_the_block():
    A = _symmetric(seed=2)
    I = np.array([0, 3, 4, 7, 10, 11, 20, 49])
    block = A[I][:, I]
    R = linsolve.Restriction(upper(A), I, upper=True)
    x = np.random.default_rng(3).standard_normal((len(I), 2))
    assert np.allclose(R @ x, block @ x, rtol=1e-14, atol=1e-14)
    assert np.allclose(R.H @ x[:, 0], block.T @ x[:, 0], rtol=1e-14, atol=1e-14)
    assert np.array_equal(R.diagonal(), block.diagonal())
    assert np.isclose(R.norm_inf(), abs(block).sum(axis=1).max(), rtol=1e-14)
    for kind in ("spd", "general"):  # what a factorization reads: the upper block, or all
        part = linsolve.block_to_factorize(upper(A), I, kind, upper=True)
        expected = sp.triu(block) if kind == "spd" and HAS_PARDISO else block
        assert abs(part - expected).max() == 0


def _bar(n=4):
    mesh = skfem.MeshTet.init_tensor(np.linspace(0, 0.1, 2 * n + 1), np.linspace(0, 0.01, 3),
                                     np.linspace(0, 0.01, 3))
    groups = {"fixed": facets_where(mesh, lambda x: np.isclose(x[0], 0.0))}
    return Model(FEMesh(mesh, groups), STEEL, Solid3D(), order=2)


def test_model_keeps_the_upper_triangles_of_the_assembled_matrices():
    model = _bar()
    lam, mu = model.lame
    K = elasticity_stiffness(model.mesh.mesh, scalar_element(model.mesh.mesh, 2),
                             model.stiffness_quadrature, model.node_pattern, 3, lam, mu, 1.0)
    # the assembled K is symmetric to round-off; the model's is its upper triangle mirrored
    assert abs(model.stiffness - K).max() <= 1e-12 * abs(K).max()
    assert abs(model.stiffness_upper - sp.triu(K)).max() == 0
    assert abs(model.stiffness - model.stiffness.T).max() == 0
    assert abs(symmetric_from_upper(model.mass_upper) - model.mass).max() == 0


def test_with_stiffness_refuses_a_non_symmetric_extra():
    model = _bar(2)
    extra = sp.lil_matrix((model.n_dofs, model.n_dofs))
    extra[0, 1] = 1e3
    with pytest.raises(ValueError, match="symmetric"):
        model.with_stiffness(extra.tocsr())
    extra[1, 0] = 1e3
    sprung = model.with_stiffness(extra.tocsr())
    assert abs(sprung.stiffness - model.stiffness - extra).max() <= 1e-9


def test_modes_without_a_kept_stiffness_do_not_keep_it_and_are_the_same():
    fresh, kept = _bar(), _bar()
    kept.stiffness_upper
    a = solve_modes(fresh, 4, [Fixed("fixed")])
    b = solve_modes(kept, 4, [Fixed("fixed")])
    assert "stiffness_upper" not in fresh.__dict__  # assembled for the solve, then dropped
    assert np.allclose(a.frequencies_hz, b.frequencies_hz, rtol=1e-12, atol=0)
    # the first bending mode of the clamped bar against Euler-Bernoulli: 3.516 sqrt(EI/(rho A))/L^2
    h, L = 0.01, 0.1
    f1 = 3.5160 / (2 * np.pi * L**2) * np.sqrt(STEEL.E * h**2 / 12 / STEEL.rho)
    assert a.frequencies_hz[0] == pytest.approx(f1, rel=0.02)


@pytest.mark.skipif(not HAS_PARDISO, reason="MKL (a default dependency on x86-64) not installed")
def test_spd_factorization_solves_after_dropping_the_matrix():
    A = (_symmetric(60, seed=4) + 20 * sp.identity(60)).tocsr()
    b = np.arange(60.0)
    with factor(A, "spd") as solve:
        dropped = len(solve._data) == 1  # the matrix dropped, where PARDISO does not read it
        assert dropped == (not linsolve._spd_solve_reads_matrix())
        assert np.allclose(solve(b), np.linalg.solve(A.toarray(), b), rtol=1e-10, atol=0)
