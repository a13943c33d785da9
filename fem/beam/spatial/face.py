"""The continuum's analysis face on a spatial beam model with named groups.

The spatial twin of :mod:`flexfem.fem.beam.face`: a group is one or more nodes, each the
master of a rigid body, and the extent (dx, dy, dz) of the face it stands for (m). The
supports and loads of :mod:`flexfem.fem.boundary` apply as they do to a 3-D continuum:

- ``Fixed(group)`` holds all six DOFs of every node of the group: a clamped rigid face;
- ``Prescribed(group, x=..., y=..., z=...)`` holds those translations at the values; a
  translation i held on a face that spans along j (j != i) holds its rotation about the third
  axis too (every point of a rigid face having the same u_i means it does not turn about
  e_i x e_j), as the continuum's every-node constraint does;
- ``Force(group, vector)`` is the group's total force (N; (F_x, F_y) or (F_x, F_y, F_z)),
  shared equally by its nodes.

Results carry the continuum's names: ``mean_displacement(group)`` (3,), ``reactions[group]``
(N), ``max_von_mises`` (the rectangular sections' von Mises bound, Pa; no stress
concentration) with ``max_von_mises_location``, ``frequencies_hz`` and ``effective_mass``
(n, 3), and a 6 x 6 :class:`~flexfem.fem.compliance.Compliance`. SI units.
"""
from dataclasses import dataclass, field

import numpy as np

from ...boundary import Fixed, Force, Prescribed
from ...compliance import Compliance, moved_compliance, rotation_frame
from ..face import no_options, modal_superposition
from ...harmonic import FRF, check_frequencies
from .modal import Beam3DModes, solve_beam3d_modes
from .model import Beam3DModel
from ..supports import Fixed as NodeFixed
from ..supports import NodalLoad
from ..supports import Prescribed as NodePrescribed
from ...beam3d_result import Beam3DPath, Beam3DResult
from ...result_face import BeamFace
from .nonlinear import solve_beam3d_nonlinear
from .static import compliance3d, solve_beam3d_static

AXES = ("x", "y", "z")
ROTATIONS = ("rx", "ry", "rz")


def group(model: Beam3DModel, name):
    """The model's group ``name``; ValueError naming the known groups."""
    if name not in model.groups:
        raise ValueError(f"group {name!r} is not one of the spatial beam model's groups "
                         f"{sorted(model.groups)}")
    return model.groups[name]


def held_rotations(axis: int, span) -> list:
    """The rotations (0 x, 1 y, 2 z) a translation along ``axis`` held uniformly on a rigid
    face of extent ``span`` (dx, dy, dz; m) holds with it: about e_axis x e_j for every j the
    face spans."""
    return sorted(3 - axis - j for j in range(3) if j != axis and span[j] > 0.0)


def node_supports(model: Beam3DModel, supports) -> list:
    """The spatial model's node supports for group supports (Fixed, Prescribed)."""
    out = []
    for s in supports:
        if isinstance(s, (NodeFixed, NodePrescribed)):
            out.append(s)
        elif isinstance(s, Fixed):
            out.append(NodeFixed(group(model, s.group).nodes))
        elif isinstance(s, Prescribed):
            g = group(model, s.group)
            values = s.components()
            if any(callable(v) for v in values.values()):
                raise ValueError(f"Prescribed({s.group!r}): the spatial beam model takes "
                                 "numbers for x, y and z (m)")
            span = tuple(g.span) + (0.0,) * (3 - len(g.span))
            turns = sorted({k for axis in values for k in held_rotations(axis, span)})
            for n in g.nodes:
                out += [NodePrescribed(n, AXES[axis], float(v)) for axis, v in values.items()]
                out += [NodePrescribed(n, ROTATIONS[k], 0.0) for k in turns]
        else:
            raise ValueError(f"supports: {s!r}: the spatial beam model takes Fixed and "
                             "Prescribed")
    return out


def node_loads(model: Beam3DModel, loads) -> list:
    """NodalLoads for group forces (Force: the total, shared equally by the group's nodes)."""
    out = []
    for load in loads:
        if isinstance(load, NodalLoad):
            out.append(load)
        elif isinstance(load, Force):
            if len(load.vector) not in (2, 3):
                raise ValueError(f"Force({load.group!r}): the spatial beam model takes (F_x, "
                                 "F_y) or (F_x, F_y, F_z) in N")
            nodes = group(model, load.group).nodes
            f = np.zeros(3)
            f[:len(load.vector)] = np.asarray(load.vector, dtype=float) / len(nodes)
            out += [NodalLoad(n, f[0], f[1], fz=f[2]) for n in nodes]
        else:
            raise ValueError(f"loads: {type(load).__name__} on the spatial beam model: it "
                             "takes forces (Force, the group's total in N)")
    return out


def supported_groups(supports) -> tuple:
    return tuple(s.group for s in supports if isinstance(s, (Fixed, Prescribed)))


def solve_static(model: Beam3DModel, supports, loads=(), **options) -> Beam3DResult:
    """Linear static solve of a grouped spatial beam model (the continuum's supports and
    loads)."""
    no_options("solve_static", options, ("solver",))
    nodal = node_loads(model, loads)
    state = solve_beam3d_static(model, node_supports(model, supports), nodal)
    return Beam3DResult(model, state, supported_groups(supports),
                        applied=load_array(model, nodal).ravel())


def _at_zero(support):
    if isinstance(support, NodePrescribed):
        return NodePrescribed(support.node, support.dof, 0.0)
    return support


def solve_modes(model: Beam3DModel, n: int = 6, supports=(), **options) -> Beam3DModes:
    """The ``n`` lowest natural frequencies (Hz) and shapes, supports held at zero (their
    values ignored, as the continuum's); effective_mass (n, 3) kg."""
    no_options("solve_modes", options, ("shift_hz",))
    held = [_at_zero(s) for s in node_supports(model, supports)]
    return solve_beam3d_modes(model, held, n=n)


def solve_nonlinear(model: Beam3DModel, supports, loads, steps: int = 10,
                    max_iterations: int = 30, tol: float = 1e-9, min_step: float = 1e-4,
                    **options) -> Beam3DPath:
    """Large-rotation (co-rotational) static solve, the loads and prescribed values scaled
    0 -> 1 in ``steps`` increments (halved on failure down to ``min_step``)."""
    no_options("solve_nonlinear", options, ("solver", "check_stability"))
    nodal = node_loads(model, loads)
    result = solve_beam3d_nonlinear(model, node_supports(model, supports), nodal,
                                    steps=steps, max_iterations=max_iterations, tol=tol,
                                    min_step=min_step)
    return Beam3DPath(model, result, supported_groups(supports),
                      load_array(model, nodal).ravel())


def compliance_matrix(model: Beam3DModel, supports, face, point=None, frame=None,
                      **options) -> Compliance:
    """6 x 6 compliance of the group ``face`` (one node: the master of its rigid body) under
    ``supports``, at ``point`` (m; default that node), in the axes ``frame`` (columns; default
    global), as the continuum's compliance_matrix."""
    no_options("compliance_matrix", options, ())
    nodes = group(model, face).nodes
    if len(nodes) != 1:
        raise ValueError(f"compliance_matrix: group {face!r} has {len(nodes)} nodes; a "
                         "compliance is of one rigid body (a group of one node)")
    C = compliance3d(model, node_supports(model, supports), nodes[0])
    centre = model.nodes[nodes[0]].copy()
    return moved_compliance(face, C, centre, point, rotation_frame(3, 0.0, frame))


@dataclass(frozen=True, eq=False)
class Beam3DHarmonic(BeamFace):
    """Steady-state amplitudes: frequencies_hz (n,); u (n, n_nodes, 3) complex (m); method
    'modal'; info."""

    model: Beam3DModel
    frequencies_hz: np.ndarray
    u: np.ndarray
    modes: Beam3DModes
    info: dict = field(default_factory=dict)

    method = "modal"

    def mean_displacement(self, name: str) -> np.ndarray:
        """(n, 3) complex mean displacement amplitude of the group, m."""
        return self.u[:, list(group(self.model, name).nodes)].mean(axis=1)

    def frf(self, name: str, component) -> FRF:
        """Response of the group's mean displacement along ``component`` (0-2 or x, y, z)."""
        i = {"x": 0, "y": 1, "z": 2}.get(component, component)
        if i not in (0, 1, 2):
            raise ValueError(f"component = {component!r} must be 'x', 'y', 'z', 0, 1 or 2")
        return FRF(self.frequencies_hz, self.mean_displacement(name)[:, i])


def solve_harmonic(model: Beam3DModel, supports, loads, frequencies_hz, damping=0.0,
                   n_modes: int = 20, **options) -> Beam3DHarmonic:
    """Steady-state response to the loads (amplitudes, N) by modal superposition of
    ``n_modes`` modes plus the static correction (exact at 0 Hz), as the continuum's 'modal'
    method: damping a modal damping ratio (one, or one per mode) or Rayleigh(alpha, beta)."""
    no_options("solve_harmonic", options, ("method",))
    f_hz = check_frequencies(frequencies_hz)
    held = [_at_zero(s) for s in node_supports(model, supports)]
    nodal = node_loads(model, loads)
    modes = solve_beam3d_modes(model, held, n=n_modes)
    static = solve_beam3d_static(model, held, nodal)
    f = load_array(model, nodal)
    q, zeta = modal_superposition(modes.frequencies_hz, modes.shapes, f, static.q, f_hz,
                                  damping)
    return Beam3DHarmonic(model, f_hz, q.reshape(len(f_hz), model.n_nodes, 6)[..., :3], modes,
                          info={"n_modes": n_modes, "damping_ratios": zeta})


def load_array(model: Beam3DModel, nodal) -> np.ndarray:
    """(n_nodes, 6) nodal loads (F N, M N m) of NodalLoads."""
    f = np.zeros((model.n_nodes, 6))
    for load in nodal:
        f[load.node] += load.vector(6)
    return f


__all__ = ["Beam3DHarmonic", "Beam3DPath", "Beam3DResult", "compliance_matrix",
           "node_loads", "node_supports", "solve_harmonic", "solve_modes",
           "solve_nonlinear", "solve_static"]
