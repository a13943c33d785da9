"""flexfem.reduced: the reduced beam models of flexure mechanisms, built from their layouts.

Every piece of the reduced model lives here: the builders from a mechanism's layout
(:mod:`.layout`, :mod:`.dbma`, :mod:`.eightbar`, :mod:`.driving`, :mod:`.pivot`,
:mod:`.model_file`), the spatial lift (:mod:`.spatial`, :mod:`.eightbar3d`), the corrections
from small 2-D models (a notch's, :mod:`.hinge_patch`; a member's patch, :mod:`.patch2d` and
:mod:`.dbma_member_patch`), the oblique roots and crossings of a model file's beams
(:mod:`.roots`, :mod:`.crossings`), Vlasov's torsion (:mod:`.torsion`) and the hinge
specimen that checks them against the continuum (:mod:`.specimen`). The solvers are
flexfem.fem.beam and flexfem.fem.beam.spatial; geometry/ draws and never solves.
"""
