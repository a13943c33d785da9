"""One set of result names for the continuum and the beam models.

``SHARED[kind]`` lists the members that a continuum result of that kind
(:class:`.static_result.StaticResult`, :class:`.modal.Modes`,
:class:`.nonlinear_result.NonlinearResult`, :class:`.compliance.Compliance`,
:class:`.harmonic.HarmonicResult`) and the planar and spatial beam models' results give
under the same name. A member a beam model cannot give (a nodal stress field, an
point stress) is in its result's ``unsupported`` and raises :class:`NotOnModel`, an
AttributeError naming the member, the result and what the beam model gives instead.
"""
from operator import attrgetter

import numpy as np

SHARED = {
    "static": ("model", "u", "displacement", "mean_displacement", "reactions",
               "applied_force", "strain_energy", "solver", "info", "face_motion",
               "face_reactions", "max_von_mises", "max_von_mises_location",
               "max_von_mises_element", "von_mises_element_max"),
    "modes": ("model", "frequencies_hz", "shapes", "effective_mass", "total_mass",
              "effective_mass_fraction", "solver", "dominant_direction", "vertex_shape"),
    "nonlinear": ("model", "load_factors", "u", "reactions", "face_reactions",
                  "face_motion", "iterations", "applied", "info", "negative_eigenvalues", "stable",
                  "strain_valid",
                  "max_strain", "strain_limit", "preload_factors", "preload_end",
                  "preloaded", "preloading", "stress_at_step", "mean_displacement", "path",
                  "force_displacement", "max_von_mises", "max_von_mises_element",
                  "max_von_mises_location", "von_mises_element_max"),
    "compliance": ("face", "matrix", "point", "frame", "dim", "stiffness", "angle",
                   "centre_of_compliance", "parasitic", "principal", "support_stiffness",
                   "support_stiffness_ratio"),
    "harmonic": ("model", "frequencies_hz", "u", "method", "modes", "info",
                 "mean_displacement", "frf"),
}

# the co-rotational beam's local law is linear elastic on the undeformed section: its
# error grows as the strain, so 1 % of strain is the range it holds to about 1 %
BEAM_STRAIN_LIMIT = 0.01

NODAL_STRESS = "the beam model gives beam stresses per element (beam_stress)"


class NotOnModel(AttributeError):
    """A result member that this model's result cannot give."""


class BeamFace:
    """Base of the beam models' results: ``unsupported`` {member: (what it is, what the beam
    model gives instead)}; reading one raises :class:`NotOnModel`."""

    unsupported: dict = {}

    def __getattr__(self, name):
        if name in type(self).unsupported:
            what, instead = type(self).unsupported[name]
            raise NotOnModel(f"{type(self).__name__} has no {what} ({name}): {instead}")
        raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")


STATIC_UNSUPPORTED = {
    "von_mises_nodal": ("nodal stress field", NODAL_STRESS),
    "nodal_stress": ("nodal stress field", NODAL_STRESS),
    "nodal_stress_full": ("nodal stress field", NODAL_STRESS),
    "stress_at": ("stress field at points", NODAL_STRESS),
}

PATH_UNSUPPORTED = {
    "von_mises_nodal": ("nodal stress field", NODAL_STRESS),
}


def alias(path: str, doc: str) -> property:
    """A read-only property: the attribute at ``path`` (dotted: "state.max_stress") of the
    result, documented ``doc``."""
    return property(attrgetter(path), doc=doc)


def group_nodes(model, name) -> list:
    """The node indices of the beam model's group ``name``; ValueError naming the known
    groups."""
    if name not in model.groups:
        raise ValueError(f"group {name!r} is not one of the beam model's groups "
                         f"{sorted(model.groups)}")
    return list(model.groups[name].nodes)


def strain_per_step(fibre_stresses, E: float) -> np.ndarray:
    """(n,) largest extreme-fibre strain per step: the largest of each step's fibre stresses
    (Pa; NaN, an element without depths, skipped) over E; 0 where none has depths."""
    return np.array([float(np.fmax.reduce(np.ravel(s), initial=0.0)) / E
                     for s in fibre_stresses])


def reaction_vector(n_nodes: int, reactions: dict, per_node: int) -> np.ndarray:
    """The node reactions {node: (per_node,)} as one DOF vector (N, N m)."""
    r = np.zeros((n_nodes, per_node))
    for node, value in reactions.items():
        r[node] = value
    return r.ravel()


class BeamStateFace(BeamFace):
    """The static members both beam results give alike, from ``state`` (q (n_nodes, DOFs a
    node), reactions {node: vector}, max_stress), ``applied`` (the nodal load vector, or
    None) and ``beam_stress`` (Pa per element)."""

    @property
    def applied_force(self) -> np.ndarray:
        """The nodal load vector (N, N m per node)."""
        if self.applied is None:
            raise NotOnModel(f"{type(self).__name__} has no applied_force: this state was "
                             "built without its loads (a buckling's prebuckling state)")
        return self.applied

    @property
    def strain_energy(self) -> float:
        """1/2 q.K.q = 1/2 q.(f + reactions), J."""
        q = self.state.q
        r = reaction_vector(len(q), self.state.reactions, q.shape[1])
        return 0.5 * float(self.u @ (self.applied_force + r))

    von_mises_element_max = alias("beam_stress", "The beam stress per element (beam_stress), Pa.")
    max_von_mises = alias("state.max_stress", "Largest beam stress (beam_stress), Pa.")
    max_von_mises_element = alias("state.max_stress",
                                  "The beam stress has no smoothing: max_von_mises, Pa.")


class BeamPathFace(BeamFace):
    """The nonlinear members both beam paths give alike, from ``result`` (states,
    load_factors, info), ``step(k)`` (the static result of step k), ``applied`` (the nodal
    load vector at load factor 1, N), ``dim`` and ``fibre_stress(state)`` (Pa)."""

    unsupported = PATH_UNSUPPORTED
    strain_limit = BEAM_STRAIN_LIMIT
    preload_end = 0

    load_factors = alias("result.load_factors", "The load factor of each step (-).")
    iterations = alias("result.iterations", "The Newton iterations of each step.")
    info = alias("result.info", "The solver's own figures.")

    @property
    def u(self) -> list:
        """Per step the DOF vector (m, rad; per node the translations and rotations)."""
        return [s.q.ravel() for s in self.result.states]

    def mean_displacement(self, name: str, step: int = -1) -> np.ndarray:
        """(dim,) mean displacement of the group's nodes at ``step``, m."""
        return self.step(step).mean_displacement(name)

    def path(self, name: str) -> np.ndarray:
        """(n_steps + 1, dim) mean displacement of the group over the steps, m."""
        return np.array([self.mean_displacement(name, k) for k in range(len(self.load_factors))])

    @property
    def reactions(self) -> list:
        """Per step {group: force (N)} of every supported group, summed over its nodes."""
        return [self.step(k).reactions for k in range(len(self.load_factors))]

    def force_displacement(self, name: str) -> tuple:
        """(displacement (n, dim) m, force (n, dim) N) of the group: its reaction if it is
        supported, its face force if it is a rigid face, else the scaled applied load on its
        nodes."""
        if name in self.reactions[0]:
            force = np.array([r[name] for r in self.reactions])
        elif name in self.face_reactions[0]:
            force = np.array([r[name][:self.dim] for r in self.face_reactions])
        else:
            per_node = self.applied.reshape(self.result.model.n_nodes, -1)
            total = per_node[group_nodes(self.result.model, name), :self.dim].sum(axis=0)
            force = np.outer(self.load_factors, total)
        return self.path(name), force

    @property
    def negative_eigenvalues(self) -> list:
        """Per step the number of negative eigenvalues of the tangent stiffness at the
        converged state (a Sturm count of its LDL^T; None where it is singular)."""
        return self.info.get("negative_eigenvalues", [None] * len(self.load_factors))

    @property
    def stable(self) -> np.ndarray:
        """(n,) bool per step: the tangent stiffness is positive definite (no negative
        eigenvalue); False at a critical or unstable state."""
        return np.array([n == 0 for n in self.negative_eigenvalues], dtype=bool)

    @property
    def max_strain(self) -> np.ndarray:
        """(n,) per step the largest extreme-fibre strain: the fibre stress over E (-)."""
        return strain_per_step([self.fibre_stress(s) for s in self.result.states],
                               self.result.model.material.E)

    @property
    def strain_valid(self) -> np.ndarray:
        """(n,) bool per step: max_strain within strain_limit (BEAM_STRAIN_LIMIT, 1 %)."""
        return self.max_strain <= self.strain_limit

    @property
    def preload_factors(self) -> np.ndarray:
        """The beam model takes no preloads: all 0."""
        return np.zeros(len(self.load_factors))

    @property
    def preloaded(self) -> np.ndarray:
        return np.zeros_like(self.applied)

    @property
    def preloading(self) -> np.ndarray:
        return np.zeros(len(self.load_factors), dtype=bool)

    @property
    def max_von_mises(self) -> float:
        """Largest beam stress at the last step, Pa."""
        return self.step(-1).max_von_mises

    @property
    def max_von_mises_element(self) -> float:
        return self.step(-1).max_von_mises

    @property
    def max_von_mises_location(self) -> np.ndarray:
        """Where max_von_mises is at the last step, m."""
        return self.step(-1).max_von_mises_location

    @property
    def von_mises_element_max(self) -> np.ndarray:
        """(n_elements,) beam stress per element at the last step, Pa."""
        return self.stress_at_step(-1)[1]

    def stress_at_step(self, k: int) -> tuple:
        """(stress, stress) per element (Pa) at step ``k``: the continuum's (nodal, element
        maximum) pair; the beam stress has no smoothing (0 on an element without depths)."""
        stress = self.step(k).beam_stress
        return stress, stress
