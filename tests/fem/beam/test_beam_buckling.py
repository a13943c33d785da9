"""Linear buckling of the planar beam model (fem/beam/buckling.py) through the analysis face,
against Euler's columns, Engesser's shear-flexible column and a column with a rigid arm."""
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from flexfem.fem import Fixed, Force, Prescribed, material, solve_buckling
from flexfem.fem.beam import BeamModel, RigidLink, Section, Superelement, beam_chain

L, W, T = 0.05, 0.01, 0.5e-3
STEEL = material("structural_steel")
EI = STEEL.E * W * T ** 3 / 12
P_E = math.pi ** 2 * EI / L ** 2  # pinned-pinned; clamped-free P_E / 4


def column(n: int, shear: bool = False, thickness: float = T) -> BeamModel:
    """A column along x of n elements, groups "base" (node 0) and "top" (node n)."""
    mesh = beam_chain([(0, 0), (L, 0)], Section.rect(W, thickness), n)
    return BeamModel(mesh.nodes, mesh.elements, mesh.sections, STEEL, shear=shear,
                     groups={"base": [0], "top": [n]})


CLAMPED_FREE = ([Fixed("base")], P_E / 4, (1, 9, 25))
PINNED = ([Prescribed("base", x=0.0, y=0.0), Prescribed("top", y=0.0)], P_E, (1, 4, 9))


def factors(model, supports, n=3) -> np.ndarray:
    return solve_buckling(model, supports, [Force("top", (-1.0, 0.0))], n=n).load_factors


@pytest.mark.parametrize("supports, p1, ratios", [CLAMPED_FREE, PINNED],
                         ids=["clamped-free", "pinned-pinned"])
def test_euler_columns(supports, p1, ratios):
    """4 elements: P1 +3.3e-5 (clamped-free), +5.1e-4 (pinned-pinned) of Euler's load; 16
    elements: the three lowest in Euler's ratios within 8e-5 and 1.6e-4."""
    assert factors(column(4), supports, 1)[0] == pytest.approx(p1, rel=1e-3)
    assert factors(column(16), supports) == pytest.approx(p1 * np.array(ratios), rel=3e-4)


@pytest.mark.parametrize("supports, p1", [CLAMPED_FREE[:2], PINNED[:2]],
                         ids=["clamped-free", "pinned-pinned"])
def test_euler_load_converges_as_h4(supports, p1):
    """The consistent geometric stiffness of the cubic element: the error of P1 falls by
    ~16 each time the elements are halved (measured 15.6-16.0), from above."""
    errors = [factors(column(n), supports, 1)[0] / p1 - 1.0 for n in (2, 4, 8)]
    assert all(e > 0 for e in errors)
    assert errors[0] < 1e-2
    assert errors[0] / errors[1] > 14 and errors[1] / errors[2] > 14


def test_timoshenko_column_is_engessers():
    """A stocky column (L/t = 5) with shear: P = P_E / (1 + P_E / kappa G A) (Engesser),
    the transverse interpolation's own shear (Friedman & Kosmatka's functions): +0.027 % at
    16 elements (+0.47 % at 4, +0.11 % at 8: order 2 with shear); 9.3 % below Euler there."""
    t = L / 5
    p_e = math.pi ** 2 * STEEL.E * W * t ** 3 / 12 / L ** 2
    kGA = 5 / 6 * STEEL.E / (2 * (1 + STEEL.nu)) * W * t
    engesser = p_e / (1 + p_e / kGA)
    got = factors(column(16, shear=True, thickness=t), PINNED[0], 1)[0]
    assert got == pytest.approx(engesser, rel=1e-3)
    assert got / p_e < 0.92


def test_a_fine_mesh_takes_the_sparse_eigensolver():
    """300 elements (897 unknowns, above the dense solver's 800): Lanczos on a factor of K,
    within 3e-7 of Euler's three lowest (the factor's round-off on K's conditioning)."""
    got = factors(column(300), CLAMPED_FREE[0])
    assert got == pytest.approx(P_E / 4 * np.array(CLAMPED_FREE[2]), rel=1e-6)


def rigid_arm_column(n: int, arm: float) -> BeamModel:
    """A clamped column with a rigid arm of length ``arm`` on along its axis beyond the top:
    the load acts at the arm's end (group "end", a rigid-link slave of the top node)."""
    mesh = beam_chain([(0, 0), (L, 0)], Section.rect(W, T), n)
    nodes = np.vstack([mesh.nodes, [(L + arm, 0.0)]])
    return BeamModel(nodes, mesh.elements, mesh.sections, STEEL,
                     rigid_links=[RigidLink(n, (n + 1,))], groups={"base": [0], "end": [n + 1]})


def test_a_rigid_arm_carries_its_load_around():
    """The column's top carries a rigid arm of length a = L / 2 with the dead axial load at
    its end: the load turns with the arm (the links' second-order term), and
    cot(k L) = k a, k^2 = P / EI; 16 elements within 3e-8 (4: 7e-6)."""
    a = L / 2
    kL = brentq(lambda x: math.cos(x) - (a / L) * x * math.sin(x), 1e-6, math.pi / 2)
    expected = EI * (kL / L) ** 2
    got = solve_buckling(rigid_arm_column(16, a), [Fixed("base")],
                         [Force("end", (-1.0, 0.0))], n=1).load_factors[0]
    assert got == pytest.approx(expected, rel=1e-4)
    assert got < P_E / 4 * 0.6  # the arm matters: 0.47 of the bare column's


def test_linear_buckling_does_not_depend_on_the_load_size():
    """Linear buckling is about the reference configuration: with the load on a rigid arm
    across the column (its top turns under the load), the critical load is the same for a
    1 N and a 1 mN load (the links' term evaluated at zero rotation, not at the state)."""
    mesh = beam_chain([(0, 0), (L, 0)], Section.rect(W, T), 16)
    nodes = np.vstack([mesh.nodes, [(L, L / 2)]])
    model = BeamModel(nodes, mesh.elements, mesh.sections, STEEL,
                      rigid_links=[RigidLink(16, (17,))], groups={"base": [0], "end": [17]})
    critical = [p * solve_buckling(model, [Fixed("base")], [Force("end", (-p, 0.0))],
                                   n=1).load_factors[0] for p in (1.0, 1e-3)]
    assert critical[0] == pytest.approx(critical[1], rel=1e-9)


def test_the_result_reads_as_the_continuums():
    """load_factors, shapes (n, n_nodes, 3) scaled to a largest translation of 1,
    vertex_shape, prebuckling (the face's static result) and critical_reaction."""
    model = column(16)
    b = solve_buckling(model, [Fixed("base")], [Force("top", (-2.0, 0.0))], n=2)
    assert b.load_factors == pytest.approx([P_E / 8, 9 * P_E / 8], rel=1e-3)
    assert b.shapes.shape == (2, 17, 3)
    first = b.vertex_shape(0)
    assert np.abs(first).max() == pytest.approx(1.0)
    assert abs(first[-1, 1]) == pytest.approx(1.0)  # the free end moves most, sideways
    assert first[0] == pytest.approx([0.0, 0.0])
    assert b.prebuckling.reactions["base"] == pytest.approx([2.0, 0.0])
    assert b.critical_reaction("base") == pytest.approx([P_E / 4, 0.0], rel=1e-3)


def test_what_it_cannot_buckle_is_named():
    model = column(4)
    with pytest.raises(ValueError, match="no beam in compression"):
        solve_buckling(model, [Fixed("base")], [Force("top", (1.0, 0.0))])
    with pytest.raises(ValueError, match="without axial force"):
        solve_buckling(model, [Fixed("base")], [])
    with pytest.raises(ValueError, match="positive integer"):
        solve_buckling(model, [Fixed("base")], [Force("top", (-1.0, 0.0))], n=0)
    with pytest.raises(TypeError, match="continuum's"):
        solve_buckling(model, [Fixed("base")], [Force("top", (-1.0, 0.0))], shift=1.0)
    patched = BeamModel(model.nodes, model.elements, model.sections, STEEL,
                        superelements=[Superelement((1, 2), np.eye(6), np.eye(6))],
                        groups={"base": [0], "top": [4]})
    with pytest.raises(ValueError, match="superelements"):
        solve_buckling(patched, [Fixed("base")], [Force("top", (-1.0, 0.0))])


def test_the_guide_buckles_as_its_continuum():
    """examples/bodies/guide.toml under a compressive stage load: the beam model (root
    extensions, Timoshenko) against the continuum's solve_buckling (2-D, 5106 DOFs): the
    sway and the two next modes -1.5, -1.3, -1.3 % (the continuum at half the element size:
    -1.1, -1.0, -0.9 %, so about -1 % converged)."""
    from flexfem.geometry.user_model import load_spec
    from flexfem.studies.user_model.analysis import build, supports_and_loads

    spec = load_spec(Path(__file__).resolve().parents[3] / "examples" / "bodies" / "guide.toml")
    supports, _ = supports_and_loads(spec)
    load = [Force("stage", (0.0, -1.0))]
    beam = solve_buckling(build(spec, "beam")[0], supports, load, n=3).load_factors
    continuum = solve_buckling(build(spec)[0], supports, load, n=3).load_factors
    assert beam == pytest.approx(continuum, rel=0.025)
    assert np.all(beam < continuum)
