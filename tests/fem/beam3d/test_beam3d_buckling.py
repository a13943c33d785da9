"""Linear buckling of the spatial beam model (fem/beam/spatial/buckling.py) through the analysis
face: Euler's columns about both axes (one of them oblique), their convergence, Saint-Venant
torsional buckling, a rigid arm, and the planar model's factors in the plane."""
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from flexfem.fem import Fixed, Force, material, solve_buckling
from flexfem.fem.beam import BeamModel, RigidLink as PlanarLink, Section as PlanarSection
from flexfem.fem.beam import beam_chain
from flexfem.fem.beam.spatial import Beam3DModel, RigidLink, Section
from flexfem.fem.beam.supports import NodeFixed
from flexfem.reduced.spatial import lifted_model

L, W, T = 0.05, 0.75e-3, 0.5e-3   # width (local z) 1.5 times the thickness (local y)
STEEL = material("structural_steel")
EI_WEAK = STEEL.E * W * T ** 3 / 12    # about local z
EI_STRONG = STEEL.E * T * W ** 3 / 12  # about local y: 2.25 EI_WEAK
OBLIQUE = np.array([1.0, 2.0, 2.0]) / 3.0  # a column in no coordinate plane


def column(n: int, axis=(1.0, 0.0, 0.0), section=None, arm: float = 0.0) -> Beam3DModel:
    """A column of n elements along ``axis`` from the origin, groups "base" and "top" (and a
    rigid arm of length ``arm`` beyond the top, its end the group "end", where arm > 0)."""
    axis = np.asarray(axis)
    nodes = np.linspace(0.0, L, n + 1)[:, None] * axis
    links, groups = (), {"base": [0], "top": [n]}
    if arm:
        nodes = np.vstack([nodes, (L + arm) * axis])
        links, groups["end"] = [RigidLink(n, (n + 1,))], [n + 1]
    return Beam3DModel(nodes, [(i, i + 1) for i in range(n)], section or Section.rect(W, T),
                       STEEL, rigid_links=links, groups=groups)


def factors(model, supports, axis=(1.0, 0.0, 0.0), n=3, group="top") -> np.ndarray:
    load = Force(group, tuple(-np.asarray(axis, dtype=float)))
    return solve_buckling(model, supports, [load], n=n).load_factors


# pinned-pinned along x: the base's translations and twist held, the top's lateral motion
PINNED = [NodeFixed([0], ("x", "y", "z", "rx"))]


def pinned(n: int) -> list:
    return PINNED + [NodeFixed([n], ("y", "z"))]


def test_euler_columns_about_both_axes():
    """An oblique clamped-free column: the weak axis's 1 and 9, the strong axis's 2.25 (x
    P_weak), 8 elements +2.1e-6, +2.1e-6, +1.6e-4; a pinned-pinned column along x: 1, 2.25
    and 4, +3.3e-5, +3.3e-5, +5.1e-4; the lowest of 4 elements +3.3e-5 and +5.1e-4."""
    p = math.pi ** 2 / (4 * L ** 2)
    expected = p * np.array([EI_WEAK, EI_STRONG, 9 * EI_WEAK])
    assert factors(column(8, OBLIQUE), [Fixed("base")], OBLIQUE) == pytest.approx(expected,
                                                                                 rel=2e-4)
    assert factors(column(4, OBLIQUE), [Fixed("base")], OBLIQUE, 1)[0] == pytest.approx(
        expected[0], rel=1e-4)
    expected = 4 * p * np.array([EI_WEAK, EI_STRONG, 4 * EI_WEAK])
    assert factors(column(8), pinned(8)) == pytest.approx(expected, rel=6e-4)
    assert factors(column(4), pinned(4), n=1)[0] == pytest.approx(expected[0], rel=6e-4)


def test_the_weak_axis_buckles_out_of_its_plane():
    """The first shape of the column along x bends about local z (the section's weak axis,
    global z by default): sideways in y; the second (strong axis) in z."""
    b = solve_buckling(column(16), [Fixed("base")], [Force("top", (-1.0, 0.0, 0.0))], n=2)
    tip = np.array([b.vertex_shape(k)[-1] for k in range(2)])
    assert np.abs(tip).ravel() == pytest.approx([0, 1, 0, 0, 0, 1], abs=1e-9)
    assert b.shapes.shape == (2, 17, 6)


def test_euler_load_converges_as_h4():
    """Both planes, the planar element's rate: the error falls ~16 times when the elements
    are halved, from above."""
    p = math.pi ** 2 / (4 * L ** 2) * np.array([EI_WEAK, EI_STRONG])
    errors = np.array([factors(column(n, OBLIQUE), [Fixed("base")], OBLIQUE, 2) / p - 1.0
                       for n in (2, 4, 8)])
    assert np.all(errors > 0) and np.all(errors[0] < 1e-3)
    assert np.all(errors[0] / errors[1] > 14) and np.all(errors[1] / errors[2] > 14)


def test_a_fine_mesh_takes_the_sparse_eigensolver():
    """160 elements (960 unknowns, above the dense solver's 800): within 1.3e-7 of Euler."""
    p = math.pi ** 2 / (4 * L ** 2) * np.array([EI_WEAK, EI_STRONG, 9 * EI_WEAK])
    got = factors(column(160, OBLIQUE), [Fixed("base")], OBLIQUE)
    assert got == pytest.approx(p, rel=1e-6)


def test_torsional_buckling_is_saint_venants():
    """A section of little torsional stiffness (J = 1e-5 I) buckles by twisting at
    P = G J A / I_p (Wagner's term, no warping), exact with any number of elements (-3.9e-11)."""
    I, A = EI_WEAK / STEEL.E, W * T
    section = Section(A=A, Iy=I, Iz=I, J=1e-5 * I)
    G = STEEL.E / (2 * (1 + STEEL.nu))
    got = factors(column(3, OBLIQUE, section), [Fixed("base")], OBLIQUE, 1)[0]
    assert got == pytest.approx(G * 1e-5 * A / 2, rel=1e-9)  # 0.1 of the flexural load


def test_a_rigid_arm_carries_its_load_around():
    """An oblique clamped column whose top carries a rigid arm of length a = L / 2 along it,
    the dead load at the arm's end: cot(k L) = k a, k^2 = P / EI, 16 elements +2.9e-8."""
    a = L / 2
    kL = brentq(lambda x: math.cos(x) - (a / L) * x * math.sin(x), 1e-6, math.pi / 2)
    got = factors(column(16, OBLIQUE, arm=a), [Fixed("base")], OBLIQUE, 1, "end")[0]
    assert got == pytest.approx(EI_WEAK * (kL / L) ** 2, rel=1e-6)


def test_a_portal_frame_buckles_as_the_planar_model():
    """A planar portal frame (two columns, a beam; a rigid stage on the columns' tops, as a
    parallel guide's) under a vertical load on the stage, and its lift into space: the
    in-plane sway factors agree to 1e-13; the sway 4.0e-4 below 2 pi^2 E I / h^2 (the
    stage's tilt on the leaves' axial stiffness)."""
    leaf = PlanarSection.rect(0.01, T)
    h, gap = L, 0.02
    mesh = beam_chain([(0, 0), (0, h)], leaf, 10).join(beam_chain([(gap, 0), (gap, h)],
                                                                  leaf, 10))
    tops = (mesh.node_at((0, h)), mesh.node_at((gap, h)))
    nodes = np.vstack([mesh.nodes, [(gap / 2, h)]])
    stage = len(nodes) - 1
    planar = BeamModel(nodes, mesh.elements, mesh.sections, STEEL,
                       rigid_links=[PlanarLink(stage, tops)],
                       groups={"ground": [mesh.node_at((0, 0)), mesh.node_at((gap, 0))],
                               "stage": [stage]})
    load = [Force("stage", (0.0, -1.0))]
    flat = solve_buckling(planar, [Fixed("ground")], load, n=2).load_factors
    space = solve_buckling(lifted_model(planar, 0.01), [Fixed("ground")], load,
                           n=2).load_factors
    assert space == pytest.approx(flat, rel=1e-8)
    ei = STEEL.E * 0.01 * T ** 3 / 12  # each leaf clamped-guided: pi^2 EI / h^2 (sway)
    assert flat[0] == pytest.approx(2 * math.pi ** 2 * ei / h ** 2, rel=1e-3)
