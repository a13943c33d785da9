"""Incremental linearised buckling of a beam model about a converged large-rotation state:
``solve_incremental_buckling(model, state, supports, loads, n) -> StateBuckling``, the
continuum's :func:`flexfem.fem.buckling.solve_incremental_buckling` on the planar and the
spatial beam model.

About the state (a step of the beam path: q, or (u, R)), the lowest lambda at which
K_T + lambda K_G is singular: K_T the co-rotational tangent there (the rigid links' term of
the state's forces included), du = K_T^-1 P the linear response to the added loads P,
K_G the geometric stiffness of the element axial-force increments dN of du (each element's
consistent geometric stiffness, :mod:`.buckling` and :mod:`.spatial.buckling`, turned into
the element's chord frame at the state; its length change, of the order of the axial strain,
left out) plus the rigid links' term of the force increments. dN is the directional
derivative of the co-rotational element forces along du (central differences). As in the
linear buckling, bending-moment and shear-force terms of K_G are left out; the path's own
loads are not scaled, so this is not the path's limit point.
"""
import numpy as np

from .assembly import BeamAssembler, Factor, gather
from .buckling import check_n, geometric_stiffness, lowest_load_factors, scaled_shapes
from .element import rotation_to_global
from .face import no_options, node_loads, node_supports
from .model import BeamModel
from .nonlinear import negative_eigenvalues
from .pattern import global_matrix
from .spatial import assembly as spatial_assembly
from .spatial import buckling as spatial_buckling
from .spatial.corotational import local_deformations
from .spatial.element import to_global
from .spatial.static import linear_solution
from .supports import NodePrescribed
from ..state_buckling import StateBuckling

STEP = 1e-6  # the central differences' step: the largest motion, over the model's size


def path_state(state) -> tuple:
    """(the step's state, its applied nodal loads (n_dofs,) N, step index) of a beam path
    (its last step) or (path, step)."""
    path, step = state if isinstance(state, tuple) and len(state) == 2 else (state, -1)
    states = getattr(getattr(path, "result", None), "states", None)
    if states is None or getattr(path, "applied", None) is None:
        raise ValueError(f"state: {type(path).__name__} is not a beam path; give the "
                         "solve_nonlinear result of the beam model, or (result, step)")
    if not (isinstance(step, (int, np.integer)) and -len(states) <= step < len(states)):
        raise ValueError(f"state step = {step!r} must index one of the {len(states)} steps")
    step = int(step) % len(states)
    return states[step], path.load_factors[step] * np.asarray(path.applied), step


def held_at_zero(model, supports) -> list:
    """The node supports of ``supports`` with every prescribed value 0 (the increments)."""
    return [NodePrescribed(s.node, s.dof, 0.0) if isinstance(s, NodePrescribed) else s
            for s in node_supports(model, supports)]


def _difference_step(dq, size: float, per_node: int) -> float:
    """h with the largest translation of h dq STEP of ``size`` and its rotation STEP rad."""
    d = np.asarray(dq).reshape(-1, per_node)
    t = per_node // 2 if per_node == 6 else 2
    big = max(np.abs(d[:, :t]).max() / size, np.abs(d[:, t:]).max())
    if not big > 0:
        raise ValueError("loads: the added loads move nothing: nothing to buckle")
    return STEP / big


def _check_stable(K) -> None:
    negative = negative_eigenvalues(K)
    if negative:
        raise ValueError(f"state: the tangent has {negative} negative eigenvalue(s) under "
                         "these supports: the state is not stable, no buckling about it")


def solve_incremental_buckling(model, state, supports, loads, n: int = 3,
                                **options) -> StateBuckling:
    """:func:`flexfem.fem.buckling.solve_incremental_buckling` of a planar or spatial beam
    model (see the module)."""
    check_n(n)
    no_options("solve_incremental_buckling", options, ())
    if getattr(model, "superelements", ()):
        raise ValueError("solve_incremental_buckling: the model has superelements, whose "
                         "geometric stiffness is unknown; solve the continuum")
    at, f_state, step = path_state(state)
    held, nodal = held_at_zero(model, supports), node_loads(model, loads)
    K, G, T, dq = (_planar if model.dim == 2 else _spatial)(model, at, f_state, held, nodal)
    factors, vectors = lowest_load_factors(K, G, n)
    full = np.asarray(T @ vectors).T
    per_node = model.PER_NODE
    return StateBuckling(model, factors, scaled_shapes(full, per_node),
                         np.asarray(dq).reshape(-1, per_node), step)


def _planar(model: BeamModel, at, f_state, held, nodal) -> tuple:
    """(K_T, K_G reduced, T = dq/dz, du full) of a planar model about the state ``at``."""
    asm = BeamAssembler(model, held, nodal)
    space, q = asm.space, at.q
    fe, ke, _ = asm.elements(q)
    w = space.weights(q)
    K = space.condense_global(global_matrix(
        model, ke, space.constraint_diagonal(q, gather(model, fe) - f_state)), w)
    _check_stable(K)
    rest = np.zeros(len(space.held))
    dq = space.expand(Factor(K).solve(space.reduce(asm.f_ext, w)[0]), rest, w)
    h = _difference_step(dq, np.ptp(model.nodes, axis=0).max(), 3)
    (fp, _, bp), (fm, _, bm) = (asm.elements(q + s * h * dq.reshape(-1, 3), tangent=False)
                                for s in (1.0, -1.0))
    dN = (bp[:, 0] - bm[:, 0]) / (2 * h)
    dr = (gather(model, fp) - gather(model, fm)) / (2 * h) - asm.f_ext
    x = model.nodes + q[:, :2]
    chord = x[model.elements[:, 1]] - x[model.elements[:, 0]]
    T0 = rotation_to_global(model.angles)
    T = rotation_to_global(np.arctan2(chord[:, 1], chord[:, 0]))
    local = T0 @ geometric_stiffness(model, dN) @ T0.transpose(0, 2, 1)
    G = space.condense_global(global_matrix(model, T.transpose(0, 2, 1) @ local @ T,
                                            space.constraint_diagonal(q, dr)), w)
    return K, G, space.jacobian(w), dq


def _spatial(model, at, f_state, held, nodal) -> tuple:
    """(K_T, K_G reduced, T = dq/dz, du full) of a spatial model about the state ``at``."""
    # the assembler of the increments' supports and loads, as the linear solve builds it
    asm = linear_solution(model, held, nodal)[-1]
    space, u, R = asm.space, at.u, at.R
    r, _, _, T, _, K_full, _ = asm.evaluate(u, R, 0.0)
    K_full = K_full + space.constraint_tangent(R, -f_state)  # r = f_int - the state's loads
    K = (T.T @ (0.5 * (K_full + K_full.T)) @ T).tocsc()
    _check_stable(K)
    dz = Factor(K).solve(T.T @ asm.f_ext)
    h = _difference_step(T @ dz, np.ptp(model.nodes, axis=0).max(), 6)
    (rp, fp), (rm, fm) = ((lambda c: (c[0], c[6]))(asm.evaluate(
        *space.update(u, R, s * h * dz, 0.0), 0.0, tangent=False)) for s in (1.0, -1.0))
    dN = (fp[:, 0] - fm[:, 0]) / (2 * h)
    dr = (rp - rm) / (2 * h) - asm.f_ext
    E0 = to_global(model.frames)
    E = to_global(local_deformations(model, model.nodes + u, R)[1][2])
    local = E0.transpose(0, 2, 1) @ spatial_buckling.geometric_stiffness(model, dN) @ E0
    links = space.constraint_tangent(R, dr)
    G_full = spatial_assembly.scatter(model, E @ local @ E.transpose(0, 2, 1)) \
        + 0.5 * (links + links.T)
    return K, (T.T @ G_full @ T).tocsc(), T, T @ dz
