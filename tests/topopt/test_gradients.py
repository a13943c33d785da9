"""Every objective's and constraint's gradient against central finite differences, on a
6 x 4 grid with the density filter active (the sensitivity filter is a heuristic, not a
gradient), for SIMP and RAMP, with passive elements and symmetry, through the Heaviside
projection at several beta and the Helmholtz filter; compliance over two load cases, the
lowest eigenfrequency and the stress norm."""
import numpy as np
import pytest
from problems import inverter, mbb

from flexfem.topopt import (Constraint, Interpolation, Optimizer, Passive, Projection, Region,
                            Response)
from flexfem.topopt.model import Discrete

CONSTRAINTS = (Constraint(Response("volume"), upper=0.4),
               Constraint(Response("displacement", "input"), upper=5.0),
               Constraint(Response("compliance"), upper=10.0),
               Constraint(Response("displacement", "output"), lower=-2.0))


def fd_check(problem, seed=0, beta=None, low=0.3, span=0.5):
    d = Discrete(problem)
    d.beta = beta if beta is not None else d.beta
    rng = np.random.default_rng(seed)
    z = np.clip(low + span * rng.random(d.n_variables), d.lower, d.upper)
    ev = d.evaluate(z)
    sign = 1.0 if problem.sense == "min" else -1.0
    h = 1e-6
    fd0, fdc = np.zeros(z.size), np.zeros((len(ev.constraints), z.size))
    for j in range(z.size):
        zp, zm = z.copy(), z.copy()
        zp[j] += h
        zm[j] -= h
        ep, em = d.evaluate(zp), d.evaluate(zm)
        fd0[j] = sign * (ep.objective - em.objective) / (2 * h)
        fdc[:, j] = (ep.constraints - em.constraints) / (2 * h)
    scale = np.max(np.abs(fd0))
    assert np.max(np.abs(ev.objective_grad - fd0)) < 1e-5 * scale
    for k in range(len(ev.constraints)):
        scale = max(np.max(np.abs(fdc[k])), 1e-12)
        assert np.max(np.abs(ev.constraint_grads[k] - fdc[k])) < 1e-5 * scale, k


@pytest.mark.parametrize("kind", ["simp", "ramp"])
def test_compliance_and_volume_gradients(kind):
    fd_check(mbb(6, 4, "density", 1.5, interpolation=Interpolation(kind, 3.0)))


@pytest.mark.parametrize("kind", ["simp", "ramp"])
@pytest.mark.parametrize("sense", ["min", "max"])
def test_mechanism_gradients_of_every_response(kind, sense):
    fd_check(inverter(6, 4, "density", constraints=CONSTRAINTS, sense=sense,
                       interpolation=Interpolation(kind, 3.0)))


def test_gradients_with_passive_regions_and_symmetry():
    passive = (Passive(Region("box", ((0.0, 0.0), (1.0, 1.0))), "solid"),
               Passive(Region("box", ((5.0, 3.0), (6.0, 4.0))), "void"))
    fd_check(mbb(6, 4, "density", 1.5, passive=passive, symmetry=("y",)))
    fd_check(inverter(6, 4, "none", constraints=CONSTRAINTS, symmetry=("x",)))


@pytest.mark.parametrize("beta", [1.0, 8.0])
def test_gradients_through_the_heaviside_projection(beta):
    projection = Projection(beta=1.0, eta=0.4, beta_max=64.0)
    fd_check(mbb(6, 4, "density", 1.5, projection=projection), beta=beta)
    fd_check(inverter(6, 4, "density", constraints=CONSTRAINTS, projection=projection,
                       passive=(Passive(Region("box", ((0.0, 0.0), (1.0, 1.0))), "solid"),)),
              beta=beta)


def test_gradients_of_weighted_compliance_over_two_load_cases():
    weighted = Response("compliance", weights=(1.0, 2.5))
    fd_check(mbb(6, 4, "density", 1.5, second_load=(-0.5, -0.3), objective=weighted,
                  optimizer=Optimizer("mma"),
                  constraints=(Constraint(Response("volume"), upper=0.4),
                               Constraint(Response("compliance", weights=(0.0, 1.0)),
                                          upper=5.0))))


def test_gradient_of_a_displacement_in_the_second_load_case():
    fd_check(inverter(6, 4, "density", second_load=(0.0, -1.0), constraints=(
        Constraint(Response("displacement", "output", case=2), upper=1.0),)))


@pytest.mark.parametrize("low", [0.3, 0.02])
def test_gradient_of_the_lowest_eigenfrequency(low):
    """Above and below 0.1, where the mass interpolation changes (z in [low, low + 0.5]
    or [0.02, 0.07]: every physical density on one side)."""
    frequency = Constraint(Response("frequency"), lower=0.01)
    fd_check(mbb(6, 4, "density", 1.5, mass_density=2.0, optimizer=Optimizer("mma"),
                  constraints=(Constraint(Response("volume"), upper=0.4), frequency)),
              low=low, span=0.5 if low > 0.1 else 0.05)


@pytest.mark.parametrize("relaxation", [0.5, 1.0])
def test_gradient_of_the_stress_norm(relaxation):
    stress = Constraint(Response("stress", pnorm=8.0, relaxation=relaxation), upper=1.0)
    fd_check(mbb(6, 4, "density", 1.5, second_load=(-0.5, -0.3), optimizer=Optimizer("mma"),
                  constraints=(stress,)))
    fd_check(inverter(6, 4, "density", constraints=(stress,),
                       projection=Projection(beta=4.0, eta=0.5)))


def test_gradients_through_the_helmholtz_filter():
    fd_check(mbb(6, 4, "helmholtz", 2.5, optimizer=Optimizer("mma")))
    fd_check(inverter(6, 4, "helmholtz", constraints=CONSTRAINTS,
                       projection=Projection(beta=4.0, eta=0.5), symmetry=("x",)))
