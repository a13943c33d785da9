"""The geometry of a rigid face in 3-D: its DOFs, its nodes' arms about the face's area
centroid and its RMS arm, used by :mod:`.rigid_face3d` (six master coordinates
(c_x, c_y, c_z, theta_x, theta_y, theta_z), node a moving by c + theta x (X_a - X_c) when
linearised) and so by :func:`.compliance.compliance_matrix` in 3-D.
"""
import numpy as np
import skfem

from .boundary import group_dofs


def face_geometry(model, group: str) -> tuple:
    """(DOFs (3, n), arms X_a - X_c (3, n) m, centroid (3,) m, RMS arm ell (m)) of a
    boundary group of a 3-D model."""
    if group not in model.mesh.boundaries:
        group_dofs(model, group)  # names the known groups if it does not exist
        raise ValueError(f"face = {group!r} must be a boundary group, not a subdomain")
    dofs = group_dofs(model, group)
    pair = np.array([dofs[0], dofs[1], dofs[2]])
    fb = skfem.FacetBasis(model.cell_mesh, model.basis.elem,
                          facets=model.mesh.facets(group), intorder=2)
    x = np.asarray(fb.global_coordinates())
    area = float(np.sum(fb.dx))
    centroid = np.array([np.sum(x[i] * fb.dx) for i in range(3)]) / area
    arms = model.basis.doflocs[:, pair[0]] - centroid[:, None]
    ell = float(np.sqrt(np.mean(np.sum(arms ** 2, axis=0))))
    if not ell > 0:
        raise ValueError(f"face {group!r} has a single node; it cannot rotate")
    return pair, arms, centroid, ell
