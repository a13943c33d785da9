"""The undeformed reduced system of a beam model for one set of held DOFs, assembled and
factored once and cached on the model: the linear static solves and the modal analysis of
a design point share it.

A static solve whose supports add a few NodePrescribed DOFs to the NodeFixed ones (a stiffness with
the load point held in some directions) is solved on the NodeFixed supports' system with the
extra DOFs as constraints (Lagrange multipliers, a k x k Schur complement): one
factorisation serves every load case of the point and the modes held by the NodeFixed supports.
"""
import numpy as np

from .assembly import (BeamAssembler, Evaluation, SingularBeamError, element_mass,
                       point_mass_blocks)
from .banded import spd_factor
from .model import BeamModel
from .supports import NodeFixed
from .space import held_values

MAX_EXTRA = 12  # extra prescribed DOFs solved by the Schur complement (more: own factor)


class LinearSystem:
    """Space, undeformed evaluation (K: reduced stiffness), its factor and the reduced mass
    (on first use) for ``supports`` (their held DOFs; the values are the caller's)."""

    def __init__(self, model: BeamModel, supports):
        self.asm = BeamAssembler(model, supports, ())
        self.space = space = self.asm.space
        q = np.zeros((model.n_nodes, 3))
        _, ke, _ = self.asm.elements(q)
        w = space.weights(q)
        # K by the Space's shared pattern (~5x faster than the sparse products of a first
        # tangent once a sweep's topology has it): every design of a sweep assembles alike.
        # The undeformed state carries no force: no residual, no links' second-order term.
        K = space.condensed().matrix(ke, w, np.zeros(space.n))
        self.ev = Evaluation(model, q, np.zeros(model.n_dofs), np.zeros(space.n), K, w, ke)
        self._factor = self._mass = None

    @property
    def factor(self):
        if self._factor is None:
            self._factor = spd_factor(self.ev.K)
        return self._factor

    @property
    def mass(self):
        """Reduced consistent mass T^T M T (CSC)."""
        if self._mass is None:
            model, space = self.asm.model, self.space
            # the point masses as blocks of their nodes after the elements': one assembly
            # by a fixed pattern (a slave's lands on its master's DOFs, off the diagonal too)
            nodes = np.array(list(model.point_masses), dtype=np.int64)
            blocks = np.vstack([model.connectivity, np.column_stack([nodes, nodes])])
            matrices = np.concatenate([element_mass(model), point_mass_blocks(model, nodes)])
            self._mass = space.condensed(blocks).matrix(matrices, self.ev.w, np.zeros(space.n))
        return self._mass


def _held(model: BeamModel, supports) -> np.ndarray:
    """The DOFs ``supports`` hold."""
    return np.flatnonzero(~np.isnan(held_values(model, supports)))


def linear_system(model: BeamModel, supports, held=None) -> LinearSystem:
    """The model's cached LinearSystem for the DOFs ``supports`` hold (``held``, where the
    caller has them)."""
    held = _held(model, supports) if held is None else held
    return model.cached(("linear", held.tobytes()), lambda: LinearSystem(model, supports))


def _on_fixed(model: BeamModel, supports, held):
    """(the NodeFixed supports' system, the other held DOFs) where those are few and the
    supports' own system (of the DOFs ``held``) is not cached, else None."""
    base = [s for s in supports if isinstance(s, NodeFixed)]
    if base and not model.is_cached(("linear", held.tobytes())):
        if len(base) == len(supports):  # all NodeFixed: the supports' own system
            return linear_system(model, base, held), held[:0]
        system = linear_system(model, base)
        extra = np.setdiff1d(held, system.space.held)
        if len(extra) <= MAX_EXTRA:
            return system, extra
    return None


def solve_linear(model: BeamModel, supports, f_ext) -> tuple:
    """(q (n_dofs,), LinearSystem used, whether it holds the supports' DOFs alone) of
    K q = f_ext with the supports' values: on the system of the NodeFixed supports with the
    other held DOFs as constraints where that system is nonsingular and they are few, else
    on the supports' own system."""
    values = held_values(model, supports)
    held = np.flatnonzero(~np.isnan(values))
    on_fixed = _on_fixed(model, supports, held)
    if on_fixed is not None:
        system, extra = on_fixed
        try:
            return _constrained(system, values, extra, f_ext), system, len(extra) == 0
        except SingularBeamError:
            pass
    system = linear_system(model, supports, held)
    return _constrained(system, values, np.zeros(0, dtype=np.int64), f_ext), system, True


def modal_system(model: BeamModel, supports) -> tuple:
    """(LinearSystem, j) for modes held by ``supports``: the NodeFixed supports' cached system
    with the other held DOFs' unknowns ``j`` kept at zero (:func:`held_at_zero`), where the
    static solves would use it; else the supports' own system and no ``j``."""
    held = _held(model, supports)
    on_fixed = _on_fixed(model, supports, held)
    if on_fixed is not None:
        system, extra = on_fixed
        return system, system.space.col[extra, 0]
    return linear_system(model, supports, held), np.zeros(0, dtype=np.int64)


def held_at_zero(system: LinearSystem, j):
    """B -> Z: the solution of K Z = B + E Lam, Z[j] = 0 (E: unit columns at the unknowns
    ``j``), for (n, k) blocks: K^-1 of the system with those unknowns held, in the larger
    system's numbering (the rows of B at ``j`` do not enter). Raises SingularBeamError where
    the held unknowns are not independent."""
    Y = system.factor.solve(_unit_columns(system.space.n, j))
    YS = Y @ np.linalg.inv(_independent(Y[j], "held"))

    def solve(B):
        Z = system.factor.solve(B)
        Z -= YS @ Z[j]
        Z[j] = 0.0
        return Z
    return solve


def _unit_columns(n: int, j) -> np.ndarray:
    """E (n, len(j)): unit columns at the unknowns ``j``."""
    E = np.zeros((n, len(j)))
    E[j, np.arange(len(j))] = 1.0
    return E


def _independent(S, what: str):
    """The Schur block ``S`` = E^T K^-1 E; SingularBeamError where the ``what`` DOFs it
    holds are not independent."""
    if not np.isfinite(S).all() or np.linalg.cond(S) > 1e12:
        raise SingularBeamError(f"the {what} DOFs are not independent")
    return S


def _constrained(system: LinearSystem, values, extra, f_ext) -> np.ndarray:
    """q of K z = rhs + E lam, E^T z = values[extra] on ``system`` (E: unit columns of the
    ``extra`` DOFs, free unknowns there)."""
    space, ev = system.space, system.ev
    p = values[space.held]
    z0 = np.zeros(space.n)
    if p.any():  # the held values' forces on the unknowns
        f_ext = f_ext - ev.full_times(space.expand(z0, p, ev.w))
    rhs = space.reduce(f_ext, ev.w)[0]
    if len(extra) == 0:
        z = system.factor.solve(rhs)
    else:
        j = space.col[extra, 0]  # their unknowns (held DOFs are never rigid-link slaves)
        Y = system.factor.solve(np.column_stack([rhs, _unit_columns(space.n, j)]))
        z0, Y = Y[:, 0], Y[:, 1:]
        S = _independent(Y[j], "prescribed")
        z = z0 + Y @ np.linalg.solve(S, values[extra] - z0[j])
    return space.expand(z, p, ev.w)
