"""The notch table of a description's notch (data/notch_description_factors.json, read by
flexfem.reduced.hinge_patch): its interpolation against the direct 2-D solve between its
nodes, within the accuracy docs/beam_speed.md states; what takes it and what is solved
directly."""
import logging
from pathlib import Path

import numpy as np
import pytest
from scipy.interpolate import PchipInterpolator

from flexfem.geometry.mechanism.beams import profile
from flexfem.geometry.mechanism.description import Notch
from flexfem.geometry.user_model import load_spec
from flexfem.reduced.hinge_patch import (NotchFactors, description_tabulated, pchip,
                                         profile_factors)
from flexfem.studies.user_model import analyze_model

ROOT = Path(__file__).resolve().parents[2]
# docs/beam_speed.md: the table against the direct solve halfway between its nodes (measured
# 5.1e-4, 9.6e-4, 2.4e-3 and 4.5e-2 at 108 points by scripts/notch_description_table.py --check)
ACCURACY = {"bending": 6e-4, "axial": 1e-3, "shear": 3e-3, "kt_bending": 5e-2,
            "kt_tension": 5e-2}
DIRECT = "no table holds"  # the log's words where the patch is solved directly


def notch_profile(t_over_r: float, aspect: float, R: float = 1e-3):
    """(profile, length) of a description's notch of neck t_over_r R, semi-axes R along and
    aspect R across (m)."""
    notch = Notch(("a", "b"), (0.0, 0.0), (2 * R, 0.0), t_over_r * R, R, aspect * R)
    return profile(notch, 2 * R), 2 * R


def test_pchip_is_scipys_monotone_cubic():
    rng = np.random.default_rng(3)
    x = np.sort(rng.random(8))
    y = rng.random((2, 3, 8))
    y[0, 1, 3] = y[0, 1, 4]  # a flat interval: zero slopes at its ends
    for at in (x[0], x[2], (x[4] + x[5]) / 2, x[-1]):
        expected = PchipInterpolator(x, y, axis=-1)(at)
        assert np.allclose(pchip(x, y, at), expected, rtol=0, atol=1e-14)


@pytest.mark.parametrize("point", [
    (0.12, 1.0, 0.3),     # a circular notch, as examples/bodies/notch.toml's t/R = 0.1
    (0.6, 1.7, 0.33),     # aluminium, a deep elliptical cut
    (0.036, 3.3, 0.26),   # a thin neck, far between the nodes of all three axes
])
def test_the_table_between_its_nodes_is_the_direct_solve(point):
    """The direct solve (table=False) at points off the table's nodes, against its
    interpolation: within the stated ACCURACY of each factor."""
    thickness, length = notch_profile(point[0], point[1])
    direct = profile_factors(thickness, length, point[2], table=False)
    table = description_tabulated(*point)
    for name in NotchFactors.__dataclass_fields__:
        assert getattr(table, name) == pytest.approx(getattr(direct, name),
                                                     rel=ACCURACY[name]), name


def test_a_description_notch_takes_the_table_at_any_size(caplog):
    """A bodies-and-flexures notch's profile in the table's range is looked up, not solved
    (nothing logged); the factors are scale-free: a 1 m notch gives the 1 mm one's."""
    caplog.set_level(logging.INFO, logger="flexfem.reduced.hinge_patch")
    small = profile_factors(*notch_profile(0.1, 3.0), 0.3)
    large = profile_factors(*notch_profile(0.1, 3.0, R=1.0), 0.3)
    assert small == description_tabulated(0.1, 3.0, 0.3)
    for name in NotchFactors.__dataclass_fields__:
        assert getattr(large, name) == pytest.approx(getattr(small, name), rel=1e-12)
    analyze_model(load_spec(ROOT / "examples" / "bodies" / "notch.toml"), model="beam")
    assert not [r for r in caplog.records if DIRECT in r.getMessage()]


def test_outside_the_table_the_patch_is_solved_and_logged(caplog):
    """An aspect beyond the table (6 > 4) or nu below it is not extrapolated: the range check
    says None, and profile_factors solves the patch and logs it."""
    assert description_tabulated(0.5, 6.0, 0.3) is None
    assert description_tabulated(0.5, 1.0, 0.064) is None  # silicon's nu
    assert description_tabulated(3.0, 1.0, 0.3) is None
    caplog.set_level(logging.INFO, logger="flexfem.reduced.hinge_patch")
    f = profile_factors(*notch_profile(1.0, 6.0), 0.3)
    assert 0 < f.bending < 1
    assert [r for r in caplog.records if DIRECT in r.getMessage()]
