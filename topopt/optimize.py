"""The design loop: evaluate, update (OC or MMA), record; resumable after every iteration."""
from dataclasses import dataclass, field, replace
from functools import lru_cache
from pathlib import Path

import numpy as np

from .mma import MMAState, mma_update
from .model import Discrete
from .oc import oc_update
from .problem import Problem
from .robust import VOLUME_UPDATE
from .robust_model import volume_ratio
from .state import load_state, save_state


@lru_cache(maxsize=1)
def _blas():
    """threadpoolctl's handle on the loaded BLAS libraries (OpenBLAS, MKL), found once
    (3 ms a search)."""
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController().select(user_api="blas")


@dataclass
class Result:
    """A finished (or stopped) design. ``objective``: compliance (J) or displacement (m) of
    the final design; ``density``: physical densities by element (grid numbering);
    ``displacements``: each spring's mean displacement along its DOF (m), in load case 1;
    ``compliances``: f_k.u_k of each load case (J)."""

    objective: float
    iterations: int
    volume_fraction: float
    converged: bool
    change: float
    density: np.ndarray
    displacements: dict
    constraints: dict
    compliances: tuple
    history: np.ndarray = field(repr=False)
    problem: Problem = field(repr=False)
    design: np.ndarray = field(repr=False, default=None)   # the design variables
    beta: float | None = None                               # the projection's last
    start_iterations: int = 0       # those of the small-displacement start (large ones)
    designs: dict | None = None     # robust: each design's objective and volume

    def summary(self) -> dict:
        """The JSON-able numbers: objective, iterations, volume_fraction, converged and,
        where springs are named 'input' and 'output', u_in and u_out (m); ``compliances``
        (J, f_c.u_c of each load case)."""
        out = {"objective": self.objective, "objective_kind": self.problem.objective.kind,
               "iterations": self.iterations, "volume_fraction": self.volume_fraction,
               "converged": self.converged, "change": self.change,
               "constraints": self.constraints,
               "displacements": {f"u_{k}": v for k, v in self.displacements.items()}}
        out["compliances"] = list(self.compliances)
        if self.problem.nonlinear is not None and len(self.history):
            # the first iteration evaluates the start: the small-displacement optimum
            out["large_displacements"] = {"start_iterations": self.start_iterations,
                                          "start_objective": float(self.history[0, 0])}
        for key, name in (("u_in", "input"), ("u_out", "output")):
            if name in self.displacements:
                out[key] = self.displacements[name]
        if self.problem.robust is not None:
            out["robust"] = robust_summary(self.problem, self.designs)
        return out


def robust_summary(problem, designs) -> dict:
    """The robust formulation's thresholds, filter radius (elements), the minimum solid and
    void sizes it imposes on the blueprint (m) and each design's objective and volume."""
    r = problem.robust
    sizes = r.minimum_sizes(problem.radius, problem.grid.dx)
    return {"thresholds": list(r.thresholds), "filter_radius": problem.radius,
            "min_solid": sizes["solid"], "min_void": sizes["void"],
            "min_hinge": r.min_size, "designs": designs}


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


def _resume(discrete, out_dir, start=None):
    """(z, iteration, change, history, mma state, scale, beta, iterations at beta) from
    out_dir, or a fresh start (from ``start``: (design variables, projection beta), if
    given)."""
    p = discrete.problem
    z, beta = (discrete.initial(), discrete.beta) if start is None else start
    fresh = (z, 0, np.inf, np.zeros((0, 2)), MMAState.start(z), 0.0, beta, 0)
    keys = ("digest", "z", "iteration", "change", "history", "xold1", "xold2", "low", "upp",
            "scale") + (("beta", "at_beta") if p.projection else ()) + (
            ("volume_ratio",) if p.robust else ())
    state = load_state(out_dir, keys) if out_dir is not None else None
    if state is None:
        return fresh
    if str(state["digest"]) != p.digest():
        raise ValueError(f"--out {out_dir}: its state.npz belongs to another problem; "
                         "choose another folder or delete the file")
    mma = MMAState(*(state[k] for k in ("xold1", "xold2", "low", "upp")))
    if p.robust:
        discrete.volume_ratio = float(state["volume_ratio"])
    beta = float(state["beta"]) if p.projection else None
    return (state["z"], int(state["iteration"]), float(state["change"]), state["history"], mma,
            float(state["scale"]), beta, int(state["at_beta"]) if p.projection else 0)


def _done(projection, change, tolerance, beta, at_beta) -> bool:
    """Converged: the change below tolerance, with a projection at its largest beta after
    at least one iteration there."""
    if projection is None:
        return change <= tolerance
    return change <= tolerance and beta >= projection.beta_max and at_beta > 0


def _step(discrete, ev, z, it, mma, scale):
    """The next design variables by OC or MMA; (z_new, objective scale)."""
    p, opt = discrete.problem, discrete.problem.optimizer
    if opt.kind == "oc":
        return oc_update(z, ev.objective_grad, ev.constraint_grads[0], p.volume_limit,
                         discrete.volume, discrete.lower, discrete.upper, opt.move), scale
    scale = scale or float(np.max(np.abs(ev.objective_grad)) or 1.0)
    sign = 1.0 if p.sense == "min" else -1.0
    f, df = _normalised(p, ev.constraints, ev.constraint_grads)
    return mma_update(mma, it, z, sign * ev.objective / scale, ev.objective_grad / scale, f, df,
                      discrete.lower, discrete.upper, opt.move), scale


def optimize(problem: Problem, out_dir=None, progress=None, start=None) -> Result:
    """Optimise ``problem``; with ``out_dir`` the state is saved after every iteration and
    a rerun continues from it. ``progress(iteration, objective, volume, change)`` is called
    after each iteration. ``start``: (design variables, projection beta or None) to begin
    from instead of the uniform start (clipped to the problem's passive bounds). A problem
    with large displacements starts from the optimum of its linear twin (the same problem,
    small displacements; saved in ``out_dir``/linear), where the load path already exists: a
    uniform grey start under the full load strains the grey material far beyond any
    solid's."""
    linear = None
    if problem.nonlinear is not None:
        twin = replace(problem, nonlinear=None)
        linear = optimize(twin, None if out_dir is None else Path(out_dir) / "linear", progress,
                          start)
        start = (linear.design, linear.beta)
    discrete = Discrete(problem)
    if start is not None:
        if np.shape(start[0]) != (discrete.n_variables,):
            raise ValueError(f"start: {np.shape(start[0])} design variables, the problem has "
                             f"{discrete.n_variables}")
        start = (np.clip(np.asarray(start[0], float), discrete.lower, discrete.upper),
                 start[1] if problem.projection else None)
    with _blas().limit(limits=1):
        result = _optimize(discrete, out_dir, progress, start)
    if linear is not None:
        result.start_iterations = linear.iterations
    return result


def _optimize(discrete, out_dir, progress, start=None) -> Result:
    """optimize()'s loop, on one BLAS thread: its vector operations are small (n of 1e4-1e5)
    and many, and with OpenBLAS's threads each waits on a thread hand-off (a dot product of
    20,000 values: 0.4 ms threaded, 0.01 ms on one thread, on two busy cores); PARDISO's
    factorisation of a 2-D grid of 40,000 DOFs is as fast on one MKL thread as on two and
    spends less CPU (200 x 100 inverter, 40 iterations at load 6.7: 6.0 s and 4.0 s CPU on
    one thread, 8.4 s and 5.6 s CPU on two)."""
    p = discrete.problem
    opt = p.optimizer
    z, it, change, history, mma, scale, beta, at_beta = _resume(discrete, out_dir, start)
    proj = p.projection
    while not _done(proj, change, opt.tolerance, beta, at_beta) and it < opt.max_iterations:
        it += 1
        discrete.beta = beta
        if p.robust is not None and (it - 1) % VOLUME_UPDATE == 0:
            discrete.volume_ratio = volume_ratio(discrete, z)
        ev = discrete.evaluate(z)
        znew, scale = _step(discrete, ev, z, it, mma, scale)
        change = float(np.max(np.abs(znew - z)))
        z = znew
        history = np.vstack([history, [ev.objective, ev.physical.mean()]])
        if proj:
            at_beta += 1
            beta = proj.next_beta(beta, at_beta, change, opt.tolerance)
            at_beta = 0 if beta != discrete.beta else at_beta
        if out_dir is not None:
            save_state(out_dir, z=z, iteration=it, change=change, history=history,
                       xold1=mma.xold1, xold2=mma.xold2, low=mma.low, upp=mma.upp, scale=scale,
                       digest=p.digest(), beta=beta if proj else 0.0, at_beta=at_beta,
                       volume_ratio=discrete.volume_ratio)
        if progress is not None:
            progress(it, ev.objective, float(ev.physical.mean()), change)
    discrete.beta = beta
    final = discrete.evaluate(z)
    names = [c.response.kind + (f"_{c.response.spring}" if c.response.spring else "")
             + ("" if c.response.springs else "_without_springs") for c in p.constraints]
    converged = _done(proj, change, opt.tolerance, beta, at_beta)
    return Result(final.objective, it, float(final.physical.mean()), converged,
                  change, final.physical, final.displacements,
                  dict(zip(names, map(float, final.constraints))),
                  tuple(map(float, final.compliances)), history, p, z, beta,
                  designs=final.designs)
