"""The spatial beam model's former import path: ``flexfem.fem.beam3d`` is
:mod:`flexfem.fem.beam.spatial` (the planar and the spatial beam are one package)."""
from .beam.spatial import *  # noqa: F401,F403
from .beam.spatial import __all__  # noqa: F401
