"""Geometrically exact (co-rotational) static analysis of a beam model, planar or spatial.

    res = solve_beam_nonlinear(model, [NodeFixed(0)], [NodalLoad(tip, fy=-P)], steps=20)
    res.path(tip)      # (n_steps + 1, 3): planar u, v, theta; spatial the displacement (m)

Load control: loads (dead) and prescribed DOFs scale with the load factor, stepped 0 -> 1.
Displacement control (``control=(node, dof, value)``; spatial: a translation DOF): the DOF is
stepped 0 -> value and the load factor is the extra unknown (Batoz & Dhatt), which passes
limit points of the load. Newton's method per step (:mod:`.stepper`; spatial rotations
updated multiplicatively, R <- exp(dw) R); a failing step is halved down to ``min_step``,
then NonConvergenceError (no unconverged answer is ever returned).
"""
from dataclasses import dataclass, field

import numpy as np

from ..newton import NonConvergenceError, check_step_arguments
from ..stepping import StepFailed, march
from .assembly import BeamAssembler
from .static import make_state
from .stepper import Stepper, negative_eigenvalues, step_failure  # noqa: F401 (public here)


@dataclass(frozen=True, eq=False)
class BeamNonlinearResult:
    """Converged steps; index 0 is the unloaded state. load_factors (n,); states: BeamState
    or Beam3DState per step (q, reactions, element forces, stresses); iterations per step."""

    model: object
    load_factors: np.ndarray
    states: list
    iterations: list
    info: dict = field(default_factory=dict)

    @property
    def final(self):
        return self.states[-1]

    def path(self, node: int) -> np.ndarray:
        """(n_steps + 1, 3) of ``node`` over the steps: planar u, v (m), theta (rad); spatial
        the displacement (m)."""
        if self.model.dim == 3:
            return np.array([s.u[int(node)] for s in self.states])
        return np.array([s.q[int(node)] for s in self.states])

    def reaction_path(self, node: int) -> np.ndarray:
        """(n_steps + 1, DOFs a node) reaction (N, N m) of a supported ``node``."""
        return np.array([s.reactions[int(node)] for s in self.states])


def solve_beam_nonlinear(model, supports, loads=(), steps: int = 10, control=None,
                         max_iterations: int = 30, tol: float = 1e-9,
                         min_step: float = 1e-4) -> BeamNonlinearResult:
    """Large-rotation static solve of a planar ``model`` under ``supports`` (NodeFixed,
    NodePrescribed) and ``loads`` (NodalLoad, dead), as :func:`solve_path`."""
    check_step_arguments(steps, max_iterations, tol, min_step)
    if model.superelements:
        raise ValueError("solve_beam_nonlinear: the model has superelements, which are "
                         "linear (small rotations only); use the linear solves")
    return solve_path(BeamAssembler(model, supports, loads), converged, steps, control,
                      max_iterations, tol, min_step)


def converged(asm, z, lam, ev=None):
    """The planar BeamState at unknowns ``z`` and load factor ``lam`` from its evaluation
    ``ev`` (default: evaluated here)."""
    ev = asm.at(z, lam, tangent=False) if ev is None else ev
    return make_state(asm, ev.q, ev.r, lam, w=ev.w)


def solve_path(asm, state, steps: int = 10, control=None, max_iterations: int = 30,
               tol: float = 1e-9, min_step: float = 1e-4) -> BeamNonlinearResult:
    """Large-rotation static solve of the model behind ``asm`` (a BeamModel's or a
    Beam3DModel's Assembler, with its supports and loads; ``state(asm, config, lam, ev)``
    its converged state) in ``steps`` equal increments of the load factor 0 -> 1, or with
    ``control=(node, dof, value)`` of that DOF 0 -> value (m or rad; the load factor then
    follows). Converged when |r| <= tol * (|applied| + |reactions|) (N) and the last
    increment |dz| <= sqrt(tol) |z|. Raises NonConvergenceError when a step cannot be cut
    below ``min_step`` (a fraction of the total); on the planar model also where the tangent
    loses definiteness under load control (a limit or bifurcation point)."""
    planar = asm.model.dim == 2
    stepper = Stepper(asm, control, tol, max_iterations)
    path = {"x": asm.space.start(), "lam": 0.0}
    states, lams, its = [state(asm, path["x"], 0.0)], [0.0], [0]
    goal = 1.0 if control is None else float(stepper.c_value)
    crossings, counts = [], [0]  # the unloaded state: the linear K, positive definite

    def advance(t, dt, _):
        x, lam, ev, n_it, flipped = stepper.step(path["x"], path["lam"], (t + dt) * goal)
        if planar and flipped and control is None:
            raise StepFailed("the tangent stiffness lost definiteness: the structure "
                             "buckles or snaps (a limit or bifurcation point) near load "
                             f"factor {path['lam']:.6g}..{lam:.6g}", [])
        path.update(x=x, lam=lam)
        if planar and flipped:
            crossings.append(len(lams))
        states.append(state(asm, x, lam, ev))
        lams.append(lam)
        its.append(n_it)
        counts.append(stepper.last_count)
        return False

    cuts = march(advance, steps, min_step,
                 lambda t, dt, cuts, failure: step_failure(t, dt, path["lam"], cuts, failure))
    info = {"step_cuts": cuts, "n_unknowns": asm.space.n, "negative_eigenvalues": counts}
    if planar:
        info["definiteness_changes"] = crossings
    return BeamNonlinearResult(model=asm.model, load_factors=np.array(lams), states=states,
                               iterations=its, info=info)

