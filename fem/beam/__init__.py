"""flexfem.fem.beam: the reduced beam model of flexure mechanisms (co-rotational), planar
here and spatial in :mod:`.spatial`, analysed by the same face as the continuum::

    from flexfem.fem import Fixed, Force, material, solve_static, solve_buckling
    mesh = beam_chain([(0, 0), (0.05, 0)], Section.rect(0.01, 0.5e-3), n_per_segment=20)
    model = BeamModel(mesh.nodes, mesh.elements, mesh.sections, material("structural_steel"),
                      groups={"root": [0], "tip": [20]})
    lin = solve_static(model, [Fixed("root")], [Force("tip", (0.0, -1.0))])
    lin.mean_displacement("tip")                      # m: (0, -2.0e-3), P L^3 / (3 E I)
    solve_buckling(model, [Fixed("root")], [Force("tip", (-1.0, 0.0))]).load_factors
    # [20.56...] N: pi^2 E I / (4 L^2)

``solve_nonlinear``, ``solve_modes`` and ``compliance_matrix`` of ``flexfem.fem`` take a beam
model too. The solvers of this package take node-addressed supports (:mod:`.supports`);
they are the face's inside.
"""
from .assembly import SingularBeamError
from .compliance import compliance
from .modal import BeamModes, solve_beam_modes
from .mesh import BeamMesh, beam_chain, beam_from_profile, profile_chain
from .model import BeamGroup, BeamModel, RigidLink
from .section import Section
from .nonlinear import BeamNonlinearResult, NonConvergenceError, solve_beam_nonlinear
from .static import BeamState, solve_beam_static
from .superelement import Superelement
from .supports import NodalLoad

__all__ = [
    "BeamGroup", "BeamMesh", "BeamModel", "BeamModes", "BeamNonlinearResult", "BeamState",
    "NodalLoad", "NonConvergenceError", "RigidLink",
    "Section", "SingularBeamError", "Superelement", "beam_chain", "beam_from_profile",
    "compliance", "profile_chain", "solve_beam_modes",
    "solve_beam_nonlinear", "solve_beam_static",
]
