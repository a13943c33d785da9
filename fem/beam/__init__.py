"""flexfem.fem.beam: a reduced planar beam model of flexure mechanisms (co-rotational).

    mesh = beam_chain([(0, 0), (0.05, 0)], Section.rect(0.01, 0.5e-3), n_per_segment=20)
    model = BeamModel(mesh.nodes, mesh.elements, mesh.sections, material("structural_steel"))
    lin = solve_beam_static(model, [NodeFixed(0)], [NodalLoad(20, fy=-1.0)])
    big = solve_beam_nonlinear(model, [NodeFixed(0)], [NodalLoad(20, fy=-5.0)], steps=20)
    modes = solve_beam_modes(model, [NodeFixed(0)], n=3)
    C = compliance(model, [NodeFixed(0)], node=20)      # 3x3 (x, y, theta) at the tip

The solvers here take node-addressed supports (:mod:`.supports`: NodeFixed, NodePrescribed);
a user meets the continuum's group supports and loads (fem/boundary: Fixed, Prescribed,
Force) on a model with groups, through the analysis face (fem.solve_static etc.).
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
