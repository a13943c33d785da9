"""The free-DOF block factorized on the matrix's own arrays (fem/block_factor.py) solves the
block's systems, leaves the matrix as it was, and falls back to a copy where it must."""
import numpy as np
import pytest
import scipy.sparse as sp
from flexfem.fem import linsolve
from flexfem.fem.block_factor import BlockFactorization, decouple
from flexfem.fem.symmetric import upper

HAS_PARDISO = linsolve.mkl_pardiso() is not None


def _spd(n=80, seed=0):
    rng = np.random.default_rng(seed)
    B = sp.random(n, n, density=0.08, random_state=rng)
    return (B + B.T + (2 * n) * sp.identity(n)).tocsr()


def test_decoupling_leaves_the_block_and_the_held_diagonal():
    A = _spd()
    U = upper(A)
    I = np.setdiff1d(np.arange(80), [0, 5, 6, 41, 79])
    before = U.copy()
    positions, values = decouple(U, I)
    # what remains is the block A[I][:, I] beside the held DOFs' own diagonal
    held = np.setdiff1d(np.arange(80), I)
    expected = sp.lil_matrix(A.shape)
    expected[np.ix_(I, I)] = A[I][:, I].toarray()
    expected[held, held] = A.diagonal()[held]
    assert np.array_equal(U.toarray(), sp.triu(expected).toarray())
    assert len(positions) == np.count_nonzero(values)  # zeroed only where something was
    U.data[positions] = values
    assert np.array_equal(U.data, before.data)


@pytest.mark.parametrize("kind", ["spd", "symmetric"])
def test_block_solve_matches_the_block_and_restores_the_matrix(kind):
    A = _spd(seed=1)
    U = upper(A)
    original = U.data.copy()
    I = np.setdiff1d(np.arange(80), [2, 3, 17, 60])
    b = np.random.default_rng(2).standard_normal((len(I), 2))
    exact = np.linalg.solve(A[I][:, I].toarray(), b)
    with BlockFactorization(U, I, kind) as solve:
        assert solve._embedded == HAS_PARDISO  # PARDISO: on U's own arrays
        # meanwhile the block as an operator on U is unchanged
        block = linsolve.Restriction(U, I, upper=True)
        assert np.allclose(block @ exact, b, rtol=1e-12, atol=1e-12)
        assert np.allclose(solve(b), exact, rtol=1e-10, atol=1e-12)
        assert np.allclose(solve(b[:, 0]), exact[:, 0], rtol=1e-10, atol=1e-12)
        with pytest.raises(ValueError, match="right-hand side"):
            solve(np.ones(len(I) + 1))
    assert np.array_equal(U.data, original)  # every zeroed entry written back


def test_a_held_row_without_its_diagonal_is_factorized_as_a_copied_block():
    A = _spd(seed=3).tolil()
    A[7, 7] = 0.0  # a held DOF with nothing on its diagonal: decoupling would make A singular
    U = upper(A.tocsr())
    U.eliminate_zeros()
    original = U.copy()
    I = np.setdiff1d(np.arange(80), [7])
    b = np.arange(len(I), dtype=float)
    with BlockFactorization(U, I, "spd") as solve:
        assert not solve._embedded
        x = solve(b)
    A = A.tocsr()
    assert np.allclose(A[I][:, I] @ x, b, rtol=1e-10, atol=1e-8)
    assert abs(U - original).max() == 0


def test_a_failed_factorization_restores_the_matrix():
    A = _spd(seed=4).tolil()
    A[10, :] = 0.0
    A[:, 10] = 0.0
    A[10, 10] = 1.0
    A[11, 11] = -1e6  # indefinite: Cholesky refuses it
    U = upper(A.tocsr())
    original = U.data.copy()
    with pytest.raises(linsolve.SingularSystemError):
        BlockFactorization(U, np.setdiff1d(np.arange(80), [10]), "spd")
    assert np.array_equal(U.data, original)
