"""The named places of a beam model, where the analysis face's supports and loads act
(:mod:`.face`)."""
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class BeamGroup:
    """The nodes (masters of rigid bodies) a group names, and the extent (dx, dy) of the face
    it stands for (m; zero for a point)."""

    nodes: tuple
    span: tuple = (0.0, 0.0)

    def __post_init__(self):
        nodes = tuple(int(n) for n in np.atleast_1d(self.nodes))
        if not nodes:
            raise ValueError("BeamGroup: a group needs at least one node")
        object.__setattr__(self, "nodes", nodes)
        object.__setattr__(self, "span", tuple(float(abs(s)) for s in self.span))

    @classmethod
    def of(cls, name: str, nodes, span, n_nodes: int) -> "BeamGroup":
        """Group ``name`` of a model of ``n_nodes`` nodes: ``nodes`` a BeamGroup or node
        indices with the face's extent ``span`` (m); ValueError naming a bad one."""
        if not isinstance(name, str) or not name:
            raise ValueError(f"group name {name!r} must be a non-empty string")
        g = nodes if isinstance(nodes, cls) else cls(nodes, span)
        outside = [n for n in g.nodes if not 0 <= n < n_nodes]
        if outside:
            raise ValueError(f"group {name!r}: node {outside[0]} outside 0..{n_nodes - 1}")
        return g
