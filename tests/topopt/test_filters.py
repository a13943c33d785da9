"""The Helmholtz (PDE) filter: a uniform field stays uniform, the filter is symmetric, a
cosine mode is damped by the continuous equation's factor 1 / (1 + R^2 k^2) with
R = radius / (2 sqrt 3), and the MBB beam designed with it is the density filter's beam.
(Its gradients: tests/topopt/test_gradients.py.)"""
import numpy as np
import pytest
from problems import mbb

from flexfem.topopt import Grid, optimize
from flexfem.topopt.filters import Filter


def test_a_uniform_field_stays_uniform():
    grid = Grid(30, 10, 3.0, 1.0)
    rho = Filter(grid, "helmholtz", 4.0).physical(np.full(grid.n_elements, 0.37))
    assert np.max(np.abs(rho - 0.37)) < 1e-13


def test_the_filter_is_symmetric_and_averages():
    grid = Grid(7, 5, 7.0, 5.0)
    f = Filter(grid, "helmholtz", 2.5)
    A = np.column_stack([f.physical(e) for e in np.eye(grid.n_elements)])
    assert np.max(np.abs(A - A.T)) < 1e-15
    assert A.min() > 0 and np.allclose(A.sum(axis=1), 1.0, atol=1e-14)
    g = np.random.default_rng(0).normal(size=grid.n_elements)
    assert np.allclose(f.back(None, g), A.T @ g, atol=1e-14)


@pytest.mark.parametrize("k", [10, 20])
def test_a_cosine_mode_is_damped_as_the_equation_says(k):
    """On a long strip, cos(pi k x / L) (zero slope at both ends, as the filter's boundary
    condition) is an eigenfunction of -R^2 u'' + u: filtered, its amplitude is
    1 / (1 + (R pi k / L)^2); the bilinear discretisation adds ~(pi k / nelx)^2 / 12."""
    grid = Grid(200, 2, 200.0, 2.0)
    radius = 6.0
    x = np.cos(np.pi * k * grid.centres[:, 0] / grid.lx)
    rho = Filter(grid, "helmholtz", radius).physical(x)
    R = radius / (2.0 * np.sqrt(3.0))
    factor = 1.0 / (1.0 + (R * np.pi * k / grid.lx) ** 2)
    assert (rho @ x) / (x @ x) == pytest.approx(factor, rel=0.015)
    assert np.max(np.abs(rho - (rho @ x) / (x @ x) * x)) < 1e-3


def test_the_mbb_beam_with_it_is_the_density_filters():
    """60 x 20, r = 3, OC: compliance 252.30 against 249.17 (1.3 %), mean density
    difference 0.022."""
    density = optimize(mbb(filter_kind="density", radius=3.0))
    pde = optimize(mbb(filter_kind="helmholtz", radius=3.0))
    assert pde.converged and pde.volume_fraction == pytest.approx(0.5, abs=1e-3)
    assert abs(pde.objective / density.objective - 1) < 0.02
    assert np.mean(np.abs(pde.density - density.density)) < 0.05
