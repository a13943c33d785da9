"""What the results of the continuum's solves share: the model each solved (:class:`Solved`,
their base) and the peaks of a nodal von Mises field (:class:`PeakStress`)."""
from dataclasses import dataclass

import numpy as np

from .model import Model


@dataclass(frozen=True, eq=False)
class Solved:
    """The result of one solve: its first attribute, ``model`` (Model), the model solved."""

    model: Model


class PeakStress:
    """The peaks of a result's ``von_mises_nodal`` ((n_vertices,) Pa) and
    ``von_mises_element_max`` ((n_elements,) Pa): at the last step of a stepped solve."""

    @property
    def max_von_mises(self) -> float:
        """Largest nodal (recovered) von Mises stress, Pa."""
        return float(self.von_mises_nodal.max())

    @property
    def max_von_mises_element(self) -> float:
        """Largest von Mises stress (Pa) at any quadrature point."""
        return float(self.von_mises_element_max.max())

    @property
    def max_von_mises_location(self) -> np.ndarray:
        """Coordinates (m; the reference ones of a stepped solve) of the vertex with the
        largest nodal von Mises stress."""
        return self.model.mesh.mesh.p[:, int(np.argmax(self.von_mises_nodal))]
