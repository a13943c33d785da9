"""The eight-bar suspension as a 3-D solid: the 2-D drawing extruded through its thickness,
with the 2-D model's groups as volumes and faces."""
import numpy as np
import pytest

from flexfem.geometry.eightbar.estimate import estimate_mesh
from flexfem.geometry.eightbar.flexure import (
    EightBarFlexureParams,
    eightbar_layout,
    mesh_eightbar_flexure,
    solid_mesh_options,
)

SIZE = 3.0  # a coarse mesh: 2 layers, flexure elements 12 x their size across


@pytest.fixture(scope="module")
def params():
    return EightBarFlexureParams()


@pytest.fixture(scope="module")
def solid(params):
    return mesh_eightbar_flexure(params, size_factor=SIZE, dim=3)


@pytest.fixture(scope="module")
def plane(params):
    return mesh_eightbar_flexure(params, size_factor=SIZE)


def _measure(mesh, elements) -> float:
    """Area (triangles) or volume (tetrahedra) of ``elements``, m^2 or m^3."""
    p, t = mesh.p, mesh.t[:, elements]
    edges = np.stack([p[:, t[k]] - p[:, t[0]] for k in range(1, t.shape[0])], axis=0)
    if t.shape[0] == 3:
        return float(np.abs(edges[0, 0] * edges[1, 1] - edges[0, 1] * edges[1, 0]).sum() / 2)
    volume = np.einsum("ij,ij->j", edges[0], np.cross(edges[1].T, edges[2].T).T)
    return float(np.abs(volume).sum() / 6)


def _face_area(mesh, facets) -> float:
    p = mesh.p[:, mesh.facets[:, facets]]
    normal = np.cross((p[:, 1] - p[:, 0]).T, (p[:, 2] - p[:, 0]).T)
    return float(np.linalg.norm(normal, axis=1).sum() / 2)


def test_every_subdomain_is_its_planar_area_times_the_thickness(params, solid, plane):
    """Each link, flexure and the union groups: volume = 2-D area x t (to 1e-3: the fillet
    arcs' chords differ between the two meshes), and the part spans -t/2 <= z <= t/2."""
    mesh3, _ = solid
    mesh2, _ = plane
    assert set(mesh3.subdomains) == set(mesh2.subdomains)
    assert len(mesh3.subdomains) == 22  # 10 flexures, 8 links (ground too), 4 unions
    for name, elements in mesh2.subdomains.items():
        area = _measure(mesh2.mesh, elements)
        assert _measure(mesh3.mesh, mesh3.subdomains[name]) == pytest.approx(
            area * params.thickness, rel=1e-3), name
    z = mesh3.mesh.p[2]
    assert z.min() == pytest.approx(-params.thickness / 2, abs=1e-12)
    assert z.max() == pytest.approx(params.thickness / 2, abs=1e-12)


def test_boundaries_are_the_swept_edges(params, solid):
    """"fixed": the four anchors' far faces (W x t each); "end_effector": the bottom face
    of the end-effector bar (its length x t)."""
    mesh, _ = solid
    layout = eightbar_layout(params)
    W, t = params.link_width, params.thickness
    assert set(mesh.boundaries) == {"fixed", "end_effector"}
    assert _face_area(mesh.mesh, mesh.boundaries["fixed"]) == pytest.approx(4 * W * t, rel=1e-9)
    a, b = layout.edges["end_effector"]
    assert _face_area(mesh.mesh, mesh.boundaries["end_effector"]) == pytest.approx(
        np.hypot(b[0] - a[0], b[1] - a[1]) * t, rel=1e-9)


def test_flexures_have_their_elements_across_and_layers_through(params, solid):
    """The structured middle of every flexure: n_across elements across its width (the
    vertices on n_across + 1 lines), ``layers`` layers of tetrahedra through t."""
    mesh, sizes = solid
    options = solid_mesh_options(params, size_factor=SIZE)
    layers = options["layers"]
    assert sizes["layer_size"] == pytest.approx(params.thickness / layers)
    assert np.unique(np.round(mesh.mesh.p[2] / sizes["layer_size"], 9)).size == layers + 1
    for fj in eightbar_layout(params).joints:
        t = mesh.mesh.t[:, mesh.subdomains[f"flexure_{fj.name}"]]
        p = mesh.mesh.p[:2, np.unique(t)] - np.asarray(fj.position)[:, None]
        d = np.asarray(fj.direction)
        along, across = d @ p, np.array([-d[1], d[0]]) @ p
        middle = np.abs(along) < fj.length / 4  # away from the fillets' unstructured zones
        lines = np.unique(np.round(across[middle] / (fj.width / options["n_across"]), 6))
        assert lines.size == options["n_across"] + 1, fj.name


def test_estimate_is_within_a_factor_1_5_of_the_mesh(params, solid):
    mesh, _ = solid
    dofs = 3 * (mesh.mesh.p.shape[1] + mesh.mesh.edges.shape[1])  # quadratic tetrahedra
    estimate = estimate_mesh(params, size_factor=SIZE, dim=3)["dofs"]
    assert 1 / 1.5 <= estimate / dofs <= 1.5


@pytest.mark.parametrize("options, match", [({"dim": 4}, "dim = 4"),
                                            ({"dim": 3, "layers": 0}, "layers = 0"),
                                            ({"dim": 3, "layers": 2.5}, "layers = 2.5")])
def test_bad_solid_options_are_refused(params, options, match):
    with pytest.raises(ValueError, match=match):
        mesh_eightbar_flexure(params, size_factor=SIZE, **options)
