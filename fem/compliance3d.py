"""The reduced stiffness of a linearised rigid face in 3-D: six master coordinates
(c_x, c_y, c_z, ell theta_x, ell theta_y, ell theta_z) about the face's area centroid, node a
moving by c + theta x (X_a - X_c). Used by :func:`.compliance.compliance_matrix` in 3-D.
"""
import numpy as np
import scipy.sparse as sp
import skfem

from .boundary import group_dofs
from .static import UnderConstrainedError, rigid_body_dof_modes


def face_geometry(model, group: str) -> tuple:
    """(DOFs (3, n), arms X_a - X_c (3, n) m, centroid (3,) m, RMS arm ell (m)) of a
    boundary group of a 3-D model."""
    if group not in model.mesh.boundaries:
        group_dofs(model, group)  # names the known groups if it does not exist
        raise ValueError(f"face = {group!r} must be a boundary group, not a subdomain")
    dofs = group_dofs(model, group)
    pair = np.array([dofs[0], dofs[1], dofs[2]])
    fb = skfem.FacetBasis(model.mesh.mesh, model.basis.elem,
                          facets=model.mesh.facets(group), intorder=2)
    x = np.asarray(fb.global_coordinates())
    area = float(np.sum(fb.dx))
    centroid = np.array([np.sum(x[i] * fb.dx) for i in range(3)]) / area
    arms = model.basis.doflocs[:, pair[0]] - centroid[:, None]
    ell = float(np.sqrt(np.mean(np.sum(arms ** 2, axis=0))))
    if not ell > 0:
        raise ValueError(f"face {group!r} has a single node; it cannot rotate")
    return pair, arms, centroid, ell


def check_held_3d(model, D: np.ndarray) -> None:
    """Raise UnderConstrainedError unless the supports ``D`` hold all 6 rigid-body modes."""
    rows = rigid_body_dof_modes(model)[D]
    s = np.linalg.svd(rows, compute_uv=False) if len(rows) else np.zeros(0)
    free = 6 - int(np.sum(s > 1e-9 * max(np.abs(rows).max(initial=0.0), 1e-300)))
    if free:
        raise UnderConstrainedError(f"the supports leave {free} of 6 rigid-body modes free with "
                                    "the face free; add supports")


def reduced_stiffness_3d(model, D: np.ndarray, group: str, K) -> tuple:
    """(K_zz (N/m), slots of the 6 face coordinates, centroid (m), ell (m)) with the face's
    DOFs replaced by its six linearised rigid coordinates."""
    pair, arms, centroid, ell = face_geometry(model, group)
    taken = np.zeros(model.n_dofs, dtype=bool)
    taken[D] = True
    if np.any(taken[pair.ravel()]):
        raise ValueError(f"face {group!r} shares DOFs with a support; a node can have one "
                         "constraint")
    taken[pair.ravel()] = True
    I = np.flatnonzero(~taken)
    n_I = len(I)
    ax, ay, az = arms / ell
    zero, one = np.zeros_like(ax), np.ones_like(ax)
    # columns: translations, then e_j x arm / ell for j = x, y, z
    columns = [(one, zero, zero), (zero, one, zero), (zero, zero, one),
               (zero, -az, ay), (az, zero, -ax), (-ay, ax, zero)]
    rows, cols, vals = [I], [np.arange(n_I)], [np.ones(n_I)]
    for k, column in enumerate(columns):
        for comp in range(3):
            rows.append(pair[comp])
            cols.append(np.full(pair.shape[1], n_I + k))
            vals.append(column[comp])
    T = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(model.n_dofs, n_I + 6))
    return (T.T @ K @ T).tocsr(), np.arange(n_I, n_I + 6), centroid, ell
