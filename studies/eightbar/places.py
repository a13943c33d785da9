"""Where a model of the eight-bar suspension has its stress maxima, by flexure name: the
continuum's from its mesh's subdomains, the beam model's from its flexures' elements
(:mod:`.beam_model`)."""
from dataclasses import dataclass
from typing import Callable

import numpy as np

from ...fem import Model
from .continuum_model import group_at_vertex


@dataclass(frozen=True)
class Places:
    """Where a model's stress maxima are, named: ``peak(result)`` {"x", "y"(, "z") m,
    "flexure"} of a linear result's max_von_mises; ``element(result, e)`` the flexure (or
    link) of entry ``e`` of a nonlinear step's element stresses."""

    peak: Callable
    element: Callable


def continuum_places(model: Model) -> Places:
    """The mesh's subdomains name the continuum's maxima (:func:`group_at_vertex`)."""
    def peak(result):
        vertex = int(np.argmax(result.von_mises_nodal))
        where = dict(zip("xyz", (float(c) for c in model.mesh.mesh.p[:, vertex])))
        return {**where, "flexure": group_at_vertex(model, vertex)}

    return Places(peak, lambda result, e: group_at_vertex(model, int(model.mesh.mesh.t[0, e])))
