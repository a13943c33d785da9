"""The free-DOF block of a matrix without its copy (linsolve.Restriction) and the part of it a
factorization reads (linsolve.block_to_factorize) are the block itself."""
import numpy as np
import pytest
import scipy.sparse as sp
from flexfem.fem import linsolve

HAS_PARDISO = linsolve.mkl_pardiso() is not None


def _spd(n=40, seed=0):
    rng = np.random.default_rng(seed)
    B = sp.random(n, n, density=0.1, random_state=rng)
    return (B @ B.T + n * sp.identity(n)).tocsr()


def test_restriction_acts_as_the_block():
    A = _spd()
    I = np.array([0, 3, 4, 7, 10, 11, 20, 39])
    block = A[I][:, I]
    R = linsolve.Restriction(A, I)
    x = np.random.default_rng(1).standard_normal((len(I), 3))
    assert R.shape == block.shape
    assert np.allclose(R @ x[:, 0], block @ x[:, 0], rtol=1e-14, atol=0)
    assert np.allclose(R @ x, block @ x, rtol=1e-14, atol=0)
    assert np.array_equal(R.diagonal(), block.diagonal())
    assert np.isclose(R.norm_inf(), abs(block).sum(axis=1).max(), rtol=1e-15)


@pytest.mark.parametrize("pardiso", [True, False])
def test_block_to_factorize(pardiso, monkeypatch):
    if pardiso and not HAS_PARDISO:
        pytest.skip("MKL (a default dependency on x86-64) not installed")
    if not pardiso:
        monkeypatch.setattr(linsolve, "mkl_pardiso", lambda: None)
    A = _spd()
    I = np.arange(1, 40, 2)
    block = A[I][:, I]
    part = linsolve.block_to_factorize(A, I, "spd")
    # PARDISO reads the upper triangle of a symmetric matrix; SuperLU needs all of it
    expected = sp.triu(block) if pardiso else block
    assert abs(part - expected).max() == 0 and part.nnz == expected.nnz
    assert linsolve._is_upper(part) == pardiso
    assert abs(linsolve.block_to_factorize(A, I, "general") - block).max() == 0


def test_solve_through_a_restriction_equals_the_solve_of_the_block():
    A = _spd(60, seed=2)
    I = np.setdiff1d(np.arange(60), [0, 5, 17])
    b = np.random.default_rng(3).standard_normal(len(I))
    x = linsolve.solve_and_check(linsolve.Restriction(A, I), b, kind="spd",
                                 factor=linsolve.block_to_factorize(A, I, "spd"))
    assert np.allclose(x, np.linalg.solve(A[I][:, I].toarray(), b), rtol=1e-10, atol=0)
