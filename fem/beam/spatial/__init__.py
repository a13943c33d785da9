"""flexfem.fem.beam.spatial: the spatial (6 DOFs per node) co-rotational beam model, analysed
by the same face and group supports and loads as the planar one::

    from flexfem.fem import Fixed, Force, compliance_matrix, solve_static
    model = Beam3DModel(nodes, elements, Section.rect(10e-3, 2e-3), steel,
                        groups={"root": [0], "tip": [tip]})
    lin = solve_static(model, [Fixed("root")], [Force("tip", (0.0, 0.0, -1.0))])
    C = compliance_matrix(model, [Fixed("root")], "tip")   # 6x6 at the tip
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
