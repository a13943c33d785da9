"""The driving linkage's beam model generated from its flexure layout
(geometry/eightbar/driving_beam.py) and its pseudo-rigid-body input stiffness."""
import numpy as np
import pytest

from flexfem.geometry.eightbar.driving import DrivingParams, driving_layout
from flexfem.geometry.eightbar.driving_beam import (driving_beam_model, driving_joint_rates,
                                                    driving_prbm_stiffness)
from flexfem.geometry.eightbar.flexure import EightBarFlexureParams


def test_generated_from_the_flexure_layout():
    params, flexure = DrivingParams(), EightBarFlexureParams()
    layout = driving_layout(params, flexure)
    model, info = driving_beam_model(params, flexure, n_per_flexure=8)
    assert len(info["flexures"]) == len(layout.joints) == 34
    assert len(info["ground"]) == sum(fj.other == "ground" for fj in layout.joints) == 12
    for face in ("input", "ee_L", "ee_R"):  # master nodes on the continuum's faces
        centre = np.mean(layout.edges[face], axis=0)
        assert model.nodes[info[face]] == pytest.approx(centre, abs=1e-12)
    # the flexures' elements span their drawn length plus 0.38 x the root thickness (width
    # and both fillets) into both roots
    root = 2 * flexure.root_fillet_radius
    for fj in layout.joints:
        first, last = info["flexures"][fj.name]
        assert model.lengths[first:last].sum() == pytest.approx(
            fj.length + 2 * 0.38 * (fj.width + root), rel=1e-8)


def test_prbm_rates_are_mirror_symmetric():
    rates = driving_joint_rates(DrivingParams())
    for name, rate in rates.items():
        if name.startswith(("lamR", "susR")):
            mirror = name.replace("lamR", "lamL").replace("susR", "susL")
            assert rates[mirror] == pytest.approx(-rate, rel=1e-6, abs=1e-9)
    share = driving_prbm_stiffness(DrivingParams(), EightBarFlexureParams())["joints"]
    assert len(share) == 34 and min(share.values()) >= 0
