"""The analysis functions of flexfem.fem, for a continuum Model, a planar BeamModel and a
spatial Beam3DModel alike.

    result = solve_static(model, [Fixed("ground")], [Force("stage", (1.0, 0.0))])
    result.mean_displacement("stage"), result.reactions["ground"], result.max_von_mises

Each takes the supports and loads of :mod:`.boundary` by group name and returns results with
the same names whichever model it is given: a continuum :class:`.model.Model` is solved by
the continuum's function (:mod:`.static`, :mod:`.modal`, ...), a beam model with named groups
by :mod:`.beam.face` (planar :class:`.beam.BeamModel`) or :mod:`.beam3d.face` (spatial
:class:`.beam3d.Beam3DModel`); what a group is on a beam model, and what its stress means,
is there (linear buckling: :mod:`.beam.buckling`, :mod:`.beam3d.buckling`). Options that
only the continuum has (a rigid face, a prestress, arc-length control) raise a TypeError or
ValueError naming them on a beam model.
"""
from . import buckling, compliance, harmonic, modal, nonlinear, static
from .beam import buckling as beam_buckling
from .beam import face as beam_face
from .beam.model import BeamModel
from .beam3d import buckling as beam3d_buckling
from .beam3d import face as beam3d_face
from .beam3d.model import Beam3DModel

BEAM_MODELS = (BeamModel, Beam3DModel)


def _pick(model, continuum, beam, spatial=None):
    """The function for ``model``: the continuum's, the planar beam's (``beam``) or the
    spatial beam's (``spatial``; default the spatial face's function of ``beam``'s name)."""
    if isinstance(model, Beam3DModel):
        return spatial or getattr(beam3d_face, beam.__name__)
    return beam if isinstance(model, BeamModel) else continuum


def solve_static(model, supports, loads=(), **options):
    return _pick(model, static.solve_static, beam_face.solve_static)(model, supports, loads,
                                                                     **options)


def solve_modes(model, n: int = 6, supports=(), **options):
    return _pick(model, modal.solve_modes, beam_face.solve_modes)(model, n, supports, **options)


def solve_nonlinear(model, supports, loads, **options):
    return _pick(model, nonlinear.solve_nonlinear, beam_face.solve_nonlinear)(
        model, supports, loads, **options)


def compliance_matrix(model, supports, face, **options):
    return _pick(model, compliance.compliance_matrix, beam_face.compliance_matrix)(
        model, supports, face, **options)


def solve_harmonic(model, supports, loads, frequencies_hz, **options):
    return _pick(model, harmonic.solve_harmonic, beam_face.solve_harmonic)(
        model, supports, loads, frequencies_hz, **options)


def solve_buckling(model, supports, loads, n: int = 3, **options):
    return _pick(model, buckling.solve_buckling, beam_buckling.solve_buckling,
                 beam3d_buckling.solve_buckling)(model, supports, loads, n, **options)


def _describe(function, continuum, beam=None) -> None:
    """The face's docstring: the continuum's, then what the beam model does."""
    text = continuum.__doc__ or ""
    if beam is not None:
        text += (f"\n\n    On a beam model (:mod:`flexfem.fem.beam.face`, "
                 f":mod:`flexfem.fem.beam3d.face` in space): {beam.__doc__}")
    function.__doc__ = text


_describe(solve_static, static.solve_static, beam_face.solve_static)
_describe(solve_modes, modal.solve_modes, beam_face.solve_modes)
_describe(solve_nonlinear, nonlinear.solve_nonlinear, beam_face.solve_nonlinear)
_describe(compliance_matrix, compliance.compliance_matrix, beam_face.compliance_matrix)
_describe(solve_harmonic, harmonic.solve_harmonic, beam_face.solve_harmonic)
_describe(solve_buckling, buckling.solve_buckling, beam_buckling.solve_buckling)
