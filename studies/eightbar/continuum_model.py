"""The eight-bar suspension's continuum model: the meshed part (2-D plane stress or the 3-D
solid) with its groups "fixed" and "end_effector" and a subdomain per flexure and link."""
import numpy as np

from ...fem import Model, PlaneStress, Solid3D, material
from ...fem.budget import check_budget
from ...geometry.eightbar.estimate import estimate_mesh
from ...geometry.eightbar.flexure import EightBarFlexureParams, mesh_eightbar_flexure


def build_model(params: EightBarFlexureParams, size_factor: float = 1.0, n_across: int = 3,
                max_dofs: int | None = None, dim: int = 2, layers: int | None = None):
    """(Model (P2: plane stress in 2-D, solid tetrahedra in 3-D), mesh sizes dict) of the
    flexure suspension; a mesh above ``max_dofs`` (None: what half the available memory
    affords) is refused before meshing. 3-D: ``layers`` through the thickness (see
    :func:`~flexfem.geometry.eightbar.flexure.solid_mesh_options`)."""
    check_budget(estimate_mesh(params, n_across, size_factor, dim=dim, layers=layers), dim,
                 max_dofs, what=f"the eight-bar mesh at size_factor {size_factor:g}"
                 + (" in 3-D" if dim == 3 else ""))
    mesh, sizes = mesh_eightbar_flexure(params, n_across=n_across, size_factor=size_factor,
                                        dim=dim, layers=layers)
    formulation = PlaneStress(params.thickness) if dim == 2 else Solid3D()
    return Model(mesh, material(params.material), formulation, order=2), sizes


def group_at_vertex(model: Model, vertex: int) -> str:
    """Name of the flexure (or link) holding mesh vertex ``vertex``: flexures first."""
    mesh = model.mesh
    elements = np.flatnonzero(np.any(mesh.mesh.t == vertex, axis=0))
    names = [n for n in mesh.subdomains if n not in ("body", "links", "flexures", "anchors")]
    names.sort(key=lambda n: (not n.startswith("flexure_"), n))
    for name in names:
        if np.intersect1d(mesh.subdomains[name], elements).size:
            return name
    return "unknown"
