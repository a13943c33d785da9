"""Buckling about a converged state (flexfem.fem.analyses.solve_incremental_buckling) on the
continuum, the planar and the spatial beam model: Euler's columns about the unloaded state,
a preloaded column (the critical added load is P_cr - P_pre), and a leaf deflected sideways
then loaded along its original axis, where the state matters, by all three models."""
import math

import numpy as np
import pytest
import skfem

from flexfem.fem import (Fixed, Force, Material, Model, PlaneStress, Prescribed,
                         solve_buckling, solve_nonlinear, solve_static)
from flexfem.fem.analyses import solve_incremental_buckling
from flexfem.fem.beam import BeamModel, Section, beam_chain
from flexfem.fem.beam.spatial import Beam3DModel
from flexfem.fem.beam.spatial import Section as SpatialSection
from flexfem.fem.beam.supports import NodeFixed
from flexfem.fem.mesh import FEMesh, facets_where

L, W, T = 0.05, 0.01, 0.5e-3  # m: length, out-of-plane width, in-plane thickness
E_MOD = 200e9  # Pa
STEEL = Material("test steel", E=E_MOD, nu=0.3, rho=7800.0, yield_strength=250e6)
EI = E_MOD * W * T ** 3 / 12
P_E = math.pi ** 2 * EI / L ** 2  # pinned-pinned; clamped-free P_E / 4
DOWN = (-1.0, 0.0)  # the added load: along -x, the column's axis


def strip(length: float, nx: int) -> Model:
    """[0, length] x [0, T] (m), P2 triangles (L / T = 100), groups "base" and "top"."""
    m = skfem.MeshTri.init_tensor(np.linspace(0, length, nx + 1), np.linspace(0, T, 3))
    groups = {"base": facets_where(m, lambda x: np.isclose(x[0], 0.0)),
              "top": facets_where(m, lambda x: np.isclose(x[0], length))}
    return Model(FEMesh(m, groups), STEEL, PlaneStress(W), order=2)


def planar(length: float, n: int) -> BeamModel:
    mesh = beam_chain([(0, 0), (length, 0)], Section.rect(W, T), n)
    return BeamModel(mesh.nodes, mesh.elements, mesh.sections, STEEL,
                     groups={"base": [0], "top": [n]})


def spatial(length: float, n: int) -> Beam3DModel:
    nodes = np.linspace(0.0, length, n + 1)[:, None] * np.array([1.0, 0.0, 0.0])
    return Beam3DModel(nodes, [(i, i + 1) for i in range(n)], SpatialSection.rect(W, T), STEEL,
                       groups={"base": [0], "top": [n]})


def force(model, vector) -> Force:
    """A Force of the model's dimension (the spatial beam's z component 0)."""
    return Force("top", tuple(vector) + ((0.0,) if isinstance(model, Beam3DModel) else ()))


MODELS = {"continuum": lambda length: strip(length, 100),
          "planar beam": lambda length: planar(length, 16),
          "spatial beam": lambda length: spatial(length, 16)}
# pinned-pinned on half the column: the mid-span ("base") held from turning and along the
# axis (x held on the continuum's whole section), the pinned end ("top") held across
HALF_PINNED = {"continuum": [Prescribed("base", x=0.0), Prescribed("top", y=0.0)],
               "planar beam": [NodeFixed([0], ("x", "theta")), NodeFixed([16], ("y",))],
               "spatial beam": [NodeFixed([0], ("x", "z", "rx", "ry", "rz")),
                                NodeFixed([16], ("y", "z"))]}


def path_to(model, supports, preload: float, steps: int = 2):
    return solve_nonlinear(model, supports, [force(model, (-preload, 0.0))], steps=steps)


@pytest.mark.parametrize("name", sorted(MODELS))
def test_euler_column_about_the_unloaded_state(name):
    """Step 0 of a path is the unloaded state: the critical load is Euler's, clamped-free
    (pi^2 EI / 4 L^2) and pinned-pinned (pi^2 EI / L^2, on half the column); measured
    +2.9e-4 and -1.9e-3 on the continuum, 1.3e-7 on both beams (16 elements). 1 % allowed."""
    model = MODELS[name](L)
    path = path_to(model, [Fixed("base")], 0.3 * P_E / 4)
    b = solve_incremental_buckling(model, (path, 0), [Fixed("base")], [force(model, DOWN)],
                                   n=1)
    assert b.load_factors[0] == pytest.approx(P_E / 4, rel=0.01)
    assert b.step == 0
    half, held = MODELS[name](L / 2), HALF_PINNED[name]
    path = path_to(half, held, 0.3 * P_E, steps=1)
    b = solve_incremental_buckling(half, (path, 0), held, [force(half, DOWN)], n=1)
    assert b.load_factors[0] == pytest.approx(P_E, rel=0.01)


@pytest.mark.parametrize("name", sorted(MODELS))
def test_preloaded_column_buckles_under_the_rest(name):
    """About a column preloaded to P_pre = 0.6 P_cr the critical added load is P_cr - P_pre:
    exactly so in linear theory (the continuum's StaticResult state: K + K_sigma(P_pre) +
    lambda K_sigma(P), measured 8e-6, from the prestressed tangent's response); about the
    large-deflection state to the shortening's order (continuum 1.3e-5) and, on the beams,
    the co-rotational tangent's string-only geometric stiffness at 32 elements (measured
    3.4e-4)."""
    model = MODELS[name](L) if name == "continuum" else (
        planar(L, 32) if name == "planar beam" else spatial(L, 32))
    supports = [Fixed("base")]
    p_cr = solve_buckling(model, supports, [force(model, DOWN)], n=1).load_factors[0]
    pre = 0.6 * p_cr
    path = path_to(model, supports, pre)
    b = solve_incremental_buckling(model, path, supports, [force(model, DOWN)], n=2)
    assert b.step == len(path.load_factors) - 1
    assert b.load_factors[0] == pytest.approx(p_cr - pre, rel=1e-3 if name == "continuum"
                                              else 5e-4)
    if name == "continuum":
        linear = solve_static(model, supports, [force(model, (-pre, 0.0))])
        b = solve_incremental_buckling(model, linear, supports, [force(model, DOWN)], n=1)
        assert b.load_factors[0] == pytest.approx(p_cr - pre, rel=1e-4)
        assert b.step is None


def test_a_leaf_deflected_sideways_then_pressed_along_its_axis():
    """A cantilever leaf bent by a tip force F_y = 0.3 EI / L^2 (tip 0.1 L aside), then
    loaded along its original axis (-x): the critical added load rises above the straight
    leaf's Euler load by the state (continuum +3.0 %, beams +4.1 %), the beams within 1.0 %
    of the continuum (1.5 % allowed), the planar and the spatial beam alike. The beams'
    geometric stiffness has no bending-moment term: bent further (F_y = EI / L^2, tip 0.3 L
    aside) the continuum gives +32 %, the beams +46 %."""
    side = 0.3 * EI / L ** 2
    critical = {}
    for name, build in MODELS.items():
        model = build(L)
        path = solve_nonlinear(model, [Fixed("base")], [force(model, (0.0, side))], steps=4)
        b = solve_incremental_buckling(model, path, [Fixed("base")], [force(model, DOWN)],
                                       n=1)
        critical[name] = b.load_factors[0]
    assert critical["continuum"] / (P_E / 4) > 1.02
    for name in ("planar beam", "spatial beam"):
        assert critical[name] == pytest.approx(critical["continuum"], rel=0.015)
    assert critical["spatial beam"] == pytest.approx(critical["planar beam"], rel=1e-5)


def test_bad_input_is_refused_in_one_line():
    model = planar(L, 8)
    with pytest.raises(ValueError, match="not a beam path"):
        solve_incremental_buckling(model, np.zeros(27), [Fixed("base")], [force(model, DOWN)])
    path = path_to(model, [Fixed("base")], 0.2 * P_E / 4)
    with pytest.raises(ValueError, match="step"):
        solve_incremental_buckling(model, (path, 9), [Fixed("base")], [force(model, DOWN)])
    with pytest.raises(ValueError, match="positive integer"):
        solve_incremental_buckling(model, path, [Fixed("base")], [force(model, DOWN)], n=0)
    with pytest.raises(ValueError, match="move nothing"):
        solve_incremental_buckling(model, path, [Fixed("base")], [])
    with pytest.raises(TypeError, match="solver"):
        solve_incremental_buckling(model, path, [Fixed("base")], [force(model, DOWN)],
                                   solver="amg")
    # beyond its Euler load a column's straight state is unstable: no buckling about it
    past = solve_nonlinear(model, [Fixed("base"), Prescribed("top", y=0.0)],
                           [force(model, (-1.5 * P_E / 4, 0.0))], steps=2)
    with pytest.raises(ValueError, match="not stable"):
        solve_incremental_buckling(model, past, [Fixed("base")], [force(model, DOWN)])


def test_solid_column_about_the_unloaded_and_a_preloaded_state():
    """The 3-D continuum (P2 tetrahedra, a square column 2 mm across, L / h = 25): Euler's
    clamped-free load within 1 % (measured +0.3 %) about the unloaded state, the linear
    buckling's there (1e-9), and P_cr - P_pre about the state preloaded to 0.5 P_cr
    (measured -3e-4)."""
    from flexfem.fem import Solid3D
    h = 0.002
    m = skfem.MeshTet.init_tensor(np.linspace(0, L, 26), np.linspace(0, h, 3),
                                  np.linspace(0, h, 3))
    groups = {"base": facets_where(m, lambda x: np.isclose(x[0], 0.0)),
              "top": facets_where(m, lambda x: np.isclose(x[0], L))}
    model = Model(FEMesh(m, groups), STEEL, Solid3D(), order=2)
    down = [Force("top", (-1.0, 0.0, 0.0))]
    p_cr = solve_buckling(model, [Fixed("base")], down, n=1).load_factors[0]
    assert p_cr == pytest.approx(math.pi ** 2 * E_MOD * h ** 4 / 12 / (4 * L ** 2), rel=0.01)
    path = solve_nonlinear(model, [Fixed("base")], [Force("top", (-0.5 * p_cr, 0.0, 0.0))],
                           steps=2)
    at_rest = solve_incremental_buckling(model, (path, 0), [Fixed("base")], down, n=1)
    assert at_rest.load_factors[0] == pytest.approx(p_cr, rel=1e-6)
    preloaded = solve_incremental_buckling(model, path, [Fixed("base")], down, n=1)
    assert preloaded.load_factors[0] == pytest.approx(0.5 * p_cr, rel=2e-3)
