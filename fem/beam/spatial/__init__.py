"""flexfem.fem.beam.spatial: a spatial (6 DOFs per node) co-rotational beam model.

    model = Beam3DModel(nodes, elements, Section.rect(10e-3, 2e-3), steel)
    lin = solve_beam3d_static(model, [NodeFixed(0)], [NodalLoad(tip, fz=-1.0)])
    big = solve_beam3d_nonlinear(model, [NodeFixed(0)], [NodalLoad(tip, fz=-50.0)], steps=20)
    modes = solve_beam3d_modes(model, [NodeFixed(0)], n=6)
    C = compliance3d(model, [NodeFixed(0)], node=tip)      # 6x6 at the tip
    lin.max_stress                                     # Pa: normal + torsion, rectangles
"""
from ..assembly import SingularBeamError
from .modal import solve_beam3d_modes
from ..supports import NodalLoad
from ..section import Section, rect_torsion_constant, rect_torsion_shear
from ..model import RigidLink
from .model import Beam3DModel, element_frames
from .nonlinear import NonConvergenceError, solve_beam3d_nonlinear
from .static import Beam3DState, solve_beam3d_static
from ..compliance import compliance as compliance3d

__all__ = [
    "Beam3DModel", "Beam3DState",
    "NodalLoad", "NonConvergenceError", "RigidLink", "Section",
    "SingularBeamError", "compliance3d", "element_frames", "rect_torsion_constant",
    "rect_torsion_shear",
    "solve_beam3d_modes", "solve_beam3d_nonlinear", "solve_beam3d_static",
]
