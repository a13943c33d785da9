"""Fixtures for the beam-model tests."""
import pytest

from flexfem.fem import Material


@pytest.fixture
def steel():
    return Material("steel", E=200e9, nu=0.3, rho=7800.0)
