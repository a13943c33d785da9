"""The analysis functions of flexfem.fem, for a continuum Model, a planar BeamModel and a
spatial Beam3DModel alike.

    result = solve_static(model, [Fixed("ground")], [Force("stage", (1.0, 0.0))])
    result.mean_displacement("stage"), result.reactions["ground"], result.max_von_mises

Each function is a :func:`functools.singledispatch` on the model's type (``DISPATCH[name]``):
a continuum :class:`.model.Model` goes to the continuum's function (:mod:`.static`,
:mod:`.modal`, ...), a planar :class:`.beam.BeamModel` and a spatial
:class:`.beam.spatial.Beam3DModel` to the beam models' one face :mod:`.beam.face` (buckling:
:mod:`.beam.buckling`, :mod:`.beam.stroke_buckling`); any other type is a TypeError. The public
function takes ``model`` by position or keyword and hands it to the dispatcher. The results
carry the same names
(:data:`.result_face.SHARED`); what a beam model cannot give raises
:class:`.result_face.NotOnModel`. Options that only the continuum has (a rigid face in 3-D, a
prestress, arc-length control) raise a TypeError or ValueError naming them on a beam model.
"""
from abc import ABC
from functools import singledispatch
import importlib
import sys

from .beam import buckling as beam_buckling
from .beam import face as beam_face
from .beam import stroke_buckling
from .beam.model import BeamModel
from .beam.spatial.model import Beam3DModel

BEAM_MODELS = (BeamModel, Beam3DModel)


class ContinuumModel(ABC):
    """The continuum :class:`.model.Model` and its subclasses, as a dispatch type that does not
    import it: the continuum's modules (scikit-fem) are imported when a continuum is solved,
    and a beam model's analysis never imports them. No object is a Model before .model is
    imported."""

    @classmethod
    def __subclasshook__(cls, other):
        module = sys.modules.get(f"{__package__}.model")
        return issubclass(other, module.Model) if module is not None else NotImplemented


def continuum(target: str):
    """The continuum's implementation "module:function" (in this package), imported when a
    continuum model is first given to it."""
    module_name, _, function_name = target.partition(":")

    def solve(model, *args, **options):
        module = importlib.import_module(f".{module_name}", __package__)
        return getattr(module, function_name)(model, *args, **options)

    solve.__name__ = solve.__qualname__ = function_name
    return solve


def dispatcher(name: str, continuum, planar, spatial=None):
    """A singledispatch function ``name`` with the three models' implementations (``spatial``
    None: the planar one's, the beam models' one face)."""
    def unknown(model, *args, **options):
        raise TypeError(f"{name}: model is a {type(model).__name__}; it takes a Model, a "
                        "BeamModel or a Beam3DModel")

    unknown.__name__ = name
    function = singledispatch(unknown)
    function.register(ContinuumModel, continuum)
    function.register(BeamModel, planar)
    function.register(Beam3DModel, planar if spatial is None else spatial)
    return function


DISPATCH = {
    "solve_static": dispatcher("solve_static", continuum("static:solve_static"),
                               beam_face.solve_static),
    "solve_modes": dispatcher("solve_modes", continuum("modal:solve_modes"),
                              beam_face.solve_modes),
    "solve_nonlinear": dispatcher("solve_nonlinear", continuum("nonlinear:solve_nonlinear"),
                                  beam_face.solve_nonlinear),
    "compliance_matrix": dispatcher("compliance_matrix",
                                    continuum("compliance:compliance_matrix"),
                                    beam_face.compliance_matrix),
    "solve_harmonic": dispatcher("solve_harmonic", continuum("harmonic:solve_harmonic"),
                                 beam_face.solve_harmonic),
    "solve_buckling": dispatcher("solve_buckling", continuum("buckling:solve_buckling"),
                                 beam_buckling.solve_buckling),
    "solve_incremental_buckling": dispatcher(
        "solve_incremental_buckling", continuum("buckling:solve_incremental_buckling"),
        stroke_buckling.solve_incremental_buckling),
}


def solve_static(model, supports, loads=(), **options):
    """Linear static solve: K u = f for the displacement ``supports`` and ``loads``.

    Parameters
    ----------
    model : Model, BeamModel or Beam3DModel
        The continuum (mesh in m, material in Pa) or a planar or spatial beam model, with
        named groups.
    supports : sequence of Fixed or Prescribed
        The held groups; a Prescribed displacement is in m (a rotation in rad).
    loads : sequence of Force, Traction, Pressure, PointForce, BodyForce or Gravity
        The loads on groups: Force in N (a group's total), Traction and Pressure in Pa, a
        BodyForce in N/m^3, Gravity in m/s^2.
    **options
        The continuum's (:func:`.static.solve_static`): ``solver`` ('auto', 'direct',
        'amg'), ``rigid_faces`` (RigidFace, forces in N, moments in N m); a beam model's
        (:func:`.beam.face.solve_static`).

    Returns
    -------
    StaticResult
        Displacements (m), stresses (Pa), ``reactions`` {group: N},
        ``mean_displacement(group)`` (m), ``max_von_mises`` (Pa) and where (m).
    """
    return DISPATCH["solve_static"](model, supports, loads, **options)


def solve_modes(model, n: int = 6, supports=(), **options):
    """The ``n`` lowest natural frequencies and mass-normalised mode shapes.

    Parameters
    ----------
    model : Model, BeamModel or Beam3DModel
        As in :func:`solve_static` (m, Pa).
    n : int
        How many modes (-).
    supports : sequence of Fixed or Prescribed
        The held groups, held at zero (free vibrations about the supported state).
    **options
        The continuum's (:func:`.modal.solve_modes`): ``shift_hz`` (the shift-invert centre,
        Hz), ``prestress`` (a loaded state: its geometric stiffness); a beam model's
        (:func:`.beam.face.solve_modes`).

    Returns
    -------
    Modes
        ``frequencies_hz`` (Hz) and the shapes (mass-normalised, m/sqrt(kg)).
    """
    return DISPATCH["solve_modes"](model, n, supports, **options)


def solve_nonlinear(model, supports, loads, **options):
    """Geometrically nonlinear static solve: the loads stepped from 0 to 1 by Newton's method.

    Parameters
    ----------
    model, supports, loads
        As in :func:`solve_static`: the model (m, Pa), the held groups (m, rad), the loads (N,
        Pa, N/m^3, m/s^2).
    **options
        ``steps`` (load increments, -), ``max_iterations``, ``tol`` (relative residual, -),
        ``min_step`` (the smallest load-factor increment, -), ``rigid_faces``; the
        continuum's further options (:func:`.nonlinear.solve_nonlinear`: ``control``,
        ``check_stability``, ``strain_limit``, ``preloads`` ...), a beam model's
        (:func:`.beam.face.solve_nonlinear`).

    Returns
    -------
    NonlinearResult
        The path: ``load_factors`` (-), displacements (m) and ``mean_displacement(group,
        step)`` (m), ``reactions`` per step (N), ``max_von_mises`` (Pa), ``stable``.
    """
    return DISPATCH["solve_nonlinear"](model, supports, loads, **options)


def compliance_matrix(model, supports, face, **options):
    """The compliance of a rigid face: its displacements and rotations per unit force and moment.

    Parameters
    ----------
    model, supports
        As in :func:`solve_static`: the model (m, Pa) and the held groups (m, rad).
    face : str or RigidFace
        The group whose compliance is asked for (all its coordinates freed).
    **options
        ``point`` (the reference point, m; default the face's centroid), ``angle`` (2-D frame
        rotation, rad) or ``frame`` (orthonormal axes), and the continuum's ``state`` (a
        loaded state: the tangent compliance there; :func:`.compliance.compliance_matrix`).

    Returns
    -------
    Compliance
        ``matrix`` (3 x 3 in 2-D, 6 x 6 in 3-D: m/N, 1/N, rad/(N m)), its ``stiffness``, the
        ``point`` (m) and ``centre_of_compliance`` (m).
    """
    return DISPATCH["compliance_matrix"](model, supports, face, **options)


def solve_harmonic(model, supports, loads, frequencies_hz, **options):
    """The steady-state harmonic response to the loads' amplitudes at each frequency.

    Parameters
    ----------
    model, supports, loads
        As in :func:`solve_static` (m, Pa; supports held at zero): the loads' amplitudes (N,
        Pa, N/m^3, m/s^2).
    frequencies_hz : array_like
        The excitation frequencies (Hz).
    **options
        ``damping`` (a modal damping ratio, -, or Rayleigh(alpha in 1/s, beta in s)),
        ``n_modes`` (-); the continuum's ``method`` ('modal' or 'direct',
        :func:`.harmonic.solve_harmonic`).

    Returns
    -------
    HarmonicResult
        The complex response (m per the load's amplitude); ``frf(group, component)``: its
        amplitude (m), phase (rad) and resonance peaks (Hz).
    """
    return DISPATCH["solve_harmonic"](model, supports, loads, frequencies_hz, **options)


def solve_buckling(model, supports, loads, n: int = 3, **options):
    """The ``n`` lowest positive critical load factors of ``loads`` and their buckling shapes.

    Parameters
    ----------
    model, supports, loads
        As in :func:`solve_static`: the model (m, Pa), the held groups (m, rad), the loads (N,
        Pa, N/m^3, m/s^2).
    n : int
        How many load factors (-).
    **options
        A model's own options (:func:`.buckling.solve_buckling`,
        :func:`.beam.buckling.solve_buckling`, planar and spatial).

    Returns
    -------
    Buckling
        ``load_factors`` (-, ascending: multiples of ``loads`` at which the structure
        buckles) and the shapes.
    """
    return DISPATCH["solve_buckling"](model, supports, loads, n, **options)


def solve_incremental_buckling(model, state, supports, loads, n: int = 3, **options):
    """Buckling about a converged state: the ``n`` lowest lambda at which K_T(state) + lambda
    K_G(state, P) is singular, P the added ``loads`` (the incremental linearised buckling,
    :func:`.buckling.solve_incremental_buckling`; not the path's own limit point).

    Parameters
    ----------
    model : Model, BeamModel or Beam3DModel
        As in :func:`solve_static` (m, Pa).
    state
        A converged state: the path of :func:`solve_nonlinear` (its last step) or (path,
        step); on the continuum also a DOF vector (m) or a StaticResult (linearised prestress).
    supports, loads
        The held groups (their values ignored: held at the state) and the added loads P (N).
    n : int
        How many load factors (-).

    Returns
    -------
    StateBuckling
        ``load_factors`` (-, ascending: multiples of P), ``shapes``, ``increment`` (the
        linear response to P about the state, m).
    """
    return DISPATCH["solve_incremental_buckling"](model, state, supports, loads, n, **options)
