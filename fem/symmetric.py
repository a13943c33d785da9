"""Symmetric sparse matrices kept as their upper triangle (diagonal included), as the model
keeps its stiffness and mass: half the memory of the full CSR matrix, and what PARDISO's
symmetric factorizations read."""
import numpy as np
import scipy.sparse as sp


def upper(A):
    """The upper triangle (diagonal included) of the square sparse ``A``, CSR, sorted."""
    U = sp.triu(A, format="csr")
    U.sort_indices()
    return U


def symmetric_from_upper(U):
    """The full symmetric CSR matrix whose upper triangle (diagonal included) is ``U``."""
    return (U + sp.triu(U, k=1, format="csr").T).tocsr()


def symmetric_matvec(U, x: np.ndarray) -> np.ndarray:
    """A @ x for the symmetric A stored as its upper triangle ``U`` (CSR), x of shape (n,)
    or (n, k): U x + U^T x less the diagonal counted twice; no copy of U (U^T is a view)."""
    d = U.diagonal()
    return U @ x + U.T @ x - (d[:, None] * x if x.ndim == 2 else d * x)
