"""The cached undeformed system of a beam model (fem/beam/linear.py): extra prescribed DOFs
by a Schur complement on the Fixed supports' factor, the banded Cholesky factor
(fem/beam/banded.py) and the block Lanczos modes on it (fem/beam/eigen.py), against closed
forms (Euler-Bernoulli: the cubic Hermite element is exact for a prismatic beam under end
loads), SuperLU and a dense eigen-solver."""
import numpy as np
import pytest

from beam_models import cantilever, parallel_guide
from flexfem.fem.beam import NodalLoad, SingularBeamError, solve_beam_modes
from flexfem.fem.beam.supports import NodeFixed, NodePrescribed
from flexfem.fem.beam import solve_beam_static
from flexfem.fem.beam.assembly import Factor
from flexfem.fem.beam.banded import BandedCholesky
from flexfem.fem.beam.eigen import lowest_modes
from flexfem.fem.beam.linear import linear_system
from flexfem.fem.beam.modal import dense_lowest_modes

BETA_L = np.array([1.8751041, 4.6940911, 7.8547574])


def test_prescribed_tip_cantilever_and_guided(steel):
    L, w, t, d = 0.1, 0.01, 1e-3, 1e-4
    model, tip = cantilever(steel, L, w, t, n=20)
    EI = steel.E * w * t**3 / 12
    free = solve_beam_static(model, [NodeFixed(0), NodePrescribed(tip, "y", d)])
    guided = solve_beam_static(model, [NodeFixed(0), NodePrescribed(tip, "y", d),
                                       NodePrescribed(tip, "theta", 0.0)])
    assert free.reactions[tip][1] == pytest.approx(3 * EI * d / L**3, rel=1e-9)
    assert guided.reactions[tip][1] == pytest.approx(12 * EI * d / L**3, rel=1e-9)
    assert guided.q[tip, 2] == 0.0 or abs(guided.q[tip, 2]) < 1e-15
    # equilibrium: the clamp carries the tip's force
    assert free.reactions[0][1] == pytest.approx(-free.reactions[tip][1], rel=1e-9)
    assert free.info["n_unknowns"] == 3 * 20 - 1  # the tip's y held: one unknown less


def test_prescribed_stage_of_parallel_guide(steel):
    """Rigid-link slaves on the Schur path: the guided stage (rotation held) of two leaves
    is 2 x 12 E I / L^3 stiff."""
    L, w, t, d = 0.05, 0.01, 0.5e-3, 1e-4
    model, supports, stage = parallel_guide(steel, L, w, t, n=50)
    s = solve_beam_static(model, supports + [NodePrescribed(stage, "y", d),
                                             NodePrescribed(stage, "theta", 0.0)])
    assert s.reactions[stage][1] == pytest.approx(24 * steel.E * w * t**3 / 12 * d / L**3,
                                                  rel=1e-9)
    # the same stage force as a load, on the Fixed supports' system alone, moves it back
    k = s.reactions[stage]
    loaded = solve_beam_static(model, supports, [NodalLoad(stage, fy=k[1], m=k[2])])
    assert loaded.q[stage, 1] == pytest.approx(d, rel=1e-8)


def test_singular_fixed_base_falls_back(steel):
    """Fixed supports that leave a mechanism (the root's rotation free) completed by a
    Prescribed one: solved on the supports' own system."""
    L, w, t, d = 0.1, 0.01, 1e-3, 1e-4
    model, tip = cantilever(steel, L, w, t, n=20)
    s = solve_beam_static(model, [NodeFixed(0, ("x", "y")), NodePrescribed(0, "theta", 0.0),
                                  NodePrescribed(tip, "y", d)])
    assert s.reactions[tip][1] == pytest.approx(3 * steel.E * w * t**3 / 12 * d / L**3,
                                                rel=1e-9)
    with pytest.raises(SingularBeamError):
        solve_beam_static(model, [NodeFixed(0, ("x", "y"))], [NodalLoad(tip, fy=1.0)])


def test_banded_cholesky_matches_superlu(steel):
    model, supports, _ = parallel_guide(steel)
    K = linear_system(model, supports).ev.K
    b = np.random.default_rng(1).standard_normal((K.shape[0], 3))
    x = BandedCholesky(K).solve(b)
    ref = Factor(K).solve(b)
    assert np.abs(x - ref).max() <= 1e-9 * np.abs(ref).max()
    assert BandedCholesky(K).solve(b[:, 0]) == pytest.approx(x[:, 0], rel=1e-12)


def test_krylov_modes_match_dense_and_euler_bernoulli(steel):
    """300 elements (899 unknowns, above DENSE_EIGEN_LIMIT): the block Lanczos path."""
    L, w, t = 0.1, 0.01, 1e-3
    model, _ = cantilever(steel, L, w, t, n=300)
    modes = solve_beam_modes(model, [NodeFixed(0)], n=4)
    system = linear_system(model, [NodeFixed(0)])
    assert system.space.n > 800
    w2, _ = dense_lowest_modes(system.ev.K.toarray(), system.mass.toarray(), 4)
    # K of 300 elements is ill-conditioned (~1e10): the dense solver, ARPACK and this one
    # scatter by ~5e-7 in f1 about the converged discretisation's (100 elements) value
    assert modes.frequencies_hz == pytest.approx(np.sqrt(w2) / (2 * np.pi), rel=1.5e-6)
    coarse = solve_beam_modes(cantilever(steel, L, w, t, n=100)[0], [NodeFixed(0)], n=4)
    assert modes.frequencies_hz == pytest.approx(coarse.frequencies_hz, rel=1.5e-6)
    bending = modes.frequencies_hz[modes.effective_mass_fraction[:, 1] > 1e-6][:3]
    f_eb = BETA_L**2 / (2 * np.pi * L**2) * np.sqrt(steel.E * t**2 / 12 / steel.rho)
    assert bending == pytest.approx(f_eb, rel=5e-4)  # rotary inertia: < 3e-4
    again = solve_beam_modes(model, [NodeFixed(0)], n=4)
    assert np.array_equal(again.frequencies_hz, modes.frequencies_hz)  # fixed start block


def test_lowest_modes_gives_up_beyond_max_dim(steel):
    model, _ = cantilever(steel, n=300)
    system = linear_system(model, [NodeFixed(0)])
    assert lowest_modes(system.factor.solve, system.mass, 4, max_dim=8) is None
    w2, phi = lowest_modes(system.factor.solve, system.mass, 4)
    assert phi.T @ (system.mass @ phi) == pytest.approx(np.eye(4), abs=1e-10)
    assert np.all(np.diff(w2) > 0)


def test_modes_with_prescribed_dofs_on_the_fixed_factor(steel):
    """Modes held by Fixed + Prescribed DOFs, solved on the Fixed supports' factor with those
    unknowns held at zero (the route the static solves take), against the held system
    assembled and factored on its own (block Lanczos; and the dense eigensolver, which on
    this K of condition ~1e12 is good to ~1e-7): a cantilever with its midpoint held along y
    and in rotation (900 DOFs: the Krylov route)."""
    model, _ = cantilever(steel, n=300)
    supports = [NodeFixed(0), NodePrescribed(150, "y", 0.0), NodePrescribed(150, "theta", 0.0)]
    solve_beam_static(model, [NodeFixed(0)], [NodalLoad(300, fy=-1.0)])  # Fixed system cached
    modes = solve_beam_modes(model, supports, n=5)
    own = linear_system(cantilever(steel, n=300)[0], supports)
    w2, _ = lowest_modes(own.factor.solve, own.mass, 5)
    assert modes.frequencies_hz == pytest.approx(np.sqrt(w2) / (2 * np.pi), rel=1e-9)
    w2, _ = dense_lowest_modes(own.ev.K.toarray(), own.mass.toarray(), 5)
    assert modes.frequencies_hz == pytest.approx(np.sqrt(w2) / (2 * np.pi), rel=2e-7)
    held = modes.shapes[:, 150, 1:]  # v and theta of the held node: zero in every mode
    assert np.abs(held).max() <= 1e-12 * np.abs(modes.shapes).max()


def test_element_matrices_of_distinct_elements_equal_every_elements(steel):
    """The local stiffness and mass computed once per distinct element (same section and
    length) and spread: bit for bit those of every element computed on its own."""
    from flexfem.fem.beam.element import (_distinct, _local_mass, _local_stiffness,
                                          local_mass, local_stiffness)
    model = parallel_guide(steel)[0]
    assert _distinct(model).n_elements < model.n_elements
    assert np.array_equal(local_stiffness(model), _local_stiffness(model))
    assert np.array_equal(local_mass(model), _local_mass(model))
