"""Geometrically exact (co-rotational) static analysis of a beam model.

    res = solve_beam_nonlinear(model, [Fixed(0)], [NodalLoad(tip, fy=-P)], steps=20)
    res.path(tip)                       # (n_steps + 1, 3): u, v, theta of the tip

Load control: loads (dead) and prescribed DOFs scale with the load factor, stepped 0 -> 1.
Displacement control (``control=(node, dof, value)``): the DOF is stepped 0 -> value and the
load factor is the extra unknown (Batoz & Dhatt), which passes limit points of the load.
Newton's method per step; a failing step is halved down to ``min_step``, then
NonConvergenceError (no unconverged answer is ever returned).
"""
from dataclasses import dataclass, field
import math

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..newton import NonConvergenceError, check_step_arguments
from ..stepping import StepFailed as _StepFailed
from ..stepping import march
from .assembly import Assembler, Factor, SingularBeamError
from .model import BeamModel
from .supports import dof_index
from .static import BeamState, make_state


@dataclass(frozen=True, eq=False)
class BeamNonlinearResult:
    """Converged steps; index 0 is the unloaded state. load_factors (n,); states: BeamState
    per step (q, reactions, element forces, stresses); iterations per step."""

    model: BeamModel
    load_factors: np.ndarray
    states: list
    iterations: list
    info: dict = field(default_factory=dict)

    @property
    def final(self) -> BeamState:
        return self.states[-1]

    def path(self, node: int) -> np.ndarray:
        """(n_steps + 1, 3) u (m), v (m), theta (rad) of ``node`` over the steps."""
        return np.array([s.q[int(node)] for s in self.states])

    def reaction_path(self, node: int) -> np.ndarray:
        """(n_steps + 1, 3) reaction (F_x, F_y N, M N m) of a supported ``node``."""
        return np.array([s.reactions[int(node)] for s in self.states])


class _Stepper:
    """Newton iterations at a load factor (load control) or a control value (displacement
    control), from a converged state."""

    def __init__(self, asm: Assembler, control, tol, max_iterations):
        self.asm, self.tol, self.max_iterations = asm, tol, max_iterations
        self.c_index = None
        if control is not None:
            node, dof, self.c_value = control
            full = 3 * int(node) + dof_index(dof)
            where = np.flatnonzero(asm.space.free == full)
            if not len(where):
                raise ValueError(f"control = {control!r}: the DOF is held or on a rigid-link "
                                 "slave; control a free DOF")
            self.c_index = int(where[0])

    def dr_dlam(self, ev):
        """d(rz)/d(lam) = T^T (K T_p p - f_ext) at the Evaluation ``ev``."""
        space = self.asm.space
        f = self.asm.f_ext
        if len(space.p_hat):
            f = f - ev.full_times(space.expand(np.zeros(space.n), space.p_hat, ev.w))
        return -space.reduce(f, ev.w)[0]

    def newton(self, z, lam, target):
        """Converged (z, lam, q, r, iterations, flipped) reaching ``target`` (a load factor,
        or the control DOF's value); flipped: the tangent's determinant changed sign over
        the step (a limit or bifurcation point crossed)."""
        history, signs, dz = [], [], None
        for it in range(1, self.max_iterations + 1):
            ev = self.asm.evaluate(z, lam)
            q, r, rz = ev.q, ev.r, ev.rz
            ref = self._reference(r, lam)
            norm = float(np.linalg.norm(rz))
            if it > 1:
                history.append(norm / ref)
                if not math.isfinite(norm) or norm > 1e6 * ref:
                    raise _StepFailed("the residual diverged", history)
                # converged; or at round-off: the last Newton correction ~ machine precision
                floor = np.linalg.norm(dz) <= 1e-12 * np.linalg.norm(z) and norm <= 1e-6 * ref
                if (norm <= self.tol * ref and self._small(dz, z)) or floor:
                    self.last_count = negative_eigenvalues(ev.K)
                    return z, lam, q, r, it - 1, signs[0] != signs[-1]
            try:
                F = Factor(ev.K)
                signs.append(F.sign)
                if self.c_index is None and it > 1:
                    a, b = F.solve(-rz), None
                else:
                    a, b = F.solve(np.column_stack([-rz, self.dr_dlam(ev)])).T
                if self.c_index is None:
                    dlam = target - lam if it == 1 else 0.0  # predictor: load increment
                    dz = a if b is None else a - dlam * b
                else:
                    if abs(b[self.c_index]) < 1e-300:
                        raise _StepFailed("the control DOF does not respond to the load",
                                          history)
                    dlam = (z[self.c_index] + a[self.c_index] - target) / b[self.c_index]
                    dz = a - dlam * b
            except SingularBeamError as exc:
                raise _StepFailed(str(exc), history) from None
            z, lam = z + dz, lam + dlam
        raise _StepFailed(f"no convergence in {self.max_iterations} iterations", history)

    def _reference(self, r, lam):
        space = self.asm.space
        ref = np.linalg.norm(lam * self.asm.f_ext) + np.linalg.norm(r[space.held])
        return max(ref, 1e-12 * (1.0 + np.abs(self.asm.f_ext).max()))

    def _small(self, dz, z):
        return np.linalg.norm(dz) <= math.sqrt(self.tol) * max(np.linalg.norm(z), 1e-14)


def negative_eigenvalues(K):
    """The number of negative eigenvalues of (the symmetric part of) the tangent ``K``, a
    Sturm count: the negative pivots of its LDL^T (SuperLU without row pivoting, Jacobi
    scaled); None where a pivot is (nearly) zero or SuperLU had to pivot."""
    K = sp.csc_matrix(0.5 * (K + K.T))
    scale = sp.diags(1.0 / np.sqrt(np.abs(K.diagonal())))
    try:
        lu = spla.splu(sp.csc_matrix(scale @ K @ scale), permc_spec="MMD_AT_PLUS_A",
                       diag_pivot_thresh=0.0, options={"SymmetricMode": True})
    except RuntimeError:
        return None
    d = lu.U.diagonal()
    if not np.array_equal(lu.perm_r, lu.perm_c) or np.abs(d).min() <= 1e-13:
        return None
    return int(np.count_nonzero(d < 0))


def step_failure(t, dt, lam, cuts, failure) -> NonConvergenceError:
    """The error of a beam solve whose step from fraction ``t`` by ``dt`` (last converged load
    factor ``lam``) failed at the smallest step allowed (planar and spatial alike)."""
    return NonConvergenceError(
        f"no convergence beyond step fraction {t:.6g} (load factor {lam:.6g}; trying "
        f"{t + dt:.6g}) after {cuts} cuts: {failure.reason}; relative residuals "
        f"{', '.join(f'{h:.2e}' for h in failure.history) or 'none'}. Use more steps or a "
        "smaller min_step; under load control a limit point (buckling, snap-through) cannot "
        "be passed: use control=(node, dof, value)", lam, t + dt, len(failure.history),
        failure.history)


def solve_beam_nonlinear(model: BeamModel, supports, loads=(), steps: int = 10,
                         control=None, max_iterations: int = 30, tol: float = 1e-9,
                         min_step: float = 1e-4) -> BeamNonlinearResult:
    """Large-rotation static solve of ``model`` under ``supports`` (Fixed, Prescribed) and
    ``loads`` (NodalLoad, dead), in ``steps`` equal increments of the load factor 0 -> 1, or
    with ``control=(node, dof, value)`` of that DOF 0 -> value (m or rad; the load factor
    then follows). Converged when |r| <= tol * (|applied| + |reactions|) (N) and the last
    increment |dz| <= sqrt(tol) |z|. Raises NonConvergenceError when a step cannot be cut
    below ``min_step`` (a fraction of the total)."""
    check_step_arguments(steps, max_iterations, tol, min_step)
    if model.superelements:
        raise ValueError("solve_beam_nonlinear: the model has superelements, which are "
                         "linear (small rotations only); use the linear solves")
    asm = Assembler(model, supports, loads)
    stepper = _Stepper(asm, control, tol, max_iterations)
    ev0 = asm.evaluate(np.zeros(asm.space.n), 0.0, tangent=False)
    states, lams, its = [make_state(asm, ev0.q, ev0.r, 0.0, w=ev0.w)], [0.0], [0]
    goal = 1.0 if control is None else float(stepper.c_value)
    path = {"z": np.zeros(asm.space.n), "lam": 0.0}
    crossings, counts = [], [0]  # the unloaded state: the linear K, positive definite

    def advance(t, dt, _):
        z_new, lam_new, q, r, n_it, flipped = stepper.newton(path["z"], path["lam"],
                                                             (t + dt) * goal)
        if flipped and control is None:
            raise _StepFailed("the tangent stiffness lost definiteness: the structure "
                              "buckles or snaps (a limit or bifurcation point) near load "
                              f"factor {path['lam']:.6g}..{lam_new:.6g}", [])
        path.update(z=z_new, lam=lam_new)
        if flipped:
            crossings.append(len(lams))
        states.append(make_state(asm, q, r, lam_new))
        lams.append(lam_new)
        its.append(n_it)
        counts.append(stepper.last_count)
        return False

    cuts = march(advance, steps, min_step,
                 lambda t, dt, cuts, failure: step_failure(t, dt, path["lam"], cuts, failure))
    return BeamNonlinearResult(model=model, load_factors=np.array(lams), states=states,
                               iterations=its, info={"step_cuts": cuts, "n_unknowns": asm.space.n,
                                     "definiteness_changes": crossings,
                                     "negative_eigenvalues": counts})
