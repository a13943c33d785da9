"""One factorisation protocol (fem/factor.py): every backend solves the same SPD system, one
right-hand side or several, and a singular system raises the one error, SingularStiffness,
naming the free unknowns."""
import numpy as np
import pytest
import scipy.sparse as sp

from flexfem.fem import SingularStiffness, linsolve
from flexfem.fem.factor import BACKENDS, LinearFactor, factor


def available(name: str) -> bool:
    if name == "mkl-pardiso":
        return linsolve.mkl_pardiso() is not None
    if name == "cholmod":
        return linsolve._cholmod() is not None
    return True


# the backends that factorise any matrix ('pmg-cg' needs a model's mesh: test_pmultigrid.py)
BACKEND_NAMES = [pytest.param(n, marks=pytest.mark.skipif(not available(n), reason=f"no {n}"))
                 for n in sorted(BACKENDS) if not getattr(BACKENDS[n], "needs_model", False)]


def grid_laplacian(m: int) -> sp.csr_matrix:
    """The 5-point Laplacian of an m x m grid held on its boundary (SPD; half-bandwidth m)."""
    one = sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(m, m))
    return (sp.kron(one, sp.identity(m)) + sp.kron(sp.identity(m), one)).tocsr()


@pytest.fixture(scope="module")
def system():
    A = grid_laplacian(12)  # 144 unknowns, cond ~ 60: every backend reaches 1e-10
    rng = np.random.default_rng(3)
    return A, rng.standard_normal(A.shape[0]), rng.standard_normal((A.shape[0], 3))


@pytest.mark.parametrize("name", BACKEND_NAMES)
def test_every_backend_solves_the_same_spd_system(system, name):
    A, b, B = system
    with factor(A, "spd", backend=name) as F:
        assert isinstance(F, LinearFactor) and F.backend == name
        x, X = F.solve(b), F(B)
    assert np.linalg.norm(A @ x - b) <= 1e-10 * np.linalg.norm(b)
    assert X.shape == B.shape and np.linalg.norm(A @ X - B) <= 1e-10 * np.linalg.norm(B)
    # the same solution as an independent dense solve
    assert np.allclose(x, np.linalg.solve(A.toarray(), b), rtol=0, atol=1e-9 * np.abs(x).max())


def held_and_free_chains(n: int = 12):
    """Two spring chains: 'base' (unknowns 0..n-1) held by a spring to the ground at its first
    node, 'arm' (n..2n-1) held by nothing: singular, its null vector moves the arm only."""
    chain = sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(n, n)).tolil()
    chain[n - 1, n - 1] = 1.0
    free = chain.copy()
    free[0, 0] = 1.0
    A = sp.block_diag([chain, free], format="csr")
    labels = ["group 'base'"] * n + ["group 'arm'"] * n
    return A, labels


@pytest.mark.filterwarnings("ignore::UserWarning")  # pyamg: "Indefinite matrix detected in CG"
@pytest.mark.parametrize("name", BACKEND_NAMES)
def test_a_singular_system_names_the_free_group(name):
    A, labels = held_and_free_chains()
    b = np.linspace(1.0, 2.0, A.shape[0])  # not in A's range: the arm's loads do not balance
    with pytest.raises(SingularStiffness) as caught:
        with factor(A, "spd", backend=name, labels=labels, check=True) as F:
            F.solve(b)
    assert caught.value.free == "group 'arm'"
    assert "free: group 'arm'" in str(caught.value) and "base" not in str(caught.value)
    assert isinstance(caught.value, ValueError)


def test_an_unknown_backend_or_kind_is_refused_in_one_line():
    A = grid_laplacian(3)
    with pytest.raises(ValueError, match="backend = 'lapack'; choose 'auto' or one of"):
        factor(A, backend="lapack")
    with pytest.raises(ValueError, match="kind = 'lu'"):
        factor(A, kind="lu")
    with pytest.raises(ValueError, match="labels has 2 names for 9 unknowns"):
        factor(A, labels=["a", "b"])
    with pytest.raises(ValueError, match="banded Cholesky factorises SPD"):
        factor(A, "general", backend="banded")
