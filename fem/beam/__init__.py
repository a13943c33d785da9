"""flexfem.fem.beam: a reduced planar beam model of flexure mechanisms (co-rotational).

    mesh = beam_chain([(0, 0), (0.05, 0)], Section.rect(0.01, 0.5e-3), n_per_segment=20)
    model = BeamModel(mesh.nodes, mesh.elements, mesh.sections, material("structural_steel"))
    lin = solve_beam_static(model, [Fixed(0)], [NodalLoad(20, fy=-1.0)])
    big = solve_beam_nonlinear(model, [Fixed(0)], [NodalLoad(20, fy=-5.0)], steps=20)
    modes = solve_beam_modes(model, [Fixed(0)], n=3)
    C = compliance(model, [Fixed(0)], node=20)      # 3x3 (x, y, theta) at the tip
"""
from .assembly import SingularBeamError
from .compliance import compliance
from .modal import BeamModes, solve_beam_modes
from .mesh import BeamMesh, beam_chain, beam_from_profile, profile_chain
from .model import BeamGroup, BeamModel, RigidLink
from .section import Section
from .nonlinear import BeamNonlinearResult, NonConvergenceError, solve_beam_nonlinear
from .static import BeamState, BeamStaticResult, solve_beam_static
from .superelement import Superelement
from .supports import Fixed, NodalLoad, Prescribed

__all__ = [
    "BeamGroup", "BeamMesh", "BeamModel", "BeamModes", "BeamNonlinearResult", "BeamState",
    "BeamStaticResult", "Fixed", "NodalLoad", "NonConvergenceError", "Prescribed", "RigidLink",
    "Section", "SingularBeamError", "Superelement", "beam_chain", "beam_from_profile",
    "compliance", "profile_chain", "solve_beam_modes",
    "solve_beam_nonlinear", "solve_beam_static",
]
