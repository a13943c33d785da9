"""The beam models' static and nonlinear results, planar and spatial, read by group under the
continuum's names (:data:`.result_face.SHARED`); made by :mod:`.beam.face`."""
from dataclasses import dataclass, field

import numpy as np

from .beam.spatial.stress import peak_stress, section_stresses
from .result_face import STATIC_UNSUPPORTED, BeamPathFace, BeamStateFace, group_nodes


@dataclass(frozen=True, eq=False)
class BeamResult(BeamStateFace):
    """A beam state read by group: the continuum StaticResult's names. ``state``: the
    BeamState or Beam3DState (q, element forces, node reactions); ``faces``: the rigid faces'
    groups (planar), ``face_loads``: {face: (F_x, F_y, M)} applied on each;
    ``applied_force``: the nodal load vector (N, N m)."""

    model: object
    state: object
    supported: tuple = ()
    faces: tuple = ()  # the groups of the solve's rigid_faces
    face_loads: dict = field(default_factory=dict)
    applied: np.ndarray | None = None

    unsupported = STATIC_UNSUPPORTED

    @property
    def dim(self) -> int:
        return self.model.dim

    @property
    def solver(self) -> str:
        return "beam" if self.dim == 2 else "beam3d"

    @property
    def info(self) -> dict:
        return self.state.info

    @property
    def u(self) -> np.ndarray:
        """DOF vector (per node the translations, m, and the rotation(s), rad)."""
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
        """(n_nodes, dim) displacement, m."""
        return self.state.q[:, :self.dim]

    def mean_displacement(self, name: str) -> np.ndarray:
        """(dim,) mean displacement of the group's nodes, m."""
        return self.state.q[group_nodes(self.model, name), :self.dim].mean(axis=0)

    def rotation(self, name: str):
        """Mean rotation of the group's nodes, rad: planar a number (counter-clockwise),
        spatial the (3,) rotation vector."""
        nodes = group_nodes(self.model, name)
        if self.dim == 2:
            return float(self.state.q[nodes, 2].mean())
        return self.state.rotation[nodes].mean(axis=0)

    @property
    def reactions(self) -> dict:
        """{group: force (dim,) N} of every supported group, summed over its nodes."""
        per_node, dim = self.state.q.shape[1], self.dim
        return {name: np.sum([self.state.reactions.get(n, np.zeros(per_node))[:dim]
                              for n in group_nodes(self.model, name)], axis=0)
                for name in self.supported}

    @property
    def beam_stress(self) -> np.ndarray:
        """(n_elements,) largest beam stress per element, Pa: planar |N|/A + |M| c / I,
        spatial the rectangles' von Mises bound (0 on an element without depths)."""
        if self.dim == 2:
            return np.nan_to_num(self.state.stress, nan=0.0)
        vm = section_stresses(self.model, self.state.local_forces)["von_mises"]
        return np.nan_to_num(vm, nan=0.0).max(axis=1)

    @property
    def max_von_mises_location(self) -> np.ndarray:
        """Where max_von_mises is, m (on the element's centre line)."""
        if self.dim == 2:
            return np.asarray(self.state.max_stress_location[2], dtype=float)
        _, e, xi = peak_stress(self.model, self.state.local_forces)
        a, b = self.model.nodes[self.model.elements[e]]
        return a + xi * (b - a)


@dataclass(frozen=True, eq=False)
class BeamPath(BeamPathFace):
    """Converged steps of a large-rotation solve, read by group as the continuum's
    NonlinearResult. ``result``: the BeamNonlinearResult (states
    per step); ``faces``: the rigid faces' groups (planar); ``face_loads``: {face: (F_x,
    F_y, M)} at load factor 1; ``applied``: the nodal load vector at load factor 1 (N, N m)."""

    model: object
    result: object
    supported: tuple = ()
    faces: tuple = ()
    face_loads: dict = field(default_factory=dict)
    applied: np.ndarray | None = None

    @property
    def dim(self) -> int:
        return self.model.dim

    def step(self, k: int = -1) -> BeamResult:
        """Step ``k`` as a BeamResult."""
        return BeamResult(self.model, self.result.states[k], self.supported)

    def fibre_stress(self, state) -> np.ndarray:
        if self.dim == 2:
            return state.stress
        return section_stresses(self.model, state.local_forces)["normal"]

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


Beam3DResult, Beam3DPath = BeamResult, BeamPath  # the spatial model's names: the same classes
