"""The converged steps of a geometrically nonlinear solve."""
from dataclasses import dataclass, field

import numpy as np

from .boundary import group_dofs
from .hyperelastic import STRAIN_LIMIT, final_stress
from .solved import PeakStress, Solved
from .static_result import mean_field


@dataclass(frozen=True, eq=False)
class NonlinearResult(PeakStress, Solved):
    """The converged steps of a nonlinear solve (:func:`flexfem.fem.solve_nonlinear`); step 0
    is the unloaded state: ``model`` (:class:`~.solved.Solved`), the peaks of stress at the
    final step (:class:`~.solved.PeakStress`) and

    Attributes
    ----------
    load_factors : ndarray
        (n,) the load factor of each step (-).
    u : list of ndarray
        The DOF vector of each step (m).
    reactions : list of dict
        Per step {group: force (N)} of every supported group.
    face_reactions, face_motion : list of dict
        Per step {group: (F_x, F_y, M)} (N, N, N m about the current centroid) and {group:
        (c_x, c_y, theta)} (m, m, rad) of every rigid face (its reaction equal to the applied
        load on a free coordinate); in 3-D (F, M) and (c, rotation vector), 6 each.
    iterations : list of int
        Newton iterations per step.
    von_mises_nodal, von_mises_element_max : ndarray
        The final Cauchy von Mises stress (Pa), nodal from the L2 projection of the stress
        components onto linear fields, and the largest over each element's quadrature points.
    applied : ndarray
        The full-load vector f_ext (N).
    info : dict
        The solver's own figures.
    negative_eigenvalues : list
        Per step, the number of negative eigenvalues of the reduced tangent stiffness (None
        where it is singular, a critical state; None everywhere if not checked).
    max_strain : ndarray
        Per step, the largest absolute principal Green-Lagrange strain (-).
    strain_limit : float
        The validity limit (-) of St. Venant-Kirchhoff (:data:`.hyperelastic.STRAIN_LIMIT`).
    preload_factors : ndarray
        Per step, the factor (-) of the preloads (:mod:`.preload`; 0 -> 1 in the preload
        stage, where load_factors is 0, then 1; all 0 without preloads).
    preload_end : int
        The step that ends the preload stage (0 without preloads):
        ``load_factors[preload_end:]`` is the path of the scaled loads from the preloaded
        state.
    preloaded : ndarray
        The nodal preload vector (N).
    """

    load_factors: np.ndarray
    u: list
    reactions: list
    face_reactions: list
    face_motion: list
    iterations: list
    von_mises_nodal: np.ndarray
    von_mises_element_max: np.ndarray
    applied: np.ndarray
    info: dict = field(default_factory=dict)
    negative_eigenvalues: list = field(default_factory=list)
    max_strain: np.ndarray = field(default_factory=lambda: np.zeros(0))
    strain_limit: float = STRAIN_LIMIT
    preload_factors: np.ndarray | None = None
    preload_end: int = 0
    preloaded: np.ndarray | None = None

    def __post_init__(self):
        if self.preload_factors is None:
            object.__setattr__(self, "preload_factors", np.zeros(len(self.load_factors)))
        if self.preloaded is None:
            object.__setattr__(self, "preloaded", np.zeros_like(self.applied))

    @property
    def preloading(self) -> np.ndarray:
        """(n,) bool per step: a converged step of the preload stage."""
        steps = np.arange(len(self.load_factors))
        return (steps > 0) & (steps <= self.preload_end)

    @property
    def stable(self) -> np.ndarray:
        """(n,) bool per step: the reduced tangent stiffness is positive definite (a strict
        minimum of the potential energy); False at a critical or unstable state, and where
        not checked (negative_eigenvalues None)."""
        return np.array([n == 0 for n in self.negative_eigenvalues], dtype=bool)

    @property
    def strain_valid(self) -> np.ndarray:
        """(n,) bool per step: every Green-Lagrange principal strain within strain_limit."""
        return np.asarray(self.max_strain) <= self.strain_limit

    def stress_at_step(self, step: int) -> tuple[np.ndarray, np.ndarray]:
        """(nodal (n_vertices,), element max (n_elements,)) Cauchy von Mises stress (Pa) at
        ``step`` (as von_mises_nodal / von_mises_element_max at the last step)."""
        if not (isinstance(step, (int, np.integer)) and -len(self.u) <= step < len(self.u)):
            raise ValueError(f"step = {step!r} must index one of the {len(self.u)} steps")
        return final_stress(self.model, self.u[step])

    def mean_displacement(self, group: str, step: int = -1) -> np.ndarray:
        """Measure-averaged displacement (m) of a group at ``step``."""
        return mean_field(self.model, self.u[step], group)

    def path(self, group: str) -> np.ndarray:
        """(n_steps + 1, dim) mean displacement (m) of ``group`` over the steps."""
        return np.array([mean_field(self.model, u, group) for u in self.u])

    def force_displacement(self, group: str) -> tuple[np.ndarray, np.ndarray]:
        """(displacement (n, dim) m, force (n, dim) N) of ``group``: its reaction if it is
        supported, its face force if it is a rigid face, else the applied load (scaled loads and
        preloads) on its DOFs."""
        if group in self.reactions[0]:
            force = np.array([r[group] for r in self.reactions])
        elif group in self.face_reactions[0]:
            force = np.array([r[group][:self.model.dim] for r in self.face_reactions])
        else:
            dofs = group_dofs(self.model, group).values()
            total = np.array([self.applied[d].sum() for d in dofs])
            held = np.array([self.preloaded[d].sum() for d in dofs])
            force = np.outer(self.load_factors, total) + np.outer(self.preload_factors, held)
        return self.path(group), force

