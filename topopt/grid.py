"""A structured grid of nelx x nely rectangles on [0, Lx] x [0, Ly] (m).

Elements are numbered column by column from the bottom-left (``e = ix * nely + iy``), nodes
likewise (``n = ix * (nely + 1) + iy``), DOFs ``2n`` (x) and ``2n + 1`` (y); y points up.
"""
from dataclasses import dataclass
from functools import cached_property

import numpy as np


@dataclass(frozen=True)
class Grid:
    """nelx x nely elements over a domain lx x ly (m)."""

    nelx: int
    nely: int
    lx: float
    ly: float

    def __post_init__(self):
        for key in ("nelx", "nely"):
            value = getattr(self, key)
            if not isinstance(value, int) or isinstance(value, bool) or value < 1:
                raise ValueError(f"{key} = {value!r}: must be an integer >= 1")
        for key in ("lx", "ly"):
            value = getattr(self, key)
            if not np.isfinite(value) or value <= 0:
                raise ValueError(f"{key} = {value!r}: must be a length > 0 (m)")

    @property
    def dx(self) -> float:
        return self.lx / self.nelx

    @property
    def dy(self) -> float:
        return self.ly / self.nely

    @property
    def n_elements(self) -> int:
        return self.nelx * self.nely

    @property
    def n_nodes(self) -> int:
        return (self.nelx + 1) * (self.nely + 1)

    @property
    def n_dofs(self) -> int:
        return 2 * self.n_nodes

    @cached_property
    def nodes(self) -> np.ndarray:
        """(n_nodes, 2) coordinates (m)."""
        ix, iy = np.divmod(np.arange(self.n_nodes), self.nely + 1)
        return np.column_stack([ix * self.dx, iy * self.dy])

    @cached_property
    def centres(self) -> np.ndarray:
        """(n_elements, 2) element centres (m)."""
        ix, iy = np.divmod(np.arange(self.n_elements), self.nely)
        return np.column_stack([(ix + 0.5) * self.dx, (iy + 0.5) * self.dy])

    @cached_property
    def edofs(self) -> np.ndarray:
        """(n_elements, 8) DOFs of each element, nodes counter-clockwise from bottom-left."""
        ix, iy = np.divmod(np.arange(self.n_elements), self.nely)
        n1 = ix * (self.nely + 1) + iy
        n2 = n1 + self.nely + 1
        corners = np.column_stack([n1, n2, n2 + 1, n1 + 1])
        return np.stack([2 * corners, 2 * corners + 1], axis=2).reshape(-1, 8)

    def image(self, values: np.ndarray) -> np.ndarray:
        """Element values as an (nely, nelx) image, row 0 at the top."""
        return np.asarray(values).reshape(self.nelx, self.nely).T[::-1]
