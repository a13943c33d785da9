"""Density and sensitivity filters with top88's weights: w = max(0, r - distance), the
distance between element centres and the radius r in elements (Andreassen et al. 2011), and
the Helmholtz (PDE) filter of Lazarov & Sigmund (2011, "Filters in topology optimization
based on Helmholtz-type differential equations", IJNME 86:765-781, doi:10.1002/nme.3072):
-R^2 lap(rho_f) + rho_f = rho with zero normal derivative on the boundary, R = r / (2 sqrt 3)
(r the density filter's radius with about the same reach), on the grid's bilinear nodes,
element values the mean of their four nodes (top88's section 5.3)."""
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse as sp

from ..fem import checks
from .grid import Grid

KINDS = ("sensitivity", "density", "helmholtz", "none")


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


def helmholtz_matrices(grid: Grid, radius: float):
    """(K, T): K (nodes^2) = R^2 (Laplacian) + mass of unit square elements, R = radius /
    (2 sqrt 3) (elements); T (nodes x elements) spreads an element's value to its four
    nodes, 1/4 each. The filter is T^T K^-1 T."""
    R2 = (radius / (2.0 * np.sqrt(3.0))) ** 2
    lap = np.array([[4, -1, -2, -1], [-1, 4, -1, -2], [-2, -1, 4, -1], [-1, -2, -1, 4]]) / 6.0
    mass = np.array([[4, 2, 1, 2], [2, 4, 2, 1], [1, 2, 4, 2], [2, 1, 2, 4]]) / 36.0
    nodes = grid.edofs[:, 0::2] // 2          # counter-clockwise from the bottom-left
    ke = (R2 * lap + mass).ravel()
    rows, cols = np.repeat(nodes, 4, axis=1).ravel(), np.tile(nodes, (1, 4)).ravel()
    K = sp.csr_matrix((np.tile(ke, grid.n_elements), (rows, cols)),
                      shape=(grid.n_nodes, grid.n_nodes))
    T = sp.csr_matrix((np.full(nodes.size, 0.25), (nodes.ravel(),
                       np.repeat(np.arange(grid.n_elements), 4))),
                      shape=(grid.n_nodes, grid.n_elements))
    return K, T


@dataclass(frozen=True)
class Filter:
    """``kind`` 'sensitivity' (top88 ft=1: the objective's gradient is filtered, densities
    are not), 'density' (ft=2: physical densities = H x / Hs), 'helmholtz' (physical
    densities = T^T K^-1 T x, symmetric, factorised once) or 'none'; ``radius`` in
    elements."""

    grid: Grid
    kind: str = "sensitivity"
    radius: float = 1.5

    def __post_init__(self):
        checks.one_of("filter.kind", self.kind, KINDS)
        if not (np.isfinite(self.radius) and self.radius > 1.0) and self.kind != "none":
            raise ValueError(f"filter.radius = {self.radius!r}: must be > 1 (elements)")

    @cached_property
    def H(self) -> sp.csr_matrix:
        return filter_matrix(self.grid, self.radius)

    @cached_property
    def Hs(self) -> np.ndarray:
        return np.asarray(self.H.sum(axis=1)).ravel()

    @cached_property
    def _helmholtz(self):
        """(factorisation of K, T), made on first use."""
        from ..fem.factor import factor

        K, T = helmholtz_matrices(self.grid, self.radius)
        return factor(K, "spd"), T

    def _pde(self, x: np.ndarray) -> np.ndarray:
        solve, T = self._helmholtz
        return T.T @ solve(T @ x)

    def physical(self, x: np.ndarray) -> np.ndarray:
        """Physical densities from design densities."""
        if self.kind == "helmholtz":
            return self._pde(x)
        return self.H @ x / self.Hs if self.kind == "density" else x.copy()

    def back(self, x: np.ndarray, g: np.ndarray, objective: bool = False) -> np.ndarray:
        """The gradient with respect to x of a function whose gradient with respect to the
        physical densities is g; ``objective``: apply the sensitivity filter (heuristic,
        not a true gradient), as top88 does to the objective only."""
        if self.kind == "density":
            return self.H.T @ (g / self.Hs)
        if self.kind == "helmholtz":
            return self._pde(g)  # the filter is symmetric
        if self.kind == "sensitivity" and objective:
            return self.H @ (x * g) / self.Hs / np.maximum(1e-3, x)
        return g
