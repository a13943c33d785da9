"""Compliance of a rigid face: ``compliance_matrix(model, supports, face) -> Compliance``.

The face (a boundary group) is made rigid with all its coordinates free and loaded by
unit generalised loads; the 3 x 3 compliance relates the face's (u_x, u_y, theta) at a
reference point (m, m, rad) to a force (F_x, F_y) (N) applied there and a moment M (N m):
[u_x, u_y, theta] = C [F_x, F_y, M]; in 3-D the 6 x 6 one relates (u, theta) to (F, M).
About a converged nonlinear state it is the tangent
(incremental) compliance: material and geometric stiffness, the face's rotation included.
"""
import numpy as np
import scipy.sparse as sp

from .compliance_result import Compliance, moved_compliance, rotation_frame
from .factor import factor
from .boundary import constrained_dofs
from .hyperelastic import Assembler
from .rigid_face import ReducedSpace, RigidFace
from .rigid_face3d import axial, rotation_derivatives
from .rigid_static import check_held, linear_map
from .stability import state_displacement, tangent_stiffness


def _nonlinear_tangent(model, space: ReducedSpace, state, u):
    """(K_zz (N/m), face coordinates q, load stiffness included) about the nonlinear state
    ``u``: the face's force and moment there are held as dead loads."""
    fk = space.faces[0]
    q = fk.rigid_fit(u)
    z = np.zeros(space.n)
    z[:len(space.I)] = u[space.I]
    z[space.slots[0]] = q * fk.scale
    assembler = Assembler(model)
    F, S = assembler.state(u)
    r = assembler.internal_force(F, S)
    if isinstance(state, tuple):
        r = r - state[0].load_factors[state[1]] * state[0].applied
    elif hasattr(state, "applied"):
        r = r - state.load_factors[-1] * state.applied
    T = space.jacobian(z, 1.0)
    K = T.T @ assembler.tangent(F, S) @ T + space.geometric_matrix(z, 1.0, r)
    load = -fk.applied_derivative(q, fk.generalised_force(r, q)) / np.outer(fk.scale, fk.scale)
    slots = space.slots[0]
    pairs = (np.repeat(slots, len(slots)), np.tile(slots, len(slots)))
    K = K + sp.csr_matrix((load.ravel(), pairs), shape=K.shape)
    return K.tocsr(), q, not np.any(load)


def _reduced_tangent(model, space: ReducedSpace, state):
    """(K_zz (N/m), face coordinates q, whether K_zz is symmetric) about ``state`` (None:
    the reference)."""
    zeros = np.zeros(len(space.faces[0].scale))
    if state is None:
        T, _ = linear_map(space)
        return (T.T @ model.stiffness @ T).tocsr(), zeros, True
    u, kind = state_displacement(model, state)
    if kind == "linear":
        T, _ = linear_map(space)
        return (T.T @ tangent_stiffness(model, state) @ T).tocsr(), zeros, True
    return _nonlinear_tangent(model, space, state, u)


def _face_compliance(model, supports, group, state):
    """(compliance about the current centroid, in global axes; current centroid (m))."""
    D, xD, _ = constrained_dofs(model, supports)
    space = ReducedSpace(model, D, xD, [RigidFace(group)])
    check_held(model, space)
    K_zz, q, symmetric = _reduced_tangent(model, space, state)
    fk = space.faces[0]
    slots = space.slots[0]
    E = np.zeros((K_zz.shape[0], len(slots)))
    E[slots, np.arange(len(slots))] = 1.0
    with factor(K_zz, "symmetric" if symmetric else "general") as F:
        X = F.solve(E)
    C = X[slots] / np.outer(fk.scale, fk.scale)  # coordinates per generalised loads
    if symmetric:
        C = 0.5 * (C + C.T)
    if model.dim == 3:  # rotation-vector increments to spatial rotations (and moments)
        R, dR, _ = rotation_derivatives(q[3:])
        B = np.eye(6)
        B[3:, 3:] = axial(dR @ R.T).T
        C = B @ C @ B.T
    return C, fk.centroid + q[:model.dim]


def compliance_matrix(model, supports, face, point=None, state=None, angle: float = 0.0,
                      frame=None) -> Compliance:
    """Compliance of the rigid ``face`` (a boundary group name or RigidFace; its prescribed
    values are ignored: all its coordinates are freed) under ``supports`` (Fixed,
    Prescribed): 3 x 3 in 2-D, 6 x 6 in 3-D (rotations: infinitesimal rotation vectors,
    moments: dead, global components).

    point : reference point (m), in the current configuration; default the face's centroid.
    state : None (the unloaded reference), a StaticResult (prestressed: K + K_sigma), or a
    converged nonlinear state (NonlinearResult, (NonlinearResult, step) or DOF vector, m):
    the tangent compliance there, the face's force and moment at the state held as dead
    loads (in 3-D a dead moment's load stiffness makes it non-symmetric in general).
    angle : 2-D frame rotation (rad, counter-clockwise) of the returned matrix's axes;
    frame : instead, an orthonormal (dim, dim) matrix whose columns are the axes. Raises UnderConstrainedError if the supports alone do not hold the
    body with the face free.
    """
    group = face.group if isinstance(face, RigidFace) else face
    if not isinstance(group, str):
        raise ValueError(f"face = {face!r} must be a boundary group name or a RigidFace")
    dim = model.dim
    R = rotation_frame(dim, angle, frame)
    C, centre = _face_compliance(model, supports, group, state)
    return moved_compliance(group, C, centre, point, R)
