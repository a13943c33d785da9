"""Density and sensitivity filters with top88's weights: w = max(0, r - distance), the
distance between element centres and the radius r in elements (Andreassen et al. 2011)."""
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse as sp

from .grid import Grid

KINDS = ("sensitivity", "density", "none")


def filter_matrix(grid: Grid, radius: float) -> sp.csr_matrix:
    """H (n_elements^2, sparse): H[e, f] = max(0, radius - |c_e - c_f|), in elements."""
    reach = int(np.ceil(radius)) - 1
    ix, iy = np.divmod(np.arange(grid.n_elements), grid.nely)
    rows, cols, vals = [], [], []
    for di in range(-reach, reach + 1):
        for dj in range(-reach, reach + 1):
            w = radius - np.hypot(di, dj)
            jx, jy = ix + di, iy + dj
            ok = (jx >= 0) & (jx < grid.nelx) & (jy >= 0) & (jy < grid.nely)
            if w <= 0 or not ok.any():
                continue
            rows.append(np.flatnonzero(ok))
            cols.append(jx[ok] * grid.nely + jy[ok])
            vals.append(np.full(int(ok.sum()), w))
    n = grid.n_elements
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(n, n))


@dataclass(frozen=True)
class Filter:
    """``kind`` 'sensitivity' (top88 ft=1: the objective's gradient is filtered, densities
    are not), 'density' (ft=2: physical densities = H x / Hs) or 'none'; ``radius`` in
    elements."""

    grid: Grid
    kind: str = "sensitivity"
    radius: float = 1.5

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"filter.kind = {self.kind!r}: choose one of {list(KINDS)}")
        if not (np.isfinite(self.radius) and self.radius > 1.0) and self.kind != "none":
            raise ValueError(f"filter.radius = {self.radius!r}: must be > 1 (elements)")

    @cached_property
    def H(self) -> sp.csr_matrix:
        return filter_matrix(self.grid, self.radius)

    @cached_property
    def Hs(self) -> np.ndarray:
        return np.asarray(self.H.sum(axis=1)).ravel()

    def physical(self, x: np.ndarray) -> np.ndarray:
        """Physical densities from design densities."""
        return self.H @ x / self.Hs if self.kind == "density" else x.copy()

    def back(self, x: np.ndarray, g: np.ndarray, objective: bool = False) -> np.ndarray:
        """The gradient with respect to x of a function whose gradient with respect to the
        physical densities is g; ``objective``: apply the sensitivity filter (heuristic,
        not a true gradient), as top88 does to the objective only."""
        if self.kind == "density":
            return self.H.T @ (g / self.Hs)
        if self.kind == "sensitivity" and objective:
            return self.H @ (x * g) / self.Hs / np.maximum(1e-3, x)
        return g
