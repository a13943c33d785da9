"""The spatial beam model's large-rotation solve: the beam models' one
(:func:`flexfem.fem.beam.nonlinear.solve_path`), its configuration (u, R).

    res = solve_beam3d_nonlinear(model, [NodeFixed(0)], [NodalLoad(tip, fz=P)], steps=20)
    res.path(tip)              # (n_steps + 1, 3) tip displacement
"""
from ..nonlinear import (BeamNonlinearResult, NonConvergenceError,  # noqa: F401
                         check_step_arguments, solve_path)
from .assembly import SpatialAssembler
from .model import Beam3DModel
from .static import make_state


def converged(asm, config, lam, ev=None):
    """The Beam3DState at the configuration (u, R) and load factor ``lam``."""
    ev = asm.at(config, lam, tangent=False) if ev is None else ev
    return make_state(asm, *config, ev.r, lam, ev.fl, ev.T, ev.Tp)


def solve_beam3d_nonlinear(model: Beam3DModel, supports, loads=(), steps: int = 10,
                           control=None, max_iterations: int = 30, tol: float = 1e-9,
                           min_step: float = 1e-4) -> BeamNonlinearResult:
    """Large-rotation static solve of a spatial ``model`` under ``supports`` (NodeFixed,
    NodePrescribed) and ``loads`` (NodalLoad, dead forces and moments about fixed global axes);
    ``control=(node, dof, value)`` a translation DOF (m); otherwise as
    :func:`..nonlinear.solve_path`."""
    check_step_arguments(steps, max_iterations, tol, min_step)
    return solve_path(SpatialAssembler(model, supports, loads), converged, steps, control,
                      max_iterations, tol, min_step)
