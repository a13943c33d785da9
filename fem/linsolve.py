"""Sparse linear solvers: a direct factorization (MKL PARDISO where installed, SuperLU
otherwise) and smoothed-aggregation AMG-preconditioned CG with rigid-body modes as the near
null space. :func:`choose_solver` picks one by problem size."""
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

# Above these sizes (free DOFs) "auto" uses AMG-CG: measured crossover on 2 cores, see
# docs/performance.md. Direct factorization fill grows much faster in 3-D.
AMG_THRESHOLD = {2: 2_000_000, 3: 400_000}


class SingularSystemError(ValueError):
    """The stiffness matrix is singular: the model can move without straining."""


def _pardiso():
    try:
        import pypardiso
    except ImportError:
        return None
    return pypardiso


def factorize(A: sp.spmatrix):
    """Factorize the square sparse matrix ``A`` once; return ``solve(b) -> x``."""
    A = sp.csr_matrix(A)
    A.sort_indices()
    pardiso = _pardiso()
    if pardiso is not None:
        solver = pardiso.PyPardisoSolver()
        solver.set_statistical_info_off()
        solver.factorize(A)
        return lambda b: solver.solve(A, np.asarray(b, dtype=float))
    lu = spla.splu(A.tocsc(), permc_spec="MMD_AT_PLUS_A")
    return lu.solve


def solve_direct(A, b) -> np.ndarray:
    return factorize(A)(b)


def solve_amg(A, b, near_null_space: np.ndarray, tol: float = 1e-10) -> np.ndarray:
    """Solve the SPD system with CG preconditioned by smoothed-aggregation AMG.

    near_null_space : (n, k) rigid-body modes restricted to the unknowns. The system is
    scaled symmetrically to unit diagonal first, and the prolongator is energy-minimising:
    on P2 elasticity plain smoothed aggregation stalls (hundreds of CG iterations), this
    setup converges in a few dozen.
    """
    import pyamg

    d = 1.0 / np.sqrt(sp.csr_matrix(A).diagonal())
    scale = sp.diags(d)
    As = (scale @ A @ scale).tocsr()
    ml = pyamg.smoothed_aggregation_solver(
        As, B=near_null_space / d[:, None], symmetry="symmetric", max_coarse=1000,
        strength=("symmetric", {"theta": 0.02}), smooth=("energy", {"degree": 2, "maxiter": 2}))
    residuals = []
    bs = d * b
    y = ml.solve(bs, tol=tol, accel="cg", maxiter=1000, residuals=residuals)
    if not residuals[-1] <= 10 * tol * np.linalg.norm(bs):
        raise SingularSystemError(
            f"AMG-CG did not converge (relative residual {residuals[-1] / np.linalg.norm(bs):.1e} "
            f"after {len(residuals) - 1} iterations); try solver='direct'")
    return d * y


def choose_solver(n_unknowns: int, dim: int, solver: str = "auto") -> str:
    """'direct' or 'amg' for ``solver='auto'`` by size; a named solver is checked and kept."""
    if solver not in ("auto", "direct", "amg"):
        raise ValueError(f"solver = {solver!r}; choose 'auto', 'direct' or 'amg'")
    if solver != "auto":
        return solver
    return "amg" if n_unknowns > AMG_THRESHOLD[dim] else "direct"


def check_solution(A, x, b, what: str = "static solve", rtol: float = 1e-6) -> None:
    """Raise :class:`SingularSystemError` if ``x`` does not solve ``A x = b``."""
    if not np.all(np.isfinite(x)):
        raise SingularSystemError(f"{what}: the solution is not finite; the model is singular "
                                  "(under-constrained, or parts not connected to a support)")
    r = np.linalg.norm(A @ x - b)
    if r > rtol * max(np.linalg.norm(b), 1e-300):
        raise SingularSystemError(f"{what}: residual {r / np.linalg.norm(b):.1e} relative; the "
                                  "stiffness matrix is singular or nearly so (under-constrained "
                                  "model or disconnected parts)")
