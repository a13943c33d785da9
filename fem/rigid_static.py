"""Rigid faces in the linear static solve: ``solve_static(..., rigid_faces=[...])``.

The faces' DOFs are eliminated in favour of their generalised coordinates (c, theta: 3 in
2-D, 6 in 3-D) linearised about the reference configuration, u_a = c + theta x (X_a - X_c):
the small-displacement limit of :mod:`.rigid_face`'s kinematics. Prescribed coordinates
are imposed, free ones carry the face's force and moment.
"""
import numpy as np

from . import linsolve
from .boundary import component_indices, constrained_dofs, load_vector
from .model import von_mises
from .rigid_face import ReducedSpace
from .solver_choice import choose_solver
from .static_result import (StaticResult, UnderConstrainedError, check_supports, nodal_average,
                     vertex_displacement)


def check_held(model, space: ReducedSpace) -> None:
    """Raise UnderConstrainedError if the supports and rigid faces of ``space`` leave a
    rigid-body motion free."""
    if not space.faces:
        check_supports(model, space.D)
        return
    rows = space.held_mode_rows(model)
    n_modes = 3 if model.dim == 2 else 6
    s = np.linalg.svd(rows, compute_uv=False) if len(rows) else np.zeros(0)
    free = n_modes - int(np.sum(s > 1e-9 * max(np.abs(rows).max(initial=0.0), 1e-300)))
    if free:
        raise UnderConstrainedError(f"the supports and rigid faces leave {free} of {n_modes} "
                                    "rigid-body modes free; prescribe more coordinates or add "
                                    "supports")


def linear_map(space: ReducedSpace) -> tuple:
    """(T, u_p): the linearised map u = T z + u_p (m) of the unknowns z, with u_p the
    prescribed displacements and face coordinates at full load."""
    T = space.jacobian(np.zeros(space.n), 0.0)
    u_p = np.zeros(space.n_dofs)
    u_p[space.D] = space.xD
    for fk in space.faces:
        u_p[fk.dofs] = fk.linear_displacement(fk.face.values(space.dim))  # 0 where free
    return T.tocsr(), u_p


def face_results(space: ReducedSpace, z: np.ndarray, r: np.ndarray):
    """({group: (force, moment)} (N, N m about the centroid), {group: (translation,
    rotation)} (m, rad)) of each face for unknowns ``z`` and nodal forces ``r`` = K u - f:
    2-D (F_x, F_y, M) and (c_x, c_y, theta), 3-D (F, M) and (c, theta) (6 each)."""
    qs = space.coordinates(z, 1.0)
    forces = {fk.face.group: fk.generalised_force(r, np.zeros_like(q))
              for fk, q in zip(space.faces, qs)}
    return forces, {fk.face.group: q for fk, q in zip(space.faces, qs)}


def solve_static_faces(model, supports, loads, rigid_faces, solver: str = "auto") -> StaticResult:
    """Linear static solve with rigid faces (2-D or 3-D); see :func:`.static.solve_static`.
    The result's ``face_motion`` and ``face_reactions`` hold each face's coordinates, 2-D
    (c_x, c_y, theta), 3-D (c_x, c_y, c_z, theta_x, theta_y, theta_z) (m, rad), and its
    force and moment about the face centroid, (F_x, F_y, M) or (F_x, F_y, F_z, M_x, M_y,
    M_z) (N, N m): on a free coordinate the applied load, on a prescribed one the reaction."""
    if solver == "amg":
        raise ValueError(f"solver = {solver!r} with rigid faces: use 'direct' or 'auto'")
    choose_solver(1, model.dim, solver)  # validates the name
    D, xD, owned = constrained_dofs(model, supports)
    space = ReducedSpace(model, D, xD, rigid_faces)
    check_held(model, space)
    K = model.stiffness
    f = load_vector(model, loads)
    T, u_p = linear_map(space)
    rhs = T.T @ (f - K @ u_p) + space.applied(1.0)
    z = np.zeros(space.n)
    if np.any(rhs):
        z = linsolve.solve_and_check((T.T @ K @ T).tocsr(), rhs, kind="spd", rtol=1e-6)
    u = u_p + T @ z
    r = K @ u - f
    reactions = {g: np.array([r[np.intersect1d(dofs, idx)].sum()
                              for idx in component_indices(model)])
                 for g, dofs in owned.items()}
    face_forces, motion = face_results(space, z, r)
    sig = model.stress(u)
    nodal = nodal_average(model, sig)
    return StaticResult(
        model=model, u=u, displacement=vertex_displacement(model, u),
        von_mises_nodal=von_mises(nodal), nodal_stress_full=np.moveaxis(nodal, 2, 0),
        von_mises_element_max=von_mises(sig).max(axis=1), reactions=reactions,
        applied_force=np.array([f[idx].sum() for idx in component_indices(model)]),
        strain_energy=0.5 * float(u @ (K @ u)), solver=linsolve.direct_backend("spd"),
        info={"n_dofs": model.n_dofs, "n_unknowns": space.n}, face_motion=motion,
        face_reactions=face_forces)
