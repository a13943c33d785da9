"""Follower pressure for the total-Lagrangian solver: the load acts on the deformed surface.

By Nanson's formula the current n da = J F^-T N dA = cof(F) N dA, so pressure p (positive
pushing into the body) gives the external virtual work
    f_p(u; v) = -t int p cof(F) N . v dA              (reference surface, N, X)
and the load stiffness (its derivative in the direction du, part of the tangent)
    K_p(du, v) = -t int p dcof(F)[grad du] N . v dA,
dcof(F)[G] = cof(G) in 2-D (cof is linear there), e_ikl e_JMN F_kM G_lN in 3-D.
It is not symmetric in general, so a solve with follower loads uses the general (LU)
factorization. The dead (reference-configuration) part f_p(0) is in the ordinary load
vector; :class:`FollowerPressure` adds f_p(u) - f_p(0).
"""
import numpy as np
import scipy.sparse as sp
import skfem

from .boundary import Pressure, facet_basis, evaluate_on_points

_EPS = np.zeros((3, 3, 3))
_EPS[0, 1, 2] = _EPS[1, 2, 0] = _EPS[2, 0, 1] = 1.0
_EPS[0, 2, 1] = _EPS[2, 1, 0] = _EPS[1, 0, 2] = -1.0


def cofactor(F: np.ndarray) -> np.ndarray:
    """cof(F) = det(F) F^-T of a (dim, dim, ...) array (dim = 2 or 3)."""
    if F.shape[0] == 2:
        return np.array([[F[1, 1], -F[1, 0]], [-F[0, 1], F[0, 0]]])
    return 0.5 * np.einsum("ikl,jmn,km...,ln...->ij...", _EPS, _EPS, F, F)


def cofactor_derivative(F: np.ndarray) -> np.ndarray:
    """D[i, J, l, N] = d cof(F)_iJ / d F_lN, (dim,) * 4 + F.shape[2:]."""
    d = F.shape[0]
    if d == 2:
        D = np.zeros((2, 2, 2, 2) + F.shape[2:])
        D[0, 0, 1, 1] = D[1, 1, 0, 0] = 1.0
        D[0, 1, 1, 0] = D[1, 0, 0, 1] = -1.0
        return D
    return np.einsum("ikl,jmn,km...->ijln...", _EPS, _EPS, F)


class FollowerPressure:
    """f_p(u) - f_p(0) (N) and the load stiffness -d f_p / du (N/m) of the follower Pressure
    loads in ``loads``, at unit load factor; ``active`` is False when there are none."""

    def __init__(self, model, loads):
        self.model = model
        self.terms = []
        for load in loads:
            if isinstance(load, Pressure) and load.follower:
                fb = facet_basis(model, load.group)
                if callable(load.p):
                    x = np.asarray(fb.global_coordinates())
                    p = evaluate_on_points(load.p, x, 0, f"Pressure({load.group!r}).p")
                else:
                    p = np.full(fb.dx.shape, float(load.p))
                self.terms.append((fb, model.thickness * p))
        self.active = bool(self.terms)
        # the factorization the tangent needs: the load stiffness is not symmetric
        self.matrix_kind = "general" if self.active else "symmetric"
        self._reference = self._force(np.zeros(model.n_dofs)) if self.active else 0.0

    def _force(self, u):
        f = np.zeros(self.model.n_dofs)
        for fb, tp in self.terms:
            F = _deformation(fb, u)
            f += skfem.LinearForm(
                lambda v, w: -w.tp * np.einsum("ij...,j...,i...->...", cofactor(w.F), w.n, v)
            ).assemble(fb, F=F, tp=tp)
        return f

    def force(self, u: np.ndarray) -> np.ndarray:
        """f_p(u) - f_p(0) (N): the change of the pressure's nodal forces from the
        undeformed surface to the deformed one, at load factor 1 (0 without follower loads)."""
        return self._force(u) - self._reference if self.active else 0.0

    def stiffness(self, u: np.ndarray) -> sp.csr_matrix:
        """-d f_p / du (N/m) at ``u``, load factor 1: add lam times it to the tangent."""
        n = self.model.n_dofs
        K = sp.csr_matrix((n, n))  # stays empty without follower loads
        for fb, tp in self.terms:
            D = cofactor_derivative(_deformation(fb, u))
            K = K + skfem.BilinearForm(
                lambda du, v, w: w.tp * np.einsum("ijln...,ln...,j...,i...->...",
                                                  w.D, du.grad, w.n, v)
            ).assemble(fb, D=D, tp=tp)
        return K.tocsr()


def _deformation(fb, u):
    """F = I + grad u (dim, dim, n_facets, n_points) at the quadrature points of ``fb``."""
    gu = fb.interpolate(u).grad
    return gu + np.eye(gu.shape[0]).reshape(gu.shape[:2] + (1, 1))
