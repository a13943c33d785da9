"""The analysis functions of flexfem.fem, for a continuum Model, a planar BeamModel and a
spatial Beam3DModel alike.

    result = solve_static(model, [Fixed("ground")], [Force("stage", (1.0, 0.0))])
    result.mean_displacement("stage"), result.reactions["ground"], result.max_von_mises

Each function is a :func:`functools.singledispatch` on the model's type (``DISPATCH[name]``):
a continuum :class:`.model.Model` goes to the continuum's function (:mod:`.static`,
:mod:`.modal`, ...), a planar :class:`.beam.BeamModel` to :mod:`.beam.face` and a spatial
:class:`.beam3d.Beam3DModel` to :mod:`.beam3d.face` (linear buckling: :mod:`.beam.buckling`,
:mod:`.beam3d.buckling`); any other type is a TypeError. The public function takes ``model``
by position or keyword and hands it to the dispatcher. The results carry the same names
(:data:`.result_face.SHARED`); what a beam model cannot give raises
:class:`.result_face.NotOnModel`. Options that only the continuum has (a rigid face in 3-D, a
prestress, arc-length control) raise a TypeError or ValueError naming them on a beam model.
"""
from functools import singledispatch

from . import buckling, compliance, harmonic, modal, nonlinear, static
from .beam import buckling as beam_buckling
from .beam import face as beam_face
from .beam.model import BeamModel
from .beam3d import buckling as beam3d_buckling
from .beam3d import face as beam3d_face
from .beam3d.model import Beam3DModel
from .model import Model

BEAM_MODELS = (BeamModel, Beam3DModel)


def dispatcher(name: str, continuum, planar, spatial):
    """A singledispatch function ``name`` with the three models' implementations."""
    def unknown(model, *args, **options):
        raise TypeError(f"{name}: model is a {type(model).__name__}; it takes a Model, a "
                        "BeamModel or a Beam3DModel")

    unknown.__name__ = name
    function = singledispatch(unknown)
    function.register(Model, continuum)
    function.register(BeamModel, planar)
    function.register(Beam3DModel, spatial)
    return function


DISPATCH = {
    "solve_static": dispatcher("solve_static", static.solve_static, beam_face.solve_static,
                               beam3d_face.solve_static),
    "solve_modes": dispatcher("solve_modes", modal.solve_modes, beam_face.solve_modes,
                              beam3d_face.solve_modes),
    "solve_nonlinear": dispatcher("solve_nonlinear", nonlinear.solve_nonlinear,
                                  beam_face.solve_nonlinear, beam3d_face.solve_nonlinear),
    "compliance_matrix": dispatcher("compliance_matrix", compliance.compliance_matrix,
                                    beam_face.compliance_matrix,
                                    beam3d_face.compliance_matrix),
    "solve_harmonic": dispatcher("solve_harmonic", harmonic.solve_harmonic,
                                 beam_face.solve_harmonic, beam3d_face.solve_harmonic),
    "solve_buckling": dispatcher("solve_buckling", buckling.solve_buckling,
                                 beam_buckling.solve_buckling, beam3d_buckling.solve_buckling),
}


def solve_static(model, supports, loads=(), **options):
    """Linear static solve (:func:`.static.solve_static`; on a beam model
    :func:`.beam.face.solve_static`, :func:`.beam3d.face.solve_static`)."""
    return DISPATCH["solve_static"](model, supports, loads, **options)


def solve_modes(model, n: int = 6, supports=(), **options):
    """The ``n`` lowest natural frequencies and shapes (:func:`.modal.solve_modes`; on a beam
    model :func:`.beam.face.solve_modes`, :func:`.beam3d.face.solve_modes`)."""
    return DISPATCH["solve_modes"](model, n, supports, **options)


def solve_nonlinear(model, supports, loads, **options):
    """Geometrically nonlinear static solve (:func:`.nonlinear.solve_nonlinear`; on a beam
    model :func:`.beam.face.solve_nonlinear`, :func:`.beam3d.face.solve_nonlinear`)."""
    return DISPATCH["solve_nonlinear"](model, supports, loads, **options)


def compliance_matrix(model, supports, face, **options):
    """Compliance of a face (:func:`.compliance.compliance_matrix`; on a beam model
    :func:`.beam.face.compliance_matrix`, :func:`.beam3d.face.compliance_matrix`)."""
    return DISPATCH["compliance_matrix"](model, supports, face, **options)


def solve_harmonic(model, supports, loads, frequencies_hz, **options):
    """Steady-state harmonic response (:func:`.harmonic.solve_harmonic`; on a beam model
    :func:`.beam.face.solve_harmonic`, :func:`.beam3d.face.solve_harmonic`)."""
    return DISPATCH["solve_harmonic"](model, supports, loads, frequencies_hz, **options)


def solve_buckling(model, supports, loads, n: int = 3, **options):
    """Linear buckling load factors and shapes (:func:`.buckling.solve_buckling`; on a beam
    model :func:`.beam.buckling.solve_buckling`, :func:`.beam3d.buckling.solve_buckling`)."""
    return DISPATCH["solve_buckling"](model, supports, loads, n, **options)
