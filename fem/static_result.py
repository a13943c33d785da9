"""The result of a linear static solve, and the support checks every solver shares."""
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
import skfem
from scipy.sparse.csgraph import connected_components

from . import stress
from .factor import SingularStiffness
from .boundary import component_indices
from .model import Model, rigid_body_modes
from .projection import nodal_average  # noqa: F401 (public here too)
from .solved import PeakStress, Solved


class UnderConstrainedError(SingularStiffness):
    """The supports leave rigid-body motions free."""


@dataclass(frozen=True, eq=False)
class StaticResult(PeakStress, Solved):
    """Fields and metrics of a static solve (:func:`flexfem.fem.solve_static`): ``model``
    (:class:`~.solved.Solved`) and

    Attributes
    ----------
    u : ndarray
        The DOF vector (m).
    displacement : ndarray
        (n_vertices, dim) displacement at the mesh vertices (m).
    von_mises_nodal : ndarray
        (n_vertices,) von Mises stress (Pa) from the stress components L2-projected onto
        continuous linear fields.
    von_mises_element_max : ndarray
        (n_elements,) the largest von Mises stress (Pa) over each element's quadrature points.
    reactions : dict
        {group: force vector (N)} on every supported group.
    applied_force : ndarray
        The assembled load vector (N).
    strain_energy : float
        1/2 u.K.u (J).
    solver : str
        The linear solver used: 'mkl-pardiso', 'cholmod', 'superlu' (direct), 'pmg-cg' or
        'amg-cg' (iterative); 'none' for no load.
    info : dict
        The solver's own figures (iterations, residual).
    nodal_stress_full : ndarray or None
        (n_vertices, 3, 3) the projected Cauchy stress components (Pa; 2-D with sigma_zz).
    face_motion, face_reactions : dict
        {group: (c_x, c_y, theta)} (m, m, rad) and {group: (F_x, F_y, M about the centroid)}
        (N, N, N m) of the rigid faces of a solve with them; in 3-D (c_x, c_y, c_z, theta_x,
        theta_y, theta_z) and (F_x, F_y, F_z, M_x, M_y, M_z).
    """

    u: np.ndarray
    displacement: np.ndarray
    von_mises_nodal: np.ndarray
    von_mises_element_max: np.ndarray
    reactions: dict
    applied_force: np.ndarray
    strain_energy: float
    solver: str = "none"
    info: dict = field(default_factory=dict)
    nodal_stress_full: np.ndarray | None = None
    face_motion: dict = field(default_factory=dict)
    face_reactions: dict = field(default_factory=dict)

    @property
    def nodal_stress(self) -> np.ndarray:
        """(n_vertices, dim, dim) Cauchy stress (Pa), L2-projected onto continuous linear
        fields (``nodal_stress_full`` has the 3 x 3 tensors)."""
        d = self.model.dim
        return self.nodal_stress_full[:, :d, :d]

    def stress_at(self, points, full: bool = False) -> np.ndarray:
        """(n, dim, dim) Cauchy stress (Pa) at ``points`` ((n, dim), m), evaluated in the
        element containing each point (no smoothing); (n, 3, 3) with ``full``. A point outside
        the body raises ValueError."""
        return stress.stress_at(self, points, full)

    def mean_displacement(self, group: str) -> np.ndarray:
        """Area- (or volume-) averaged displacement (m) of a boundary group or subdomain."""
        return mean_field(self.model, self.u, group)


def group_basis(model: Model, group: str):
    """The basis over a boundary group (a FacetBasis) or a subdomain, exact for products of
    the model's shape functions."""
    mesh = model.mesh
    if group in mesh.boundaries:
        return skfem.FacetBasis(model.cell_mesh, model.basis.elem, facets=mesh.facets(group),
                                intorder=2 * model.order)
    return model.basis.with_elements(mesh.elements(group))


def mean_field(model: Model, u: np.ndarray, group: str) -> np.ndarray:
    """Average of the vector field ``u`` (DOF vector) over a boundary group or subdomain."""
    basis = group_basis(model, group)
    uh = basis.interpolate(u)
    w = basis.dx
    return np.array([np.sum(uh[i] * w) for i in range(model.dim)]) / np.sum(w)


def vertex_displacement(model: Model, u: np.ndarray) -> np.ndarray:
    """(n_vertices, dim) displacement at the mesh vertices."""
    return np.stack([u[dofs] for dofs in model.basis.nodal_dofs], axis=1)


def rigid_body_dof_modes(model: Model) -> np.ndarray:
    """Rigid-body modes as DOF vectors, (n_dofs, 3) in 2-D or (n_dofs, 6) in 3-D."""
    locs = model.basis.doflocs
    comp = np.empty(model.n_dofs, dtype=int)
    for i, idx in enumerate(component_indices(model)):
        comp[idx] = i
    per_node = rigid_body_modes(locs)  # (n_modes, n_dofs, dim), evaluated at every DOF location
    return per_node[:, np.arange(model.n_dofs), comp].T


def check_supports(model: Model, D: np.ndarray) -> None:
    """Raise :class:`UnderConstrainedError` if the constrained DOFs ``D`` leave a rigid-body
    motion free."""
    modes = rigid_body_dof_modes(model)
    n_modes = modes.shape[1]
    if len(D) == 0:
        raise UnderConstrainedError(f"the model has no supports: all {n_modes} rigid-body modes are "
                                    "free; add a Fixed or Prescribed support")
    parts = body_parts(model)
    held = np.zeros(model.n_dofs, dtype=bool)
    held[D] = True
    for k, part in enumerate(parts):
        rows = modes[part[held[part]]]
        s = np.linalg.svd(rows, compute_uv=False) if len(rows) else np.zeros(0)
        free = n_modes - int(np.sum(s >= 1e-9 * max(np.abs(modes).max(), 1.0) * np.sqrt(len(D))))
        if not free:
            continue
        unheld = free_rigid_motions(rows, free)
        if len(parts) == 1:
            raise UnderConstrainedError(
                f"the supports leave {free} of {n_modes} rigid-body modes free: no support "
                f"holds {unheld}; add supports", free=unheld)
        where = model.basis.doflocs[:, part].mean(axis=1)
        raise UnderConstrainedError(
            f"the mesh has {len(parts)} disconnected parts and part {k + 1} (centred near "
            f"{np.round(where, 6).tolist()} m) has {free} of {n_modes} rigid-body modes free "
            f"(nothing holds {unheld}): connect it to the rest of the body or give it its own "
            "supports", free=unheld)


#: the rigid-body modes of rigid_body_dof_modes, in its order, in words
RIGID_MOTION_NAMES = {3: ("the rigid motion along x", "the rigid motion along y",
                          "the rotation about z"),
                      6: ("the rigid motion along x", "the rigid motion along y",
                          "the rigid motion along z", "the rotation about z",
                          "the rotation about x", "the rotation about y")}


def free_rigid_motions(rows: np.ndarray, free: int) -> str:
    """Words for the ``free`` rigid-body motions that the held rows ``rows`` ((n_held,
    n_modes) of rigid_body_dof_modes) leave free: each free combination of the modes (scaled
    to unit norm on the held DOFs' scale) by its largest mode, 'a combination of ...' where
    none has 90 % of it."""
    n_modes = rows.shape[1]
    names = RIGID_MOTION_NAMES[n_modes]
    if len(rows) == 0:
        return "any rigid motion"
    scale = np.maximum(np.linalg.norm(rows, axis=0), 1e-300)
    _, _, vt = np.linalg.svd(rows / scale, full_matrices=True)
    words = []
    for c in vt[n_modes - free:]:
        c = np.abs(c) / np.abs(c).sum()
        main = np.argsort(-c)
        words.append(names[main[0]] if c[main[0]] >= 0.9 else
                     "a combination of " + " and ".join(names[i] for i in main[:2] if c[i] > 0.05))
    return ", ".join(dict.fromkeys(words))


def body_parts(model: Model) -> list[np.ndarray]:
    """DOF indices of each connected part of the mesh (elements sharing a vertex are
    connected), largest part first."""
    mesh = model.mesh.mesh
    n_vertices = mesh.p.shape[1]
    # a chain through each element's vertices connects them all: enough for the components
    heads, tails = mesh.t[:-1].ravel(), mesh.t[1:].ravel()
    chain = sp.coo_matrix((np.ones(heads.size), (heads, tails)), shape=(n_vertices, n_vertices))
    n_parts, label = connected_components(chain, directed=False)
    if n_parts == 1:
        return [np.arange(model.n_dofs)]
    element_part = label[mesh.t[0]]
    dofs = model.basis.element_dofs
    parts = [np.unique(dofs[:, element_part == k]) for k in range(n_parts)]
    return sorted(parts, key=len, reverse=True)
