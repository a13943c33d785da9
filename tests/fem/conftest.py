"""Fixtures of the FEM tests (the small meshes are in meshes.py)."""
import pytest

from flexfem.fem import Material


@pytest.fixture(scope="session")
def steel():
    return Material("test steel", E=200e9, nu=0.3, rho=7800.0, yield_strength=250e6)
