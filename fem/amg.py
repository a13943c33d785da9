"""CG preconditioned by smoothed-aggregation AMG as a factor of the protocol
(fem/factor_protocol.py): the iterative backend 'amg-cg' of fem/factor.py's ``factor``."""
import numpy as np
import scipy.sparse as sp

from .factor_protocol import LinearFactor, SingularStiffness, checked_rhs


class AmgFactor(LinearFactor):
    """CG preconditioned by smoothed-aggregation AMG, set up once, one CG solve per column
    to the relative residual ``tol``; SingularStiffness where CG does not converge.

    near_null_space : (n, k) rigid-body modes restricted to the unknowns (a constant vector
    by default). The system is scaled symmetrically to unit diagonal first, and the
    prolongator is energy-minimising: on P2 elasticity plain smoothed aggregation stalls
    (hundreds of CG iterations), this setup converges in a few dozen.
    """

    backend = "amg-cg"

    def __init__(self, A, kind: str = "spd", near_null_space=None, tol: float = 1e-10):
        import pyamg

        if kind != "spd":
            raise ValueError(f"AMG-CG solves SPD systems, not kind = {kind!r}")
        A = sp.csr_matrix(A)
        self.n, self.tol = A.shape[0], tol
        B = np.ones((self.n, 1)) if near_null_space is None else np.asarray(near_null_space)
        self.d = 1.0 / np.sqrt(A.diagonal())
        scale = sp.diags(self.d)
        self._ml = pyamg.smoothed_aggregation_solver(
            (scale @ A @ scale).tocsr(), B=B / self.d[:, None], symmetry="symmetric",
            max_coarse=1000, strength=("symmetric", {"theta": 0.02}),
            smooth=("energy", {"degree": 2, "maxiter": 2}))

    def solve(self, b) -> np.ndarray:
        b = checked_rhs(b, self.n)
        if b.ndim == 2:
            return np.column_stack([self.solve(c) for c in b.T]).reshape(b.shape)
        residuals = []
        bs = self.d * b
        y = self._ml.solve(bs, tol=self.tol, accel="cg", maxiter=1000, residuals=residuals)
        if not residuals[-1] <= 10 * self.tol * np.linalg.norm(bs):
            raise SingularStiffness(
                f"AMG-CG did not converge (relative residual "
                f"{residuals[-1] / np.linalg.norm(bs):.1e} after {len(residuals) - 1} "
                "iterations); try solver='direct'")
        return self.d * y

    def free(self) -> None:
        self._ml = None
