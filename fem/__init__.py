"""flexfem.fem: mechanism-agnostic finite elements. Meshes with named groups in, fields out.

    mesh = mesh_from_gmsh(gmsh)                         # inside gmsh_session()
    model = Model(mesh, material("structural_steel"), PlaneStress(thickness=0.01), order=2)
    result = solve_static(model, [Fixed("fixed")], [Force("tip", (0.0, -10.0))])
    modes = solve_modes(model, n=6, supports=[Fixed("fixed")])
"""
from flexfem.fem.boundary import BodyForce, Fixed, Force, Gravity, PointForce, Prescribed, Traction
from flexfem.fem.gmsh_session import gmsh_session
from flexfem.fem.linsolve import SingularSystemError
from flexfem.fem.materials import Material, material, material_names
from flexfem.fem.mesh import FEMesh, facets_where, mesh_from_gmsh, read_mesh
from flexfem.fem.modal import Modes, solve_modes
from flexfem.fem.model import Model, PlaneStrain, PlaneStress, Solid3D, von_mises
from flexfem.fem.static import StaticResult, UnderConstrainedError, solve_static

__all__ = [
    "BodyForce", "FEMesh", "Fixed", "Force", "Gravity", "Material", "Model", "Modes",
    "PlaneStrain", "PlaneStress", "PointForce", "Prescribed", "SingularSystemError", "Solid3D",
    "StaticResult", "Traction", "UnderConstrainedError", "facets_where", "gmsh_session",
    "material", "material_names", "mesh_from_gmsh", "read_mesh", "solve_modes", "solve_static",
    "von_mises",
]
