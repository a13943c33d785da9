"""flexfem.fem: mechanism-agnostic finite elements. Meshes with named groups in, fields out.

    mesh = mesh_from_gmsh(gmsh)                         # inside gmsh_session()
    model = Model(mesh, material("structural_steel"), PlaneStress(thickness=0.01), order=2)
    result = solve_static(model, [Fixed("fixed")], [Force("tip", (0.0, -10.0))])
    result.stress_at([(0.05, 0.0)]), result.nodal_stress, result.solver   # Pa; 'mkl-pardiso'
    solve_static(model, [Fixed("fixed")], [Pressure("bore", 1e6)])       # Pa, into the body
    modes = solve_modes(model, n=6, supports=[Fixed("fixed")])
    write_result(result, "result.vtu")                  # ParaView; write_mesh for .msh/.inp
    large = solve_nonlinear(model, [Fixed("fixed")], [Force("tip", (0.0, -1e3))], steps=20)
    large.stable, large.strain_valid, large.stress_at_step(5)   # per-step checks
    hub = solve_static(model, [Fixed("fixed")], [], rigid_faces=[RigidFace("tip", moment=1.0)])
    c = compliance_matrix(model, [Fixed("fixed")], "tip", state=(large, -1))
    buckling = solve_buckling(model, [Fixed("fixed")], [Force("tip", (-1.0, 0.0))], n=3)
    frf = solve_harmonic(model, [Fixed("fixed")], loads, freqs, damping=0.02).frf("tip", "y")

The same functions take a planar BeamModel with named groups (:mod:`.beam.face`): one set of
supports and loads, by group name, for the continuum and the reduced beam model.
Its names are imported when first used (PEP 562): importing one module of the package (the
beam model's, the input checks) imports neither scikit-fem nor meshio nor the solvers.
"""
from .lazy_exports import lazy_exports
from typing import TYPE_CHECKING

# light (it imports gmsh inside gmsh_session()), and imported now so that the function, not
# its module of the same name, is flexfem.fem.gmsh_session whichever is imported first
from .gmsh_session import gmsh_session

if TYPE_CHECKING:  # what a reader and a type checker see; imported on first use below
    from .boundary import (BodyForce, Fixed, Force, Gravity, PointForce, Prescribed, Pressure,
                           Traction)
    from .export import write_mesh, write_result
    from .factor import SingularStiffness
    from .linsolve import SingularSystemError
    from .materials import Material, material, material_names
    from .mesh import FEMesh, drop_unused_vertices, facets_where, mesh_from_gmsh, read_mesh
    from .modal import Modes
    from .model import Model, PlaneStrain, PlaneStress, Solid3D, von_mises
    from .nonlinear import NonConvergenceError, NonlinearResult
    from .rigid_face import RigidFace
    from .static import StaticResult, UnderConstrainedError
    from .buckling import Buckling
    from .compliance_result import Compliance
    from .frequency_response import FRF, Rayleigh
    from .harmonic import HarmonicResult
    from .analyses import (compliance_matrix, solve_buckling, solve_harmonic,
                           solve_incremental_buckling, solve_modes, solve_nonlinear, solve_static)
    from .state_buckling import StateBuckling
    from .beam import BeamGroup, BeamModel
    from .springs import ground_spring, group_spring
    from .stress import nonlinear_stress, nonlinear_stress_at

_EXPORTS = {  # name: the module that defines it
    "BodyForce": "boundary", "Fixed": "boundary", "Force": "boundary", "Gravity": "boundary",
    "PointForce": "boundary", "Prescribed": "boundary", "Pressure": "boundary",
    "Traction": "boundary", "write_mesh": "export", "write_result": "export",
    "SingularStiffness": "factor",
    "SingularSystemError": "linsolve", "Material": "materials", "material": "materials",
    "material_names": "materials", "FEMesh": "mesh", "drop_unused_vertices": "mesh",
    "facets_where": "mesh", "mesh_from_gmsh": "mesh", "read_mesh": "mesh", "Modes": "modal",
    "Model": "model", "PlaneStrain": "model", "PlaneStress": "model", "Solid3D": "model",
    "von_mises": "model", "NonConvergenceError": "nonlinear", "NonlinearResult": "nonlinear",
    "RigidFace": "rigid_face", "StaticResult": "static", "UnderConstrainedError": "static",
    "Buckling": "buckling", "Compliance": "compliance_result", "FRF": "frequency_response",
    "HarmonicResult": "harmonic", "Rayleigh": "frequency_response",
    "compliance_matrix": "analyses",
    "solve_buckling": "analyses", "solve_harmonic": "analyses",
    "solve_incremental_buckling": "analyses", "solve_modes": "analyses",
    "solve_nonlinear": "analyses", "solve_static": "analyses", "StateBuckling": "state_buckling",
    "BeamGroup": "beam", "BeamModel": "beam", "ground_spring": "springs",
    "group_spring": "springs", "nonlinear_stress": "stress", "nonlinear_stress_at": "stress",
}

__all__ = sorted([*_EXPORTS, "gmsh_session"])

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
