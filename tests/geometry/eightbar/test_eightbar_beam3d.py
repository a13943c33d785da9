"""The eight-bar's spatial beam model: with rigid links against its planar one (the same
in-plane answers, link inertias consistent); with flexible links (link plates and anchors as
beams) the plates' mass and inertia kept, converged in the link elements; in-plane and
out-of-plane modes decoupled in both."""
import numpy as np
import pytest

from flexfem.fem import beam as planar
from flexfem.fem.beam.spatial import compliance3d, solve_beam3d_modes
from flexfem.fem.beam.supports import NodeFixed
from flexfem.fem.beam.spatial.inertia import mass_properties
from flexfem.reduced.layout import link_inertia
from flexfem.reduced.eightbar import eightbar_beam_model
from flexfem.reduced.eightbar3d import eightbar_beam3d_model, link_plate_inertia
from flexfem.geometry.eightbar.flexure import EightBarFlexureParams, eightbar_layout

IN_PLANE = [0, 1, 5]  # x, y, r_z of the spatial DOFs


def _both(params, n_per_flexure=24):  # 24: the planar modes' sparse solver (> 800 DOFs)
    m3, info = eightbar_beam3d_model(params, n_per_flexure, links="rigid")
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
    C2 = planar.compliance(m2, [NodeFixed(ground)], ee)
    C3 = compliance3d(m3, [NodeFixed(ground)], ee)[np.ix_(IN_PLANE, IN_PLANE)]
    assert np.abs(C3 - C2).max() <= 1e-6 * np.abs(np.diag(C2)).max()
    assert np.diag(C3) == pytest.approx(np.diag(C2), rel=1e-6)
    f2 = planar.solve_beam_modes(m2, [NodeFixed(ground)], n=6).frequencies_hz
    in_plane, out_of_plane = _in_plane(solve_beam3d_modes(m3, [NodeFixed(ground)], n=10))
    assert in_plane[:6] == pytest.approx(f2, rel=1e-6)
    assert len(out_of_plane) >= 1


def test_link_inertias_add_up_to_the_planar_polar_inertia():
    """J_x + J_y = J_z + m w^2 / 6 for a plate of thickness w (perpendicular axes)."""
    params = EightBarFlexureParams()
    m3, _ = eightbar_beam3d_model(params, links="rigid")
    w = params.thickness
    assert len(m3.point_masses) == 7
    for m, jx, jy, jz in m3.point_masses.values():
        assert jx + jy == pytest.approx(jz + m * w**2 / 6, rel=1e-9)


def test_flexible_links_keep_each_plate_s_mass_and_inertia():
    """Each link's beams (their consistent mass's rigid-body motions) against its plate, the
    union of its rectangles (link_moments): mass to 1e-12; centroid and J_x, J_y, J_z (about
    it) to 1e-9 for the links whose parts meet at right angles (couplers, end-effector), to
    the oblique slivers for the cranks and rockers (measured 2 um, 1e-5, 9.8e-4, 1e-5). The
    whole model: the rigid-link model's mass plus the four anchors'."""
    params = EightBarFlexureParams()
    layout = eightbar_layout(params)
    model, info = eightbar_beam3d_model(params)
    rho, w = model.material.rho, params.thickness
    for link, (first, last) in info["links"].items():
        m, c, J = mass_properties(model, range(first, last))
        m_ref, c_ref, jx, jy = link_plate_inertia(layout.parts, link, w, rho)
        jz = link_inertia(layout.parts, link, w, rho)[2]
        right_angles = link.startswith(("coupler", "end_effector"))
        rel = 1e-9 if right_angles else 2e-3
        assert m == pytest.approx(m_ref, rel=1e-12)
        assert c == pytest.approx([*c_ref, 0.0], abs=rel * layout.link_width)
        assert np.diag(J) == pytest.approx([jx, jy, jz], rel=rel), link
    anchors = [p for p in layout.parts if p.kind == "anchor"]
    rigid, _ = eightbar_beam3d_model(params, links="rigid")
    extra = sum(rho * w * p.width * p.length for p in anchors)
    assert mass_properties(model)[0] == pytest.approx(mass_properties(rigid)[0] + extra,
                                                      rel=1e-12)


def test_flexible_links_converge_in_the_link_elements_and_decouple():
    """The first ten modes with link elements of W (5 mm) and W / 2: the same to 1e-6 (the
    links' own modes are far above these); in-plane and out-of-plane modes still decouple.
    All ten at or below the rigid-link model's (which is this model with the plates made
    rigid, less the anchors' mass and the cranks' product of inertia: Rayleigh's principle,
    nearly; measured 0.1-17 % below)."""
    params = EightBarFlexureParams()
    f = []
    for size in (None, params.link_width / 2):
        model, info = eightbar_beam3d_model(params, link_element=size)
        modes = solve_beam3d_modes(model, [NodeFixed(tuple(info["ground"]))], n=10)
        _in_plane(modes)
        f.append(modes.frequencies_hz)
    assert f[1] == pytest.approx(f[0], rel=1e-6)
    rigid, info = eightbar_beam3d_model(params, links="rigid")
    stiff = solve_beam3d_modes(rigid, [NodeFixed(tuple(info["ground"]))], n=10).frequencies_hz
    assert np.all(f[0] <= stiff * (1 + 1e-9))


def test_links_option_is_checked():
    with pytest.raises(ValueError, match="links = 'soft' must be one of"):
        eightbar_beam3d_model(EightBarFlexureParams(), links="soft")
    with pytest.raises(ValueError, match="link_element = -0.001 m must be a number > 0"):
        eightbar_beam3d_model(EightBarFlexureParams(), link_element=-1e-3)
