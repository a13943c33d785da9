"""Geometrically exact (co-rotational) static analysis of a spatial beam model.

    res = solve_beam3d_nonlinear(model, [Fixed(0)], [NodalLoad(tip, fz=P)], steps=20)
    res.path(tip)              # (n_steps + 1, 3) tip displacement

Load control: loads (dead) and prescribed DOFs scale with the load factor, stepped 0 -> 1.
Displacement control (``control=(node, dof, value)``, a translation DOF): that DOF is
stepped 0 -> value and the load factor is the extra unknown (Batoz & Dhatt). Newton's
method with the consistent tangent per step; nodal rotations are updated multiplicatively
(R <- exp(dw) R); a failing step is halved down to ``min_step``, then NonConvergenceError.
"""
from dataclasses import dataclass, field
import math

import numpy as np

from ..assembly import Factor, SingularBeamError
from ..nonlinear import negative_eigenvalues, step_failure
from ...newton import NonConvergenceError, check_step_arguments  # noqa: F401 (public here)
from ...stepping import StepFailed as _StepFailed
from ...stepping import march
from .assembly import Assembler
from ..supports import dof_index
from .model import Beam3DModel
from .rotations import logm
from .static import Beam3DState, make_state


@dataclass(frozen=True, eq=False)
class Beam3DNonlinearResult:
    """Converged steps; index 0 is the unloaded state. load_factors (n,); states: Beam3DState
    per step; iterations per step."""

    model: Beam3DModel
    load_factors: np.ndarray
    states: list
    iterations: list
    info: dict = field(default_factory=dict)

    @property
    def final(self) -> Beam3DState:
        return self.states[-1]

    def path(self, node: int) -> np.ndarray:
        """(n_steps + 1, 3) displacement (m) of ``node`` over the steps."""
        return np.array([s.u[int(node)] for s in self.states])


class _Stepper:
    """Newton iterations to a load factor (load control) or a control value."""

    def __init__(self, asm: Assembler, control, tol, max_iterations):
        self.asm, self.tol, self.max_iterations = asm, tol, max_iterations
        self.c_index = None
        if control is not None:
            node, dof, self.c_value = control
            k = dof_index(dof, 6)
            where = np.flatnonzero(asm.space.free == 6 * int(node) + k)
            if k > 2 or not len(where):
                raise ValueError(f"control = {control!r}: control a free translation DOF (not "
                                 "held, not on a rigid-link slave, not a rotation)")
            self.c_index = int(where[0])
            self.c_dof = 6 * int(node) + k

    def dr_dlam(self, K, T, Tp):
        """d(rz)/d(lam) = T^T (K T_p p - f_ext)."""
        p = self.asm.space.p_hat
        g = -(T.T @ self.asm.f_ext)
        if len(p):
            g = g + T.T @ (K @ (Tp @ p))
        return g

    def newton(self, u, R, lam, target):
        """Converged (u, R, lam, r, iterations, T, Tp, f_l) reaching ``target`` (a load
        factor, or the control DOF's displacement)."""
        space, history, dz = self.asm.space, [], None
        for it in range(1, self.max_iterations + 1):
            r, rz, K, T, Tp, Kf, fl = self.asm.evaluate(u, R, lam)
            ref = self._reference(r, lam)
            norm = float(np.linalg.norm(rz))
            if it > 1:
                history.append(norm / ref)
                if not math.isfinite(norm) or norm > 1e6 * ref:
                    raise _StepFailed("the residual diverged", history)
                size = np.linalg.norm(np.hstack([u, logm(R)]).ravel()[space.free])
                step = np.linalg.norm(dz)
                # at round-off: a correction of 1e-10 of the configuration (K dz is then
                # as small: a load-free rigid motion has no force scale to compare with)
                floor = step <= 1e-10 * size
                if (norm <= self.tol * ref and step <= math.sqrt(self.tol) * max(size, 1e-14)) \
                        or floor:
                    self.last_count = negative_eigenvalues(K)
                    return u, R, lam, r, it - 1, T, Tp, fl
            try:
                F = Factor(K)
                a, b = F.solve(np.column_stack([-rz, self.dr_dlam(Kf, T, Tp)])).T
            except SingularBeamError as exc:
                raise _StepFailed(str(exc), history) from None
            if self.c_index is None:
                dlam = target - lam if it == 1 else 0.0
            else:
                if abs(b[self.c_index]) < 1e-300:
                    raise _StepFailed("the control DOF does not respond to the load", history)
                now = u.ravel()[self.c_dof // 6 * 3 + self.c_dof % 6]
                dlam = (now + a[self.c_index] - target) / b[self.c_index]
            dz = a - dlam * b
            u, R = space.update(u, R, dz, dlam)
            lam = lam + dlam
        raise _StepFailed(f"no convergence in {self.max_iterations} iterations", history)

    def _reference(self, r, lam):
        ref = np.linalg.norm(lam * self.asm.f_ext) + np.linalg.norm(r[self.asm.space.held])
        return max(ref, 1e-12 * (1.0 + np.abs(self.asm.f_ext).max()))


def solve_beam3d_nonlinear(model: Beam3DModel, supports, loads=(), steps: int = 10,
                           control=None, max_iterations: int = 30, tol: float = 1e-9,
                           min_step: float = 1e-4) -> Beam3DNonlinearResult:
    """Large-rotation static solve of ``model`` under ``supports`` (Fixed, Prescribed) and
    ``loads`` (NodalLoad, dead forces and moments about fixed global axes) in ``steps``
    equal increments of the load factor 0 -> 1, or with ``control=(node, dof, value)`` of
    that translation DOF 0 -> value (m; the load factor follows). Converged when |r| <=
    tol * (|applied| + |reactions|) (N, N m) and the last increment is small. Raises
    NonConvergenceError when a step cannot be cut below ``min_step``."""
    check_step_arguments(steps, max_iterations, tol, min_step)
    asm = Assembler(model, supports, loads)
    stepper = _Stepper(asm, control, tol, max_iterations)
    u, R = asm.space.reference()
    r0, _, _, T0, Tp0, _, fl0 = asm.evaluate(u, R, 0.0, tangent=False)
    states, lams, its = [make_state(asm, u, R, r0, 0.0, fl0, T0, Tp0)], [0.0], [0]
    goal = 1.0 if control is None else float(stepper.c_value)
    path = {"u": u, "R": R, "lam": 0.0}
    counts = [0]  # the unloaded state: the linear K, positive definite

    def advance(t, dt, _):
        u_new, R_new, lam_new, r, n_it, T, Tp, fl = stepper.newton(
            path["u"], path["R"], path["lam"], (t + dt) * goal)
        path.update(u=u_new, R=R_new, lam=lam_new)
        states.append(make_state(asm, u_new, R_new, r, lam_new, fl, T, Tp))
        lams.append(lam_new)
        its.append(n_it)
        counts.append(stepper.last_count)
        return False

    cuts = march(advance, steps, min_step,
                 lambda t, dt, cuts, failure: step_failure(t, dt, path["lam"], cuts, failure))
    return Beam3DNonlinearResult(model=model, load_factors=np.array(lams), states=states,
                                 iterations=its, info={"step_cuts": cuts,
                                                       "n_unknowns": asm.space.n,
                                                       "negative_eigenvalues": counts})
