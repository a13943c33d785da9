"""The planar beam model's static and nonlinear results, read by group under the continuum's
names (:data:`.result_face.SHARED`); made by :mod:`.beam.face`."""
from dataclasses import dataclass, field

import numpy as np

from .result_face import STATIC_UNSUPPORTED, BeamPathFace, BeamStateFace, group_nodes


@dataclass(frozen=True, eq=False)
class BeamResult(BeamStateFace):
    """A beam state read by group: the continuum StaticResult's names. ``state``: the
    BeamState (q, element forces, stresses, node reactions); ``face_loads``: {face: (F_x,
    F_y, M)} applied on each rigid face; ``applied_force``: the nodal load vector (N, N m)."""

    model: object
    state: object
    supported: tuple = ()
    solver: str = "beam"
    faces: tuple = ()  # the groups of the solve's rigid_faces
    face_loads: dict = field(default_factory=dict)
    applied: np.ndarray | None = None

    unsupported = STATIC_UNSUPPORTED
    dim = 2

    @property
    def info(self) -> dict:
        return self.state.info

    @property
    def u(self) -> np.ndarray:
        """DOF vector (u, v m, theta rad per node)."""
        return self.state.q.ravel()

    @property
    def face_motion(self) -> dict:
        """{face: (c_x, c_y, theta)} (m, m, rad) of each rigid face's node."""
        return {f: self.state.q[group_nodes(self.model, f)[0]].copy() for f in self.faces}

    @property
    def face_reactions(self) -> dict:
        """{face: (F_x, F_y, M)} (N, N, N m) on each rigid face's node: the support's
        reaction on a held coordinate, the applied load on a free one."""
        return {f: self.state.reactions.get(group_nodes(self.model, f)[0], np.zeros(3))
                + self.face_loads.get(f, 0.0) for f in self.faces}

    @property
    def displacement(self) -> np.ndarray:
        """(n_nodes, 2) displacement, m."""
        return self.state.displacement

    def mean_displacement(self, name: str) -> np.ndarray:
        """(2,) mean displacement of the group's nodes, m."""
        return self.state.q[group_nodes(self.model, name), :2].mean(axis=0)

    def rotation(self, name: str) -> float:
        """Mean rotation of the group's nodes, rad (counter-clockwise)."""
        return float(self.state.q[group_nodes(self.model, name), 2].mean())

    @property
    def reactions(self) -> dict:
        """{group: (F_x, F_y) N} of every supported group, summed over its nodes."""
        out = {}
        for name in self.supported:
            rows = [self.state.reactions.get(n, np.zeros(3))[:2]
                    for n in group_nodes(self.model, name)]
            out[name] = np.sum(rows, axis=0)
        return out

    @property
    def beam_stress(self) -> np.ndarray:
        """(n_elements,) largest beam stress |N|/A + |M| c / I per element, Pa (0 on an
        element without its outer-fibre distance c)."""
        return np.nan_to_num(self.state.stress, nan=0.0)

    @property
    def max_von_mises_location(self) -> np.ndarray:
        """Where max_von_mises is, m (on the element's centre line)."""
        return np.asarray(self.state.max_stress_location[2], dtype=float)


@dataclass(frozen=True, eq=False)
class BeamPath(BeamPathFace):
    """Converged steps of a large-rotation solve, read by group as the continuum's
    NonlinearResult. ``result``: the BeamNonlinearResult (states per step); ``faces``: the
    rigid faces' groups; ``face_loads``: {face: (F_x, F_y, M)} at load factor 1;
    ``applied``: the nodal load vector at load factor 1 (N, N m)."""

    model: object
    result: object
    supported: tuple = ()
    faces: tuple = ()
    face_loads: dict = field(default_factory=dict)
    applied: np.ndarray | None = None

    dim = 2

    def step(self, k: int = -1) -> BeamResult:
        """Step ``k`` as a BeamResult."""
        return BeamResult(self.model, self.result.states[k], self.supported)

    def fibre_stress(self, state) -> np.ndarray:
        return state.stress

    @property
    def face_motion(self) -> list:
        """Per step {face: (c_x, c_y, theta)} (m, m, rad) of each rigid face's node."""
        return [{f: s.q[group_nodes(self.model, f)[0]].copy() for f in self.faces}
                for s in self.result.states]

    @property
    def face_reactions(self) -> list:
        """Per step {face: (F_x, F_y, M)} (N, N, N m) on each rigid face's node: the support's
        reaction on a held coordinate, the applied load on a free one."""
        out = []
        for lam, s in zip(self.load_factors, self.result.states):
            row = {}
            for f in self.faces:
                node = group_nodes(self.model, f)[0]
                row[f] = s.reactions.get(node, np.zeros(3)) + lam * self.face_loads.get(f, 0.0)
            out.append(row)
        return out
