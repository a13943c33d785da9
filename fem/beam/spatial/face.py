"""The analysis face of a spatial beam model: the beam models' one face
(:mod:`flexfem.fem.beam.face`), planar and spatial alike."""
from ..face import (Beam3DHarmonic, compliance_matrix, group, held_rotations,  # noqa: F401
                    node_loads, node_supports, solve_harmonic, solve_modes, solve_nonlinear,
                    solve_static, supported_groups)
from ...beam_result import Beam3DPath, Beam3DResult  # noqa: F401

__all__ = ["Beam3DHarmonic", "Beam3DPath", "Beam3DResult", "compliance_matrix",
           "node_loads", "node_supports", "solve_harmonic", "solve_modes",
           "solve_nonlinear", "solve_static"]
