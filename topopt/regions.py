"""Where a support, load, spring or passive region acts: an edge, a box or a point (m)."""
from dataclasses import dataclass, field

import numpy as np

from .grid import Grid

EDGES = ("left", "right", "bottom", "top")


@dataclass(frozen=True)
class Region:
    """``kind`` 'edge' (value: one of EDGES), 'box' (value: ((x0, y0), (x1, y1)), m) or
    'point' (value: (x, y), m: the nearest node, inside the domain or within half a cell of
    it); ``key``: where a problem file gives it ('support[0].where'), for messages."""

    kind: str
    value: object
    key: str = field(default="", compare=False, repr=False)  # not in the problem's digest

    def nodes(self, grid: Grid) -> np.ndarray:
        """Indices of the grid's nodes in this region (never empty)."""
        tol = 1e-9 * max(grid.lx, grid.ly)
        return self._found(grid.nodes, grid, (tol, tol), tol, "node")

    def elements(self, grid: Grid) -> np.ndarray:
        """Indices of the elements whose centre lies in this region (a point: the element
        holding it; an edge: the row or column of elements along it)."""
        half = (0.5 * grid.dx * (1 + 1e-9), 0.5 * grid.dy * (1 + 1e-9))
        return self._found(grid.centres, grid, half, 1e-9 * max(grid.lx, grid.ly), "element")

    def _found(self, xy, grid: Grid, edge_tol: tuple, box_tol: float, what: str):
        """Indices of the points ``xy`` (m) in this region: within ``edge_tol`` (m, across x
        and y) of an edge, ``box_tol`` (m) of a box, or the nearest one to a point."""
        if self.kind == "edge":
            axis, at = {"left": (0, 0.0), "right": (0, grid.lx), "bottom": (1, 0.0),
                        "top": (1, grid.ly)}[self.value]
            found = np.flatnonzero(np.abs(xy[:, axis] - at) <= edge_tol[axis])
        elif self.kind == "box":
            found = np.flatnonzero(_inside(xy, self.value, box_tol))
        else:
            x, y = self.value
            reach = 0.5 * max(grid.dx, grid.dy)
            if not (-reach <= x <= grid.lx + reach and -reach <= y <= grid.ly + reach):
                raise ValueError(f"{self._named()} = {list(self.value)} lies outside the "
                                 f"design domain (0 to {grid.lx:g} by 0 to {grid.ly:g})")
            found = np.array([np.argmin(np.sum((xy - np.asarray(self.value)) ** 2, axis=1))])
        if found.size == 0:
            raise ValueError(f"{self._named()} = {self.value!r} holds no {what} of the grid")
        return found

    def _named(self) -> str:
        return f"{self.key}.{self.kind}" if self.key else self.kind

    def touching(self, grid: Grid) -> np.ndarray:
        """Indices of the elements with a node in this region."""
        nodes = np.zeros(grid.n_nodes, dtype=bool)
        nodes[self.nodes(grid)] = True
        return np.flatnonzero(nodes[grid.edofs[:, 0::2] // 2].any(axis=1))


def _inside(xy: np.ndarray, box, tol: float) -> np.ndarray:
    (x0, y0), (x1, y1) = box
    return ((xy[:, 0] >= min(x0, x1) - tol) & (xy[:, 0] <= max(x0, x1) + tol)
            & (xy[:, 1] >= min(y0, y1) - tol) & (xy[:, 1] <= max(y0, y1) + tol))


def parse_region(data, key: str) -> Region:
    """A Region from a TOML table such as ``{edge = "left"}``, ``{point = [0, 1]}`` or
    ``{box = [[0, 0], [1, 2]]}``; ValueError naming ``key`` otherwise."""
    if not isinstance(data, dict) or len(data) != 1:
        raise ValueError(f"{key} = {data!r}: give one of {{edge = ...}}, {{box = ...}}, "
                         "{point = ...}")
    (kind, value), = data.items()
    if kind == "edge":
        if value not in EDGES:
            raise ValueError(f"{key}.edge = {value!r}: choose one of {list(EDGES)}")
        return Region("edge", value, key)
    if kind == "point":
        return Region("point", _pair(value, f"{key}.point"), key)
    if kind == "box":
        if not isinstance(value, (list, tuple)) or len(value) != 2:
            raise ValueError(f"{key}.box = {value!r}: give [[x0, y0], [x1, y1]] (m)")
        return Region("box", (_pair(value[0], f"{key}.box"), _pair(value[1], f"{key}.box")),
                      key)
    raise ValueError(f"{key}: unknown region {kind!r}; choose edge, box or point")


def _pair(value, key: str) -> tuple:
    if (not isinstance(value, (list, tuple)) or len(value) != 2
            or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                       and np.isfinite(v) for v in value)):
        raise ValueError(f"{key} = {value!r}: give two finite numbers [x, y] (m)")
    return (float(value[0]), float(value[1]))
