"""Flexure suspension geometry: validation, layout, mesh groups and the pseudo-rigid-body model."""
from dataclasses import replace

import numpy as np
import pytest
from flexfem.geometry.eightbar.flexure import (
    HOSTS,
    EightBarFlexureParams,
    eightbar_layout,
    flexure_contacts,
    flexure_rotational_stiffness,
    joint_rotation_rates,
    mesh_eightbar_flexure,
    prbm_stiffness,
)
from flexfem.geometry.eightbar.rigid import EightBarParams


@pytest.fixture(scope="module")
def params():
    return EightBarFlexureParams()


def test_flexures_are_centred_on_the_joints_and_have_their_sizes(params):
    layout = eightbar_layout(params)
    assert len(layout.joints) == 10
    for fj in layout.joints:
        part = layout.flexure(fj.name)
        centre = (np.asarray(part.p0) + np.asarray(part.p1)) / 2
        assert np.allclose(centre, fj.position, atol=1e-12)
        assert part.length == pytest.approx(params.flexure_size(fj.name)[0], rel=1e-12)
        assert part.width == params.flexure_size(fj.name)[1]
        assert fj.host == HOSTS[fj.name]
    assert len(layout.fixed) == 4  # one anchor per base joint


@pytest.mark.parametrize("name", ["flexure_width", "base_flexure_width"])
def test_flexure_as_wide_as_the_links_is_rejected(name):
    with pytest.raises(ValueError, match=name):
        EightBarFlexureParams(**{name: 5e-3})


def test_flexure_longer_than_its_link_segment_is_rejected():
    # the coupler bar A-M-B is 50 mm: two 50 mm flexures centred on A and B leave nothing
    with pytest.raises(ValueError, match="too long for link 'coupler"):
        EightBarFlexureParams(flexure_length=50e-3)


def test_flexure_touching_another_link_over_the_travel_is_rejected():
    # halves 90.4 mm apart with 90 mm ground spacing put the inner pivots C_L, C_R 0.4 mm
    # apart: the rockers (5 mm bars) swing into the other side's base flexure over the travel
    rigid = replace(EightBarParams(), travel=33.1e-3, module_spacing=90.4e-3)
    with pytest.raises(ValueError, match=r"flexure_C_. touches link 'rocker_."):
        EightBarFlexureParams(rigid=rigid)


def test_default_design_is_clear_over_its_travel(params):
    assert flexure_contacts(params) == []


@pytest.mark.parametrize("bad", [0.0, -1e-3, float("nan")])
def test_non_positive_sizes_raise_naming_the_parameter(bad):
    with pytest.raises(ValueError, match="thickness"):
        EightBarFlexureParams(thickness=bad)


def test_unknown_material_raises():
    with pytest.raises(ValueError, match="unobtainium"):
        EightBarFlexureParams(material="unobtainium")


def test_scaled_design_scales_every_length(params):
    micro = params.scaled(1e-3, "silicon_110")
    assert micro.flexure_width == pytest.approx(params.flexure_width * 1e-3)
    assert micro.rigid.crank_length == pytest.approx(params.rigid.crank_length * 1e-3)
    assert micro.material == "silicon_110"
    # joint rotation per unit displacement scales as 1 / length
    r0, r1 = joint_rotation_rates(params), joint_rotation_rates(micro)
    assert r1["A_L"] == pytest.approx(r0["A_L"] * 1e3, rel=1e-6)


def test_prbm_is_the_sum_of_flexure_stiffnesses_times_squared_rates(params):
    prbm = prbm_stiffness(params)
    # mirror symmetry: left and right joints contribute the same
    for j in ("O", "A", "B", "C", "P"):
        assert prbm["joints"][f"{j}_L"] == pytest.approx(prbm["joints"][f"{j}_R"], rel=1e-6)
    E, t, w, L = 68.9e9, params.thickness, params.flexure_width, params.flexure_length
    assert flexure_rotational_stiffness(params, "A_L") == pytest.approx(E * t * w ** 3 / 12 / L)
    assert prbm["k_x"] == pytest.approx(sum(prbm["joints"].values()))


def test_mesh_has_groups_and_three_elements_across_the_thinnest_flexure(params):
    params = replace(params, root_fillet_radius=0.0)  # sharp roots: the flexure is a rectangle
    mesh, sizes = mesh_eightbar_flexure(params, size_factor=2.0)
    assert {"fixed", "end_effector"} <= set(mesh.boundaries)
    assert {f"flexure_{j}" for j in HOSTS} <= set(mesh.subdomains)
    assert {"crank_L", "rocker_R", "coupler_L", "end_effector_link"} <= set(mesh.subdomains)
    thinnest = min(params.flexure_width, params.base_flexure_width)
    assert sizes["flexure_size"] <= thinnest / 3 * (1 + 1e-9)
    # the flexure subdomain's area is L * w (structured grid of the rectangle)
    m = mesh.mesh
    el = mesh.subdomains["flexure_A_L"]
    p = m.p[:, m.t[:, el]]
    area = 0.5 * np.abs((p[0, 1] - p[0, 0]) * (p[1, 2] - p[1, 0]) - (p[0, 2] - p[0, 0]) * (p[1, 1] - p[1, 0]))
    assert area.sum() == pytest.approx(params.flexure_length * params.flexure_width, rel=1e-9)
    # every element's vertices across the flexure: at least 3 element layers
    ys = np.unique(np.round(m.p[1, np.unique(m.t[:, el])], 12))
    assert len(ys) >= 4


def test_travel_larger_than_the_ground_spacing_is_rejected():
    with pytest.raises(ValueError, match="travel"):
        EightBarFlexureParams(rigid=replace(EightBarParams(), travel=0.2))


# -- root fillets ------------------------------------------------------------------------------

def _subdomain_area(mesh, name):
    m = mesh.mesh
    p = m.p[:, m.t[:3, mesh.subdomains[name]]]
    return 0.5 * np.abs((p[0, 1] - p[0, 0]) * (p[1, 2] - p[1, 0])
                        - (p[0, 2] - p[0, 0]) * (p[1, 1] - p[1, 0])).sum()


def test_sharp_root_mesh_is_the_rectangle_and_the_default_keyword_changes_nothing():
    from flexfem.geometry.flexure_drawing import mesh_layout
    sharp = EightBarFlexureParams(root_fillet_radius=0.0)
    layout = eightbar_layout(sharp)
    m0, s0 = mesh_layout(layout, n_across=3, aspect=8.0, coarse=5e-3)
    m1, s1 = mesh_layout(layout, n_across=3, aspect=8.0, coarse=5e-3, root_fillet_radius=0.0)
    assert np.array_equal(m0.mesh.p, m1.mesh.p) and np.array_equal(m0.mesh.t, m1.mesh.t)
    assert s0 == s1 and "root_size" not in s0
    for j in ("A_L", "O_R"):  # straight-sided: the mesh area is exactly L w (round-off only)
        L, w = sharp.flexure_size(j)
        assert _subdomain_area(m0, f"flexure_{j}") == pytest.approx(L * w, rel=1e-9)


def test_each_root_fillet_adds_r2_one_minus_pi_over_4():
    r = 0.3e-3
    fillet_area = r ** 2 * (1.0 - np.pi / 4.0)  # one quarter-circle fillet in a right angle
    p = EightBarFlexureParams(root_fillet_radius=r)
    mesh, sizes = mesh_eightbar_flexure(p, size_factor=2.0)
    h = sizes["root_size"]
    assert h <= r / 3 * (1 + 1e-12)
    for j in ("A_L", "O_R", "P_L"):
        L, w = p.flexure_size(j)
        exact = L * w + 4 * fillet_area
        # the mesh's straight chords cut the arcs: each chord of angle theta = h / r adds the
        # circular segment r^2 (theta - sin theta) / 2 ~ h^3 / (12 r); (pi / 2) r / h chords per
        # arc, 4 arcs: at most pi h^2 / 6 more than the exact area, never less
        excess = _subdomain_area(mesh, f"flexure_{j}") - exact
        assert 0 <= excess <= np.pi * h ** 2 / 6 * 1.05
        assert excess < 0.1 * 4 * fillet_area


@pytest.mark.parametrize("bad", [-1e-4, float("nan"), 2.4e-3, 5.7e-3])
def test_bad_root_fillet_radius_is_rejected(bad):
    # 2.4 mm > (W - w) / 2 = 2.35 mm (the step to the link); 5.7 mm >= L / 2 - w for the
    # 12 mm base flexures (no straight middle left)
    with pytest.raises(ValueError, match="root_fillet_radius"):
        EightBarFlexureParams(root_fillet_radius=bad)


def test_scaled_design_scales_the_fillet(params):
    assert params.scaled(1e-3).root_fillet_radius == pytest.approx(params.root_fillet_radius * 1e-3)


def test_prbm_flexure_loads_balance_the_drive_by_virtual_work(params):
    # the linear PRBM's equilibrium (21 equations) must give the drive force the energy gives,
    # F = k_x s, to round-off; the A flexures lie across the cranks, so the crank's axial force
    # shears them and their root moment exceeds the spring moment
    from flexfem.geometry.eightbar.flexure import prbm_flexure_loads
    s = params.rigid.travel / 2
    loads = prbm_flexure_loads(params, s)
    assert loads["drive_force_n"] == pytest.approx(prbm_stiffness(params)["k_x"] * s, rel=1e-8)
    a = loads["joints"]["A_L"]
    assert a["end_moment_nm"] == pytest.approx(abs(a["moment_nm"]) + abs(a["shear_n"]) * 10e-3)
    assert abs(a["shear_n"]) > abs(a["axial_n"])
