"""The design loop: evaluate, update (OC or MMA), record; resumable after every iteration."""
from dataclasses import dataclass, field

import numpy as np

from .mma import MMAState, mma_update
from .model import Discrete
from .oc import oc_update
from .problem import Problem
from .state import load_state, save_state


@dataclass
class Result:
    """A finished (or stopped) design. ``objective``: compliance (J) or displacement (m) of
    the final design; ``density``: physical densities by element (grid numbering);
    ``displacements``: each spring's mean displacement along its DOF (m)."""

    objective: float
    iterations: int
    volume_fraction: float
    converged: bool
    change: float
    density: np.ndarray
    displacements: dict
    constraints: dict
    history: np.ndarray = field(repr=False)
    problem: Problem = field(repr=False)

    def summary(self) -> dict:
        """The JSON-able numbers: objective, iterations, volume_fraction, converged and,
        where springs are named 'input' and 'output', u_in and u_out (m)."""
        out = {"objective": self.objective, "objective_kind": self.problem.objective.kind,
               "iterations": self.iterations, "volume_fraction": self.volume_fraction,
               "converged": self.converged, "change": self.change,
               "constraints": self.constraints,
               "displacements": {f"u_{k}": v for k, v in self.displacements.items()}}
        for key, name in (("u_in", "input"), ("u_out", "output")):
            if name in self.displacements:
                out[key] = self.displacements[name]
        return out


def _normalised(problem, values, grads):
    """MMA's constraints f_i <= 0, each scaled by its bound."""
    f, df = [], []
    for c, v, g in zip(problem.constraints, values, grads):
        if c.upper is not None:
            s = abs(c.upper) or 1.0
            f.append((v - c.upper) / s)
            df.append(g / s)
        if c.lower is not None:
            s = abs(c.lower) or 1.0
            f.append((c.lower - v) / s)
            df.append(-g / s)
    return f, df


def _resume(discrete, out_dir):
    """(z, iteration, change, history, mma state, scale) from out_dir, or a fresh start."""
    p = discrete.problem
    z = discrete.initial()
    fresh = (z, 0, np.inf, np.zeros((0, 2)), MMAState.start(z), 0.0)
    state = load_state(out_dir) if out_dir is not None else None
    if state is None:
        return fresh
    if str(state["digest"]) != p.digest():
        raise ValueError(f"--out {out_dir}: its state.npz belongs to another problem; "
                         "choose another folder or delete the file")
    mma = MMAState(*(state[k] for k in ("xold1", "xold2", "low", "upp")))
    return (state["z"], int(state["iteration"]), float(state["change"]), state["history"], mma,
            float(state["scale"]))


def optimize(problem: Problem, out_dir=None, progress=None) -> Result:
    """Optimise ``problem``; with ``out_dir`` the state is saved after every iteration and
    a rerun continues from it. ``progress(iteration, objective, volume, change)`` is called
    after each iteration."""
    discrete = Discrete(problem)
    p, opt = problem, problem.optimizer
    z, it, change, history, mma, scale = _resume(discrete, out_dir)
    while change > opt.tolerance and it < opt.max_iterations:
        it += 1
        ev = discrete.evaluate(z)
        if opt.kind == "oc":
            znew = oc_update(z, ev.objective_grad, ev.constraint_grads[0], p.volume_limit,
                             discrete.physical, discrete.lower, discrete.upper, opt.move)
        else:
            scale = scale or float(np.max(np.abs(ev.objective_grad)) or 1.0)
            sign = 1.0 if p.sense == "min" else -1.0
            f, df = _normalised(p, ev.constraints, ev.constraint_grads)
            znew = mma_update(mma, it, z, sign * ev.objective / scale, ev.objective_grad / scale,
                              f, df, discrete.lower, discrete.upper, opt.move)
        change = float(np.max(np.abs(znew - z)))
        z = znew
        history = np.vstack([history, [ev.objective, ev.physical.mean()]])
        if out_dir is not None:
            save_state(out_dir, z=z, iteration=it, change=change, history=history,
                       xold1=mma.xold1, xold2=mma.xold2, low=mma.low, upp=mma.upp, scale=scale,
                       digest=p.digest())
        if progress is not None:
            progress(it, ev.objective, float(ev.physical.mean()), change)
    final = discrete.evaluate(z)
    names = [c.response.kind + (f"_{c.response.spring}" if c.response.spring else "")
             for c in p.constraints]
    return Result(final.objective, it, float(final.physical.mean()), change <= opt.tolerance,
                  change, final.physical, final.displacements,
                  dict(zip(names, map(float, final.constraints))), history, p)
