"""The driving linkage's compensated coupler length is derived, not typed in: recomputing it
gives the value the default design uses (data/eightbar_design.toml)."""
import pytest

from flexfem.data import load_toml
from flexfem.geometry.eightbar.driving import DrivingParams
from flexfem.studies.eightbar.compensation import compensated_coupler_length


@pytest.mark.slow
def test_the_default_coupler_length_is_the_one_that_cancels_the_bow():
    derived = compensated_coupler_length()
    stored = load_toml("eightbar_design.toml")["driving"]["compensated_coupler_length_m"]
    assert derived == pytest.approx(stored, abs=1e-6)
    assert DrivingParams().suspension.coupler_length == stored
    assert derived > 50e-3   # longer than the Chapter 5 design: it pre-bows the rigid path
