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

import numpy as np

from ..stepper import Stepper, step_failure
from ...newton import NonConvergenceError, check_step_arguments  # noqa: F401 (public here)
from ...stepping import march
from .assembly import Assembler
from .model import Beam3DModel
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
    stepper = Stepper(asm, control, tol, max_iterations)
    u, R = asm.space.reference()
    r0, _, _, T0, Tp0, _, fl0 = asm.evaluate(u, R, 0.0, tangent=False)
    states, lams, its = [make_state(asm, u, R, r0, 0.0, fl0, T0, Tp0)], [0.0], [0]
    goal = 1.0 if control is None else float(stepper.c_value)
    path = {"u": u, "R": R, "lam": 0.0}
    counts = [0]  # the unloaded state: the linear K, positive definite

    def advance(t, dt, _):
        (u_new, R_new), lam_new, ev, n_it, _ = stepper.step((path["u"], path["R"]), path["lam"],
                                                            (t + dt) * goal)
        path.update(u=u_new, R=R_new, lam=lam_new)
        states.append(make_state(asm, u_new, R_new, ev.r, lam_new, ev.fl, ev.T, ev.Tp))
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
