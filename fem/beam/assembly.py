"""Assembly of a beam model on the reduced space of unknowns (fem/beam/space.py): residual,
tangent, mass, and the sparse LU of the reduced tangent.

Sparsity patterns are computed once (fem/beam/pattern.py): the global matrix's per topology,
the condensed tangent's (supports and rigid links eliminated) per Space and topology; derived
per-model data (the basic stiffness, the undeformed tangent, the mass) is cached on the model
(BeamModel.cached).
"""
from dataclasses import dataclass
import math

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .element import (basic_stiffness, corotational, local_mass, rotation_to_global,
                      undeformed)
from .model import BeamModel
from .pattern import block_dofs, global_matrix
from .space import Space
from .supports import load_vector

DENSE_EIGEN_LIMIT = 800  # unknowns up to which modal analysis uses a dense eigensolver
ORDERING = "MMD_AT_PLUS_A"  # SuperLU column ordering: the reduced K's pattern is symmetric


class SingularBeamError(ValueError):
    """The reduced stiffness is singular: a mechanism (supports leave a motion free)."""


def element_dofs(model: BeamModel) -> np.ndarray:
    """(n_e + n_pairs, 6) global DOFs of each element, then of each superelement pair."""
    return model.cached("element_dofs", lambda: block_dofs(model.connectivity))


def gather(model: BeamModel, fe: np.ndarray) -> np.ndarray:
    """Global vector from element vectors (n_e, 6)."""
    return np.bincount(element_dofs(model).ravel(), weights=fe.ravel(), minlength=model.n_dofs)


def element_mass(model: BeamModel) -> np.ndarray:
    """(n_e + n_pairs, 6, 6) consistent element mass matrices in global DOF order, then the
    superelements' pairs' (cached)."""
    def compute():
        T = rotation_to_global(model.angles)
        return np.concatenate([np.matmul(T.transpose(0, 2, 1), local_mass(model) @ T),
                               model.pair_mass])
    return model.cached("element_mass", compute)


def point_mass_diagonal(model: BeamModel) -> np.ndarray:
    """(n_dofs,) the point masses (kg; rotary inertia kg m^2 on theta) as a diagonal."""
    diag = np.zeros(model.n_dofs)
    for node, (m, J) in model.point_masses.items():
        diag[3 * int(node):3 * int(node) + 2] += m
        diag[3 * int(node) + 2] += J
    return diag


def point_mass_blocks(model: BeamModel, nodes) -> np.ndarray:
    """(k, 6, 6) the point masses of ``nodes`` (k,) as blocks of the node pair (node, node):
    mass (kg) and rotary inertia (kg m^2) on the first node's DOFs, zeros elsewhere."""
    blocks = np.zeros((len(nodes), 6, 6))
    for k, node in enumerate(nodes.tolist()):
        m, J = model.point_masses[node]
        blocks[k, 0, 0] = blocks[k, 1, 1] = m
        blocks[k, 2, 2] = J
    return blocks


def mass_matrix(model: BeamModel) -> sp.csr_matrix:
    """Consistent global mass matrix (kg, kg m, kg m^2), point masses included (cached)."""
    return model.cached("mass_matrix", lambda: global_matrix(model, element_mass(model),
                                                             point_mass_diagonal(model)))


@dataclass(frozen=True, eq=False)
class Evaluation:
    """A state: q (n_nodes, 3); r (n_dofs,) = f_int - lam f_ext (N, N m); rz = T^T r; K the
    reduced tangent (CSC, None without tangent); w the link weights (Space.weights); ke the
    element tangents (n_e, 6, 6)."""

    model: BeamModel
    q: np.ndarray
    r: np.ndarray
    rz: np.ndarray
    K: object
    w: np.ndarray
    ke: object

    def full_times(self, v) -> np.ndarray:
        """K_full v (n_dofs,) for a full vector v, element by element."""
        dofs = element_dofs(self.model)
        return gather(self.model, np.einsum("eij,ej->ei", self.ke, v[dofs]))


class BeamAssembler:
    """Internal force, residual and reduced tangent of a model at a state."""

    def __init__(self, model: BeamModel, supports, loads):
        self.model = model
        self.space = Space(model, supports)
        self.f_ext = load_vector(model, loads)
        self.Kb = model.cached("basic_stiffness", lambda: basic_stiffness(model))

    def elements(self, q, tangent=True) -> tuple:
        """corotational(model, Kb, q, tangent), the superelements' pairs (linear) appended
        to the forces and tangents; the undeformed state's is cached (the linear solves of
        a design point all start there)."""
        if not q.any():
            return self.model.cached("undeformed", lambda: self._with_pairs(
                undeformed(self.model, self.Kb), q))
        return self._with_pairs(corotational(self.model, self.Kb, q, tangent), q)

    def _with_pairs(self, out, q) -> tuple:
        model = self.model
        if not len(model.pairs):
            return out
        fe, ke, basic = out
        qp = q.reshape(-1)[element_dofs(model)[model.n_elements:]]
        fe = np.concatenate([fe, np.einsum("eij,ej->ei", model.pair_stiffness, qp)])
        if ke is not None:
            ke = np.concatenate([ke, model.pair_stiffness])
        return fe, ke, basic

    def evaluate(self, z, lam, tangent=True) -> Evaluation:
        """The state at unknowns z and load factor lam (r = f_int - lam f_ext, N, N m)."""
        space = self.space
        q = space.q(z, lam)
        fe, ke, _ = self.elements(q, tangent)
        r = gather(self.model, fe) - lam * self.f_ext
        w = space.weights(q)
        rz = space.reduce(r, w)[0]
        K = space.condense(ke, w, space.constraint_diagonal(q, r)) if tangent else None
        return Evaluation(self.model, q, r, rz, K, w, ke)

    def at(self, z, lam, tangent=True) -> Evaluation:
        """evaluate(z, lam): the stepper's state (fem/beam/stepper.py)."""
        return self.evaluate(z, lam, tangent)

    def load_rate(self, ev: Evaluation) -> np.ndarray:
        """d(rz)/d(lam) = T^T (K T_p p - f_ext) at the Evaluation ``ev``."""
        space, f = self.space, self.f_ext
        if len(space.p_hat):
            f = f - ev.full_times(space.expand(np.zeros(space.n), space.p_hat, ev.w))
        return -space.reduce(f, ev.w)[0]



class Factor:
    """Sparse LU (SuperLU: single-threaded, fast for the banded systems of beam models) of
    the Jacobi-scaled K (unit diagonal, so that pivots compare across DOFs of any
    stiffness). Raises SingularBeamError if K is (numerically) singular. ``sign``: the sign
    of det K (it flips where the tangent loses definiteness: a limit or bifurcation point)."""

    def __init__(self, K):
        K = sp.csc_matrix(K)
        if not K.has_canonical_format:  # the scaled copy below shares K's index arrays
            K = K.copy()
            K.sum_duplicates()
        diag = np.abs(K.diagonal())
        if not np.all(np.isfinite(diag)) or np.any(diag == 0):
            raise SingularBeamError("singular stiffness: a DOF has no stiffness at all (a "
                                    "node without elements, or a mechanism)")
        self.scale = 1.0 / np.sqrt(diag)
        col = np.repeat(np.arange(K.shape[1]), np.diff(K.indptr))
        scaled = sp.csc_matrix((K.data * self.scale[K.indices] * self.scale[col], K.indices,
                                K.indptr), shape=K.shape)
        try:
            self.lu = spla.splu(scaled, permc_spec=ORDERING)
        except RuntimeError as exc:
            raise SingularBeamError(f"singular stiffness ({exc}): a mechanism; the supports or "
                                    "links leave a motion free") from None
        d = self.lu.U.diagonal()
        if not np.isfinite(d).all() or np.abs(d).min() <= 1e-13:
            raise SingularBeamError(f"singular stiffness (scaled pivot {np.abs(d).min():.1e}): "
                                    "a mechanism; the supports or links leave a motion free")
        self.d = d

    @property
    def sign(self) -> int:
        parity = _parity(self.lu.perm_r) ^ _parity(self.lu.perm_c)
        return int(np.prod(np.sign(self.d))) * (-1 if parity else 1)

    def solve(self, b):
        b = np.asarray(b, dtype=float)
        scale = self.scale if b.ndim == 1 else self.scale[:, None]
        return scale * self.lu.solve(scale * b)


def _parity(perm) -> int:
    """0 for an even permutation, 1 for an odd one: (n - number of cycles) mod 2, the cycles
    counted by pointer doubling (label each index with the smallest index of its cycle)."""
    perm = np.asarray(perm, dtype=np.int64)
    n = len(perm)
    label, step = np.arange(n), perm.copy()
    for _ in range(max(1, math.ceil(math.log2(max(n, 2))))):
        label = np.minimum(label, label[step])
        step = step[step]
    return int(n - np.count_nonzero(label == np.arange(n))) % 2


def solve(K, b):
    """Solve K x = b (see Factor)."""
    return Factor(K).solve(b)
