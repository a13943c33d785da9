"""The spatial beam model's static and nonlinear results, read by group under the
continuum's names (:data:`.result_face.SHARED`); made by :mod:`.beam.spatial.face`."""
from dataclasses import dataclass

import numpy as np

from .beam.spatial.stress import peak_stress, section_stresses
from .result_face import STATIC_UNSUPPORTED, BeamPathFace, BeamStateFace, group_nodes


@dataclass(frozen=True, eq=False)
class Beam3DResult(BeamStateFace):
    """A spatial beam state read by group: the continuum StaticResult's names. ``state``:
    the Beam3DState (u, rotations, reactions, element forces); ``applied``: the nodal load
    vector (N, N m)."""

    model: object
    state: object
    supported: tuple = ()
    solver: str = "beam3d"
    applied: np.ndarray | None = None

    unsupported = STATIC_UNSUPPORTED
    dim = 3
    face_motion = property(lambda self: {}, doc="{}: the spatial face takes no rigid faces")
    face_reactions = property(lambda self: {}, doc="{}: the spatial face takes no rigid faces")

    @property
    def info(self) -> dict:
        return self.state.info

    @property
    def u(self) -> np.ndarray:
        """DOF vector (u_x, u_y, u_z m, rotation vector rad per node)."""
        return self.state.q.ravel()

    @property
    def displacement(self) -> np.ndarray:
        """(n_nodes, 3) displacement, m."""
        return self.state.u

    def mean_displacement(self, name: str) -> np.ndarray:
        """(3,) mean displacement of the group's nodes, m."""
        return self.state.u[group_nodes(self.model, name)].mean(axis=0)

    def rotation(self, name: str) -> np.ndarray:
        """(3,) mean rotation vector of the group's nodes, rad."""
        return self.state.rotation[group_nodes(self.model, name)].mean(axis=0)

    @property
    def reactions(self) -> dict:
        """{group: (F_x, F_y, F_z) N} of every supported group, summed over its nodes."""
        return {name: np.sum([self.state.reactions.get(n, np.zeros(6))[:3]
                              for n in group_nodes(self.model, name)], axis=0)
                for name in self.supported}

    @property
    def beam_stress(self) -> np.ndarray:
        """(n_elements,) largest von Mises bound of the rectangular sections per element, Pa
        (0 on a general section)."""
        vm = section_stresses(self.model, self.state.local_forces)["von_mises"]
        return np.nan_to_num(vm, nan=0.0).max(axis=1)

    @property
    def max_von_mises_location(self) -> np.ndarray:
        """Where max_von_mises is, m (on the element's centre line)."""
        _, e, xi = peak_stress(self.model, self.state.local_forces)
        a, b = self.model.nodes[self.model.elements[e]]
        return a + xi * (b - a)


@dataclass(frozen=True, eq=False)
class Beam3DPath(BeamPathFace):
    """Converged steps of a large-rotation spatial solve, read by group; ``applied``: the
    nodal load vector at load factor 1 (N, N m)."""

    model: object
    result: object
    supported: tuple = ()
    applied: np.ndarray | None = None

    dim = 3
    faces = ()

    def step(self, k: int = -1) -> Beam3DResult:
        """Step ``k`` as a Beam3DResult."""
        return Beam3DResult(self.model, self.result.states[k], self.supported)

    def fibre_stress(self, state) -> np.ndarray:
        return section_stresses(self.model, state.local_forces)["normal"]

    @property
    def face_motion(self) -> list:
        """Per step {}: the spatial face takes no rigid faces."""
        return [{} for _ in self.result.states]

    face_reactions = face_motion
