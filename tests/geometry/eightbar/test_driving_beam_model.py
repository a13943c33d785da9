"""The driving linkage's beam model generated from its flexure layout
(reduced/driving.py) and its pseudo-rigid-body input stiffness."""
import numpy as np
import pytest

from flexfem.geometry.eightbar.driving import (DrivingParams, driving_layout,
                                              mesh_driving_flexure)
from flexfem.reduced.driving import (driving_beam_model, driving_joint_rates,
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
    # the flexures' elements span their drawn length plus 0.38 x the root thickness into
    # both roots, at their drawn width (sharp roots: the continuum's mesh draws no fillets)
    for fj in layout.joints:
        first, last = info["flexures"][fj.name]
        assert model.lengths[first:last].sum() == pytest.approx(
            fj.length + 2 * 0.38 * fj.width, rel=1e-8)
        inner = [model.sections[e] for e in range(first + 1, last - 1)]  # no root elements
        assert {(s.taper or (s.depth_y, s.depth_y))[:2] for s in inner} == {
            (fj.width, fj.width)}


def test_roots_as_the_continuum_draws_them():
    """The continuum's mesh of the driving linkage has sharp roots whatever
    root_fillet_radius says (no root zone is meshed), so the beam model has none either; the
    fillets stay available as an option."""
    params, flexure = DrivingParams(), EightBarFlexureParams()
    assert flexure.root_fillet_radius > 0
    _, sizes = mesh_driving_flexure(params, flexure, size_factor=4.0)
    assert "root_size" not in sizes  # mesh_layout's key for filleted roots
    sharp, _ = driving_beam_model(params, flexure, n_per_flexure=8)
    filleted, _ = driving_beam_model(params, flexure, n_per_flexure=8,
                                     fillet_radius=flexure.root_fillet_radius)
    def thickest(model):
        return max(s.depth_y for s in model.sections if s.depth_y is not None)
    assert thickest(sharp) == max(flexure.flexure_width, flexure.base_flexure_width)
    assert thickest(filleted) > thickest(sharp)


def test_prbm_rates_are_mirror_symmetric():
    rates = driving_joint_rates(DrivingParams())
    for name, rate in rates.items():
        if name.startswith(("lamR", "susR")):
            mirror = name.replace("lamR", "lamL").replace("susR", "susL")
            assert rates[mirror] == pytest.approx(-rate, rel=1e-6, abs=1e-9)
    share = driving_prbm_stiffness(DrivingParams(), EightBarFlexureParams())["joints"]
    assert len(share) == 34 and min(share.values()) >= 0
