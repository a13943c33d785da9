"""The continuum's analysis face on a planar beam model with named groups.

A group is what a mesh's boundary group is to the continuum: the place where supports hold
and loads act. On a beam model it is one or more nodes, each the master of a rigid body (a
block, a pad, a mounting face), and the extent of the face it stands for (``span``, m). So the
supports and loads of :mod:`flexfem.fem.boundary` apply to either model:

- ``Fixed(group)`` holds every node of the group (x, y and rotation): a clamped rigid face;
- ``Prescribed(group, x=..., y=...)`` holds those components at the values; a component held
  on a face that spans across it holds the face's rotation too (every point of a rigid face
  having the same x means it does not turn), as the continuum's every-node constraint does;
- ``Force(group, vector)`` is the group's total force (N), shared equally by its nodes.

Results carry the continuum's names: ``mean_displacement(group)`` (the mean of the group's
nodes: the face's motion at its reference point), ``reactions[group]`` (N, summed over its
nodes), ``max_von_mises`` (the beam stress |N|/A + |M| c / I, Pa; no stress concentration)
and ``max_von_mises_location`` (m). SI units.
"""
from dataclasses import dataclass, field

import numpy as np

from ..boundary import Fixed, Force, Prescribed
from ..compliance import Compliance, moved_compliance, rotation_frame
from ..harmonic import FRF, check_frequencies, damping_ratios
from ..rigid_face_input import RigidFace
from .compliance import shared_compliance
from .modal import BeamModes, solve_beam_modes
from .model import BeamGroup, BeamModel
from .supports import Fixed as NodeFixed
from .supports import NodalLoad
from .supports import Prescribed as NodePrescribed
from ..beam_result import BeamPath, BeamResult
from ..result_face import BeamFace
from .nonlinear import solve_beam_nonlinear
from .static import solve_beam_static

AXES = ("x", "y")


def group(model: BeamModel, name) -> BeamGroup:
    """The model's group ``name``; ValueError naming the known groups."""
    groups = model.groups
    if name not in groups:
        raise ValueError(f"group {name!r} is not one of the beam model's groups "
                         f"{sorted(groups)}")
    return groups[name]


def node_supports(model: BeamModel, supports) -> list:
    """The beam model's own node supports for group supports (Fixed, Prescribed)."""
    out = []
    for s in supports:
        if isinstance(s, (NodeFixed, NodePrescribed)):
            out.append(s)
        elif isinstance(s, Fixed):
            out.append(NodeFixed(group(model, s.group).nodes))
        elif isinstance(s, Prescribed):
            g = group(model, s.group)
            values = s.components()
            if 2 in values or any(callable(v) for v in values.values()):
                raise ValueError(f"Prescribed({s.group!r}): the planar beam model takes numbers "
                                 "for x and y (m)")
            turns_free = True
            for axis, value in values.items():
                out += [NodePrescribed(n, AXES[axis], float(value)) for n in g.nodes]
                turns_free &= g.span[1 - axis] == 0.0
            if not turns_free:
                out += [NodePrescribed(n, "theta", 0.0) for n in g.nodes]
        else:
            raise ValueError(f"supports: {s!r}: the beam model takes Fixed and Prescribed")
    return out


def node_loads(model: BeamModel, loads) -> list:
    """NodalLoads for group forces (Force: the total, shared equally by the group's nodes)."""
    out = []
    for load in loads:
        if isinstance(load, NodalLoad):
            out.append(load)
        elif isinstance(load, Force):
            if len(load.vector) != 2:
                raise ValueError(f"Force({load.group!r}): the planar beam model takes (F_x, "
                                 "F_y) in N")
            nodes = group(model, load.group).nodes
            fx, fy = (v / len(nodes) for v in load.vector)
            out += [NodalLoad(n, fx, fy) for n in nodes]
        else:
            raise ValueError(f"loads: {type(load).__name__} on the beam model: it takes forces "
                             "(Force, the group's total in N; in a model file force = [...]); "
                             "a traction, pressure or body load is the continuum's")
    return out


def supported_groups(supports) -> list:
    return [s.group for s in supports if isinstance(s, (Fixed, Prescribed))]


def solve_static(model: BeamModel, supports, loads=(), rigid_faces=(),
                 **options) -> BeamResult:
    """Linear static solve of a grouped beam model (the continuum's supports and loads;
    ``rigid_faces``: RigidFace on one-node groups, a prescribed x, y or rotation held, a free
    one carrying the face's force or moment; face_motion reads them)."""
    no_options("solve_static", options, ("solver",))
    held, face_loads, applied = rigid_face_conditions(model, rigid_faces)
    nodal = node_loads(model, loads) + face_loads
    state = solve_beam_static(model, node_supports(model, supports) + held, nodal)
    return BeamResult(model, state, tuple(supported_groups(supports)),
                      faces=tuple(f.group for f in rigid_faces), face_loads=applied,
                      applied=load_array(model, nodal).ravel())


def solve_modes(model: BeamModel, n: int = 6, supports=(), **options) -> BeamModes:
    """The ``n`` lowest natural frequencies (Hz) and shapes, supports held at zero (their
    values ignored, as the continuum's); effective_mass (n, 2) kg. A shift_hz is accepted
    and not needed (the beam's eigensolvers choose their own)."""
    no_options("solve_modes", options, ("shift_hz",))
    held = [_at_zero(s) for s in node_supports(model, supports)]
    return solve_beam_modes(model, held, n=n)


def _at_zero(support):
    if isinstance(support, NodePrescribed):
        return NodePrescribed(support.node, support.dof, 0.0)
    return support


def rigid_face_conditions(model: BeamModel, faces) -> tuple:
    """(node supports, node loads, {face: applied (F_x, F_y, M)}) of RigidFaces on groups of
    one node (a rigid body's master): a prescribed x, y or rotation holds that DOF; a free one
    carries the face's force or moment."""
    supports, loads, applied = [], [], {}
    for face in faces:
        if not isinstance(face, RigidFace) or face.dim == 3:
            raise ValueError(f"rigid_faces: {face!r}: the planar beam model takes 2-D "
                             "RigidFace")
        nodes = group(model, face.group).nodes
        if len(nodes) != 1:
            raise ValueError(f"RigidFace({face.group!r}): the group has {len(nodes)} nodes; a "
                             "rigid face on the beam model is one rigid body's node")
        values = (face.x, face.y, face.rotation)
        supports += [NodePrescribed(nodes[0], dof, float(v))
                     for dof, v in zip(("x", "y", "theta"), values) if v is not None]
        force = (*face.force[:2], face.moment)
        loads.append(NodalLoad(nodes[0], *force[:2], m=force[2]))
        applied[face.group] = np.array(force, dtype=float)
    return supports, loads, applied


def solve_nonlinear(model: BeamModel, supports, loads, steps: int = 10,
                    max_iterations: int = 25, tol: float = 1e-9, min_step: float = 1e-4,
                    rigid_faces=(), **options) -> BeamPath:
    """Large-rotation (co-rotational) static solve, the loads, prescribed values and
    ``rigid_faces`` (RigidFace on one-node groups) scaled 0 -> 1 in ``steps`` increments
    (halved on failure down to ``min_step``)."""
    no_options("solve_nonlinear", options, ("solver", "check_stability"))
    held, applied_loads, applied = rigid_face_conditions(model, rigid_faces)
    nodal = node_loads(model, loads) + applied_loads
    result = solve_beam_nonlinear(model, node_supports(model, supports) + held, nodal,
                                  steps=steps, max_iterations=max_iterations, tol=tol,
                                  min_step=min_step)
    return BeamPath(model, result, tuple(supported_groups(supports)),
                    tuple(f.group for f in rigid_faces), applied,
                    load_array(model, nodal).ravel())


def compliance_matrix(model: BeamModel, supports, face, point=None, angle: float = 0.0,
                      frame=None, **options) -> Compliance:
    """3 x 3 compliance of the group ``face`` (one node: the master of its rigid body) under
    ``supports``, at ``point`` (m; default that node), in the axes rotated by ``angle`` (rad)
    or the columns of ``frame`` (as the continuum's compliance_matrix)."""
    no_options("compliance_matrix", options, ())
    nodes = group(model, face).nodes
    if len(nodes) != 1:
        raise ValueError(f"compliance_matrix: group {face!r} has {len(nodes)} nodes; a "
                         "compliance is of one rigid body (a group of one node)")
    C = shared_compliance(model, node_supports(model, supports), nodes[0])
    centre = model.nodes[nodes[0]].copy()
    return moved_compliance(face, C, centre, point, rotation_frame(2, angle, frame))


@dataclass(frozen=True, eq=False)
class BeamHarmonic(BeamFace):
    """Steady-state amplitudes: frequencies_hz (n,); q (n, n_nodes, 3) complex (m, rad);
    u (n, n_nodes, 2) their translations; method 'modal'."""

    model: BeamModel
    frequencies_hz: np.ndarray
    q: np.ndarray
    modes: BeamModes
    info: dict = field(default_factory=dict)

    method = "modal"

    @property
    def u(self) -> np.ndarray:
        """(n, n_nodes, 2) complex translation amplitudes, m."""
        return self.q[..., :2]

    def mean_displacement(self, name: str) -> np.ndarray:
        """(n, 2) complex mean displacement amplitude of the group, m."""
        return self.q[:, list(group(self.model, name).nodes), :2].mean(axis=1)

    def frf(self, name: str, component) -> FRF:
        """Response of the group's mean displacement along ``component`` (0/'x', 1/'y')."""
        i = {"x": 0, "y": 1}.get(component, component)
        if i not in (0, 1):
            raise ValueError(f"component = {component!r} must be 'x', 'y', 0 or 1")
        return FRF(self.frequencies_hz, self.mean_displacement(name)[:, i])


def solve_harmonic(model: BeamModel, supports, loads, frequencies_hz, damping=0.0,
                   n_modes: int = 20, **options) -> BeamHarmonic:
    """Steady-state response to the loads (amplitudes, N) by modal superposition of
    ``n_modes`` modes plus the static correction (exact at 0 Hz), as the continuum's 'modal'
    method: damping a modal damping ratio (one, or one per mode) or Rayleigh(alpha, beta)."""
    no_options("solve_harmonic", options, ("method",))
    f_hz = check_frequencies(frequencies_hz)
    held = [_at_zero(s) for s in node_supports(model, supports)]
    nodal = node_loads(model, loads)
    modes = solve_beam_modes(model, held, n=n_modes)
    static = solve_beam_static(model, held, nodal).q
    f = load_array(model, nodal)
    q, zeta = modal_superposition(modes.frequencies_hz, modes.shapes, f, static, f_hz, damping)
    return BeamHarmonic(model, f_hz, q.reshape(len(f_hz), model.n_nodes, 3), modes,
                        info={"n_modes": n_modes, "damping_ratios": zeta})


def modal_superposition(modes_hz, shapes, f, static, f_hz, damping) -> tuple:
    """((n_f, n_dofs) complex amplitudes, the modal damping ratios): the modes (Hz;
    mass-normalised ``shapes``, one row of DOFs each) driven by ``f``, plus the static
    residual ``static`` - sum phi p / w^2 (exact at 0 Hz); also the spatial face's."""
    w_r = 2 * np.pi * np.asarray(modes_hz)
    zeta = damping_ratios(damping, w_r)
    phi = shapes.reshape(len(w_r), -1)
    p = phi @ f.ravel()
    residual = static.ravel() - phi.T @ (p / w_r ** 2)
    omega = 2 * np.pi * f_hz
    with np.errstate(divide="ignore", invalid="ignore"):
        h = 1.0 / (w_r[None, :] ** 2 - omega[:, None] ** 2 + 2j * zeta * w_r * omega[:, None])
    return (h * p) @ phi + residual, zeta


def load_array(model: BeamModel, nodal) -> np.ndarray:
    """(n_nodes, 3) nodal loads (F_x, F_y N, M N m) of NodalLoads."""
    f = np.zeros((model.n_nodes, 3))
    for load in nodal:
        f[load.node] += load.vector(3)
    return f


def no_options(what: str, options: dict, ignored: tuple) -> None:
    """Options of the continuum's function that mean nothing on a beam model: those in
    ``ignored`` (a solver choice) are accepted, any other is a TypeError naming it."""
    unknown = sorted(set(options) - set(ignored))
    if unknown:
        raise TypeError(f"{what}: option(s) {unknown} are the continuum's; the beam model "
                        "takes none of them")


__all__ = ["BeamGroup", "BeamHarmonic", "BeamPath", "BeamResult",
           "compliance_matrix", "node_loads", "node_supports", "solve_harmonic",
           "solve_modes", "solve_nonlinear", "solve_static"]
