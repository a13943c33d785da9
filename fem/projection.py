"""Recovery of continuous nodal fields from quadrature-point values (stresses)."""
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
import skfem

from .model import Model, scalar_element


def nodal_average(model: Model, values: np.ndarray) -> np.ndarray:
    """L2 projection of quadrature-point values ((..., n_elements, n_points)) onto continuous
    piecewise-linear fields at the mesh vertices (consistent P1 mass matrix, so a linear stress
    field is recovered exactly; scikit-fem issue #618)."""
    mesh = model.mesh.mesh  # the vertices' hat functions (a curved copy's p holds its edge nodes too)
    hat = skfem.CellBasis(mesh, scalar_element(mesh, 1), quadrature=(model.basis.X, model.basis.W))
    flat = values.reshape((-1,) + hat.dx.shape)
    M = skfem.BilinearForm(lambda u, v, w: u * v).assemble(hat).tocsr()
    jacobi = sp.diags(1.0 / M.diagonal())
    nodal = np.zeros((len(flat), mesh.p.shape[1]))
    done = []  # components projected so far; a zero or repeated one (sigma_ji) is not redone
    for k, component in enumerate(flat):
        if not np.any(component):
            continue
        same = next((j for j in done if np.array_equal(flat[j], component)), None)
        if same is not None:
            nodal[k] = nodal[same]
            continue
        b = skfem.LinearForm(lambda v, w: w["s"] * v).assemble(hat, s=component)
        nodal[k], info = spla.cg(M, b, rtol=1e-12, atol=0.0, M=jacobi, maxiter=1000)
        done.append(k)
    return nodal.reshape(values.shape[:-2] + (mesh.p.shape[1],))
