"""The robust formulation's evaluation (topopt/robust.py): the eroded, intermediate and
dilated designs of one filtered field, each solved on its own, the objective the worst of
the three (a KS aggregate), the volume constraint on the dilated design with its limit
scaled so that the intermediate design meets the problem's, every other constraint on the
worst of the three in the direction of its bound."""
import numpy as np

from .evaluation import DesignResponses
from .robust import DESIGNS, worst


def design_volumes(d, z: np.ndarray) -> dict:
    """{design: volume fraction} of the three projections of design variables z."""
    filtered = d.filter.physical(d.P @ z)
    return {name: float(d.physical(z, filtered, eta).mean())
            for name, eta in zip(DESIGNS, d.problem.robust.thresholds)}


def volume_ratio(d, z: np.ndarray) -> float:
    """V_intermediate / V_dilated of z: the dilated design's volume limit is the problem's
    times this (Wang, Lazarov, Sigmund 2011, section 5), so that the blueprint meets it."""
    v = design_volumes(d, z)
    return v["intermediate"] / v["dilated"] if v["dilated"] > 0 else 1.0


def _solve_designs(d, z: np.ndarray) -> list:
    """Each design's (rho, state, displacements, objective, d objective / dz of sign *
    objective, constraint values, their gradients with respect to z)."""
    x = d.P @ z
    filtered = d.filter.physical(x)
    out = []
    for eta in d.problem.robust.thresholds:
        rho = d.physical(z, filtered, eta)
        state, disp, f0, g0, values, grads = d.responses(rho)

        def back(g, objective=False):
            return d.back(x, g, objective=objective, filtered=filtered, eta=eta)

        out.append((rho, state, disp, f0, back(g0, True), values, [back(g) for g in grads]))
    return out


def robust_evaluate(d, z: np.ndarray) -> DesignResponses:
    """The robust formulation's :class:`~.evaluation.DesignResponses` at z: ``physical``,
    ``u``, ``displacements`` and ``compliances`` those of the intermediate design (the
    blueprint), ``designs`` each design's objective and volume."""
    p = d.problem
    sign = 1.0 if p.sense == "min" else -1.0
    designs = _solve_designs(d, z)
    f0s = [D[3] for D in designs]
    f, g = worst(f0s, [sign * D[4] for D in designs], sign)
    values, grads = [], []
    for k, c in enumerate(p.constraints):
        if c.response.kind == "volume":
            v, gv = designs[2][5][k], designs[2][6][k]
            values.append(d.volume_ratio * v)
            grads.append(d.volume_ratio * gv)
            continue
        bound = 1.0 if c.upper is not None else -1.0
        v, gv = worst([D[5][k] for D in designs], [D[6][k] for D in designs], bound)
        values.append(v)
        grads.append(gv)
    rho, state, disp = designs[1][:3]
    grads = np.array(grads).reshape(len(values), d.n_variables)
    compliances = np.einsum("ik,ik->k", d.forces, state.U)
    summary = {name: {"objective": float(D[3]), "volume": float(D[0].mean())}
               for name, D in zip(DESIGNS, designs)}
    return DesignResponses(f, sign * g, np.array(values), grads, rho, state.U[:, 0], disp,
                           compliances, summary)
