"""The continuum's analysis face on a beam model with named groups, planar or spatial.

A group is what a mesh's boundary group is to the continuum: the place where supports hold
and loads act. On a beam model it is one or more nodes, each the master of a rigid body (a
block, a pad, a mounting face), and the extent of the face it stands for (``span``, m: (dx,
dy) planar, (dx, dy, dz) spatial). So the supports and loads of :mod:`flexfem.fem.boundary`
apply to either model:

- ``Fixed(group)`` holds every DOF of every node of the group: a clamped rigid face;
- ``Prescribed(group, x=..., y=..., z=...)`` holds those translations at the values; a
  translation i held on a face that spans along j (j != i) holds its rotation about the
  third axis too (every point of a rigid face having the same u_i means it does not turn
  about e_i x e_j; planar: the in-plane rotation), as the continuum's every-node constraint
  does;
- ``Force(group, vector)`` is the group's total force (N), shared equally by its nodes.

Results carry the continuum's names: ``mean_displacement(group)`` (the mean of the group's
nodes: the face's motion at its reference point), ``reactions[group]`` (N, summed over its
nodes), ``max_von_mises`` (the beam stress, Pa: planar |N|/A + |M| c / I, spatial the
rectangles' von Mises bound; no stress concentration) and ``max_von_mises_location`` (m).
Rigid faces (``rigid_faces``) on the planar model only. SI units.
"""
from dataclasses import dataclass, field

import numpy as np

from ..boundary import Fixed, Force, Prescribed
from ..compliance_result import Compliance, moved_compliance, rotation_frame
from ..frequency_response import FRF, check_frequencies, damping_ratios
from ..rigid_face_input import RigidFace
from .compliance import compliance, shared_compliance
from .modal import BeamModes, solve_beam_modes
from .model import BeamGroup, BeamModel
from .supports import NodalLoad, NodeFixed, NodePrescribed
from ..beam_result import BeamPath, BeamResult
from ..result_face import BeamFace
from .nonlinear import solve_beam_nonlinear
from .spatial.modal import solve_beam3d_modes
from .spatial.nonlinear import solve_beam3d_nonlinear
from .spatial.static import solve_beam3d_static
from .static import solve_beam_static

AXES = ("x", "y", "z")
ROTATIONS = {2: (None, None, "theta"), 3: ("rx", "ry", "rz")}  # about x, y, z
NAMES = {2: "planar beam model", 3: "spatial beam model"}
# each dimension's solvers: static, modes, nonlinear, compliance; Newton's default iterations
SOLVERS = {2: (solve_beam_static, solve_beam_modes, solve_beam_nonlinear, shared_compliance, 25),
           3: (solve_beam3d_static, solve_beam3d_modes, solve_beam3d_nonlinear, compliance,
               30)}


def group(model, name) -> BeamGroup:
    """The model's group ``name``; ValueError naming the known groups."""
    if name not in model.groups:
        raise ValueError(f"group {name!r} is not one of the {NAMES[model.dim]}'s groups "
                         f"{sorted(model.groups)}")
    return model.groups[name]


def held_rotations(axis: int, span) -> list:
    """The rotations (0 x, 1 y, 2 z) a translation along ``axis`` held uniformly on a rigid
    face of extent ``span`` (dx, dy[, dz]; m) holds with it: about e_axis x e_j for every j
    the face spans."""
    span = tuple(span) + (0.0,) * (3 - len(span))
    return sorted(3 - axis - j for j in range(3) if j != axis and span[j] > 0.0)


def node_supports(model, supports) -> list:
    """The beam model's own node supports for group supports (Fixed, Prescribed)."""
    out, dim = [], model.dim
    for s in supports:
        if isinstance(s, (NodeFixed, NodePrescribed)):
            out.append(s)
        elif isinstance(s, Fixed):
            out.append(NodeFixed(group(model, s.group).nodes))
        elif isinstance(s, Prescribed):
            g = group(model, s.group)
            values = s.components()
            if any(axis >= dim or callable(v) for axis, v in values.items()):
                raise ValueError(f"Prescribed({s.group!r}): the {NAMES[dim]} takes numbers "
                                 f"for {', '.join(AXES[:dim - 1])} and {AXES[dim - 1]} (m)")
            turns = sorted({k for axis in values for k in held_rotations(axis, g.span)})
            for n in g.nodes:
                out += [NodePrescribed(n, AXES[axis], float(v)) for axis, v in values.items()]
                out += [NodePrescribed(n, ROTATIONS[dim][k], 0.0) for k in turns]
        else:
            raise ValueError(f"supports: {s!r}: the {NAMES[dim]} takes Fixed and Prescribed")
    return out


def node_loads(model, loads) -> list:
    """NodalLoads for group forces (Force: the total, shared equally by the group's nodes)."""
    out, dim = [], model.dim
    for load in loads:
        if isinstance(load, NodalLoad):
            out.append(load)
        elif isinstance(load, Force):
            if not 2 <= len(load.vector) <= dim:
                raise ValueError(f"Force({load.group!r}): the {NAMES[dim]} takes (F_x, F_y)"
                                 f"{' or (F_x, F_y, F_z)' if dim == 3 else ''} in N")
            nodes = group(model, load.group).nodes
            f = np.zeros(3)
            f[:len(load.vector)] = np.asarray(load.vector, dtype=float) / len(nodes)
            out += [NodalLoad(n, f[0], f[1], fz=f[2]) for n in nodes]
        else:
            raise ValueError(f"loads: {type(load).__name__} on the {NAMES[dim]}: it takes "
                             "forces (Force, the group's total in N; in a model file force = "
                             "[...]); a traction, pressure or body load is the continuum's")
    return out


def supported_groups(supports) -> tuple:
    return tuple(s.group for s in supports if isinstance(s, (Fixed, Prescribed)))


def solve_static(model, supports, loads=(), rigid_faces=(), **options) -> BeamResult:
    """Linear static solve of a grouped beam model (the continuum's supports and loads;
    ``rigid_faces``, planar: RigidFace on one-node groups, a prescribed x, y or rotation
    held, a free one carrying the face's force or moment; face_motion reads them)."""
    no_options("solve_static", _faces_option(model, rigid_faces, options), ("solver",))
    held, face_loads, applied = rigid_face_conditions(model, rigid_faces)
    nodal = node_loads(model, loads) + face_loads
    state = SOLVERS[model.dim][0](model, node_supports(model, supports) + held, nodal)
    return BeamResult(model, state, supported_groups(supports),
                      faces=tuple(f.group for f in rigid_faces), face_loads=applied,
                      applied=load_array(model, nodal).ravel())


def _faces_option(model, rigid_faces, options) -> dict:
    """``options`` with ``rigid_faces`` among them on a spatial model (which takes none)."""
    return {**options, "rigid_faces": rigid_faces} if model.dim == 3 and rigid_faces \
        else options


def solve_modes(model, n: int = 6, supports=(), **options) -> BeamModes:
    """The ``n`` lowest natural frequencies (Hz) and shapes, supports held at zero (their
    values ignored, as the continuum's); effective_mass (n, dim) kg. A shift_hz is accepted
    and not needed (the beam's eigensolvers choose their own)."""
    no_options("solve_modes", options, ("shift_hz",))
    held = [_at_zero(s) for s in node_supports(model, supports)]
    return SOLVERS[model.dim][1](model, held, n=n)


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


def solve_nonlinear(model, supports, loads, steps: int = 10, max_iterations: int | None = None,
                    tol: float = 1e-9, min_step: float = 1e-4, rigid_faces=(),
                    **options) -> BeamPath:
    """Large-rotation (co-rotational) static solve, the loads, prescribed values and
    ``rigid_faces`` (planar: RigidFace on one-node groups) scaled 0 -> 1 in ``steps``
    increments (halved on failure down to ``min_step``); ``max_iterations`` per step
    (default 25 planar, 30 spatial)."""
    no_options("solve_nonlinear", _faces_option(model, rigid_faces, options),
               ("solver", "check_stability"))
    held, applied_loads, applied = rigid_face_conditions(model, rigid_faces)
    nodal = node_loads(model, loads) + applied_loads
    solvers = SOLVERS[model.dim]
    result = solvers[2](model, node_supports(model, supports) + held, nodal, steps=steps,
                        max_iterations=solvers[4] if max_iterations is None else max_iterations,
                        tol=tol, min_step=min_step)
    return BeamPath(model, result, supported_groups(supports),
                    tuple(f.group for f in rigid_faces), applied,
                    load_array(model, nodal).ravel())


def compliance_matrix(model, supports, face, point=None, angle: float = 0.0, frame=None,
                      **options) -> Compliance:
    """Compliance (3 x 3 planar, 6 x 6 spatial) of the group ``face`` (one node: the master
    of its rigid body) under ``supports``, at ``point`` (m; default that node), in the axes
    rotated by ``angle`` (rad, planar) or the columns of ``frame`` (as the continuum's
    compliance_matrix)."""
    no_options("compliance_matrix", options, ())
    nodes = group(model, face).nodes
    if len(nodes) != 1:
        raise ValueError(f"compliance_matrix: group {face!r} has {len(nodes)} nodes; a "
                         "compliance is of one rigid body (a group of one node)")
    C = SOLVERS[model.dim][3](model, node_supports(model, supports), nodes[0])
    centre = model.nodes[nodes[0]].copy()
    return moved_compliance(face, C, centre, point, rotation_frame(model.dim, angle, frame))


@dataclass(frozen=True, eq=False)
class BeamHarmonic(BeamFace):
    """Steady-state amplitudes: frequencies_hz (n,); q (n, n_nodes, DOFs a node) complex (m,
    rad); u (n, n_nodes, dim) their translations; method 'modal'."""

    model: object
    frequencies_hz: np.ndarray
    q: np.ndarray
    modes: BeamModes
    info: dict = field(default_factory=dict)

    method = "modal"

    @property
    def u(self) -> np.ndarray:
        """(n, n_nodes, dim) complex translation amplitudes, m."""
        return self.q[..., :self.model.dim]

    def mean_displacement(self, name: str) -> np.ndarray:
        """(n, dim) complex mean displacement amplitude of the group, m."""
        return self.u[:, list(group(self.model, name).nodes)].mean(axis=1)

    def frf(self, name: str, component) -> FRF:
        """Response of the group's mean displacement along ``component`` (0/'x', 1/'y',
        spatial 2/'z')."""
        dim = self.model.dim
        i = {"x": 0, "y": 1, "z": 2}.get(component, component)
        if i not in range(dim):
            words = ", ".join(f"'{a}'" for a in AXES[:dim]) + ", " + ", ".join(map(str, range(dim)))
            raise ValueError(f"component = {component!r} must be one of {words}")
        return FRF(self.frequencies_hz, self.mean_displacement(name)[:, i])


def solve_harmonic(model, supports, loads, frequencies_hz, damping=0.0, n_modes: int = 20,
                   **options) -> BeamHarmonic:
    """Steady-state response to the loads (amplitudes, N) by modal superposition of
    ``n_modes`` modes plus the static correction (exact at 0 Hz), as the continuum's 'modal'
    method: damping a modal damping ratio (one, or one per mode) or Rayleigh(alpha, beta)."""
    no_options("solve_harmonic", options, ("method",))
    f_hz = check_frequencies(frequencies_hz)
    held = [_at_zero(s) for s in node_supports(model, supports)]
    nodal = node_loads(model, loads)
    solvers = SOLVERS[model.dim]
    modes = solvers[1](model, held, n=n_modes)
    static = solvers[0](model, held, nodal).q
    f = load_array(model, nodal)
    q, zeta = modal_superposition(modes.frequencies_hz, modes.shapes, f, static, f_hz, damping)
    return BeamHarmonic(model, f_hz, q.reshape(len(f_hz), model.n_nodes, -1), modes,
                        info={"n_modes": n_modes, "damping_ratios": zeta})


def modal_superposition(modes_hz, shapes, f, static, f_hz, damping) -> tuple:
    """((n_f, n_dofs) complex amplitudes, the modal damping ratios): the modes (Hz;
    mass-normalised ``shapes``, one row of DOFs each) driven by ``f``, plus the static
    residual ``static`` - sum phi p / w^2 (exact at 0 Hz)."""
    w_r = 2 * np.pi * np.asarray(modes_hz)
    zeta = damping_ratios(damping, w_r)
    phi = shapes.reshape(len(w_r), -1)
    p = phi @ f.ravel()
    residual = static.ravel() - phi.T @ (p / w_r ** 2)
    omega = 2 * np.pi * f_hz
    with np.errstate(divide="ignore", invalid="ignore"):
        h = 1.0 / (w_r[None, :] ** 2 - omega[:, None] ** 2 + 2j * zeta * w_r * omega[:, None])
    return (h * p) @ phi + residual, zeta


def load_array(model, nodal) -> np.ndarray:
    """(n_nodes, DOFs a node) nodal loads (F N, M N m) of NodalLoads."""
    per_node = model.n_dofs // model.n_nodes
    f = np.zeros((model.n_nodes, per_node))
    for load in nodal:
        f[load.node] += load.vector(per_node)
    return f


def no_options(what: str, options: dict, ignored: tuple) -> None:
    """Options of the continuum's function that mean nothing on a beam model: those in
    ``ignored`` (a solver choice) are accepted, any other is a TypeError naming it."""
    unknown = sorted(set(options) - set(ignored))
    if unknown:
        raise TypeError(f"{what}: option(s) {unknown} are the continuum's; the beam model "
                        "takes none of them")


__all__ = ["BeamGroup", "BeamHarmonic", "BeamPath", "BeamResult",
           "compliance_matrix", "held_rotations", "node_loads", "node_supports",
           "solve_harmonic", "solve_modes", "solve_nonlinear", "solve_static"]
