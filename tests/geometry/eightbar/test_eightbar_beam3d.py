"""The eight-bar's spatial beam model against its planar one: the same in-plane answers,
link inertias consistent, in-plane and out-of-plane modes decoupled."""
import numpy as np
import pytest

from flexfem.fem import beam as planar
from flexfem.fem.beam3d import Fixed, compliance3d, solve_beam3d_modes
from flexfem.geometry.eightbar.beam import eightbar_beam_model
from flexfem.geometry.eightbar.beam3d import eightbar_beam3d_model
from flexfem.geometry.eightbar.flexure import EightBarFlexureParams

IN_PLANE = [0, 1, 5]  # x, y, r_z of the spatial DOFs


def _both(params, n_per_flexure=24):  # 24: the planar modes' sparse solver (> 800 DOFs)
    m3, info = eightbar_beam3d_model(params, n_per_flexure)
    m2, _ = eightbar_beam_model(params, n_per_flexure)
    return m2, m3, info


def _in_plane(modes):
    """(in-plane, out-of-plane) frequencies: modes whose out-of-plane (z, r_x, r_y) or
    in-plane (x, y, r_z) amplitude is below 1e-6 of the other (the eigensolver leaves
    1e-8 of noise)."""
    s = np.abs(modes.shapes)
    lifted, flat = s[:, :, 2:5].max(axis=(1, 2)), s[:, :, IN_PLANE].max(axis=(1, 2))
    in_plane, out_of_plane = lifted <= 1e-6 * flat, flat <= 1e-6 * lifted
    assert np.all(in_plane ^ out_of_plane), "a mode mixes in-plane and out-of-plane motion"
    return modes.frequencies_hz[in_plane], modes.frequencies_hz[out_of_plane]


def test_spatial_eightbar_matches_the_planar_model_in_plane():
    """End-effector compliance (x, y, r_z) and the first six in-plane modes of the default
    design (root fillets: tapered elements, the same tapers in both models): to 1e-6
    (measured 3e-8, 5e-8: round-off through K's conditioning and the eigensolver)."""
    m2, m3, info = _both(EightBarFlexureParams())
    ground, ee = tuple(info["ground"]), info["end_effector"]
    C2 = planar.compliance(m2, [planar.Fixed(ground)], ee)
    C3 = compliance3d(m3, [Fixed(ground)], ee)[np.ix_(IN_PLANE, IN_PLANE)]
    assert np.abs(C3 - C2).max() <= 1e-6 * np.abs(np.diag(C2)).max()
    assert np.diag(C3) == pytest.approx(np.diag(C2), rel=1e-6)
    f2 = planar.solve_beam_modes(m2, [planar.Fixed(ground)], n=6).frequencies_hz
    in_plane, out_of_plane = _in_plane(solve_beam3d_modes(m3, [Fixed(ground)], n=10))
    assert in_plane[:6] == pytest.approx(f2, rel=1e-6)
    assert len(out_of_plane) >= 1


def test_link_inertias_add_up_to_the_planar_polar_inertia():
    """J_x + J_y = J_z + m w^2 / 6 for a plate of thickness w (perpendicular axes)."""
    params = EightBarFlexureParams()
    m3, _ = eightbar_beam3d_model(params)
    w = params.thickness
    assert len(m3.point_masses) == 7
    for m, jx, jy, jz in m3.point_masses.values():
        assert jx + jy == pytest.approx(jz + m * w**2 / 6, rel=1e-9)
