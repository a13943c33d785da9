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

import numpy as np

from ..newton import NonConvergenceError, check_step_arguments
from ..stepping import StepFailed, march
from .assembly import Assembler
from .model import BeamModel
from .static import BeamState, make_state
from .stepper import Stepper, negative_eigenvalues, step_failure  # noqa: F401 (public here)


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
    stepper = Stepper(asm, control, tol, max_iterations)
    ev0 = asm.evaluate(np.zeros(asm.space.n), 0.0, tangent=False)
    states, lams, its = [make_state(asm, ev0.q, ev0.r, 0.0, w=ev0.w)], [0.0], [0]
    goal = 1.0 if control is None else float(stepper.c_value)
    path = {"z": np.zeros(asm.space.n), "lam": 0.0}
    crossings, counts = [], [0]  # the unloaded state: the linear K, positive definite

    def advance(t, dt, _):
        z_new, lam_new, ev, n_it, flipped = stepper.step(path["z"], path["lam"], (t + dt) * goal)
        if flipped and control is None:
            raise StepFailed("the tangent stiffness lost definiteness: the structure "
                              "buckles or snaps (a limit or bifurcation point) near load "
                              f"factor {path['lam']:.6g}..{lam_new:.6g}", [])
        path.update(z=z_new, lam=lam_new)
        if flipped:
            crossings.append(len(lams))
        states.append(make_state(asm, ev.q, ev.r, lam_new))
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
