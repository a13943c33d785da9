"""One step of the method of moving asymptotes (Svanberg 1987) through mmapy's ``mmasub``;
the asymptotes and the last two designs are the state a resumed run needs.

mmapy's subproblem solver multiplies (n, 1) by (1, 1) arrays thousands of times a step; with
OpenBLAS's threads each product waits on a thread hand-off, eight times the whole step's
single-threaded time at 20,000 variables, so ``mmasub`` runs with one BLAS thread."""
from dataclasses import dataclass
from functools import lru_cache

import numpy as np


@lru_cache(maxsize=1)
def _threadpools():
    """threadpoolctl's view of the loaded BLAS libraries, found once (3 ms a search)."""
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController()


@dataclass
class MMAState:
    """What MMA carries from one iteration to the next (column vectors of n)."""

    xold1: np.ndarray
    xold2: np.ndarray
    low: np.ndarray
    upp: np.ndarray

    @classmethod
    def start(cls, z: np.ndarray) -> "MMAState":
        col = z.reshape(-1, 1).copy()
        return cls(col, col.copy(), np.zeros_like(col), np.ones_like(col))


def mma_update(state: MMAState, iteration: int, z, f0, df0, fvals, dfdx, lower, upper,
               move: float) -> np.ndarray:
    """The next design variables of min f0 s.t. fvals <= 0 (normalised constraints);
    ``iteration`` counts from 1; updates ``state`` in place."""
    from mmapy import mmasub

    n, m = z.size, max(len(fvals), 1)
    fval = np.asarray(fvals, dtype=float).reshape(-1, 1) if len(fvals) else -np.ones((1, 1))
    dfdx = np.asarray(dfdx, dtype=float).reshape(len(fvals), n) if len(fvals) else np.zeros((1, n))
    xcol = z.reshape(-1, 1)
    zeros, ones = np.zeros((n, 1)), np.ones((n, 1))  # pinned variables are clipped after
    with _threadpools().limit(limits=1, user_api="blas"):
        xmma, *_, low, upp = mmasub(
            m, n, iteration, xcol, zeros, ones, state.xold1, state.xold2, float(f0),
            np.asarray(df0, dtype=float).reshape(-1, 1), fval, dfdx, state.low, state.upp,
            1.0, np.zeros((m, 1)), np.full((m, 1), 1000.0), np.ones((m, 1)), move=move)
    state.xold2, state.xold1 = state.xold1, xcol.copy()
    state.low, state.upp = low, upp
    return np.clip(xmma.ravel(), lower, upper)
