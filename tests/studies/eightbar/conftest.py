"""The quick stage study, solved once for the stage's test modules (~2 min on a shared
machine: the continuum's stroke, its modes and its buckling along the stroke)."""
import pytest

from flexfem.studies.eightbar.stage import stage_study


@pytest.fixture(scope="session")
def stage():
    return stage_study(quick=True)
