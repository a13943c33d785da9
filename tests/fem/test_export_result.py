"""Field export: displacement, von Mises and mode shapes read back from VTU and XDMF."""
import meshio
import numpy as np
import pytest
from meshes import beam_2d, beam_3d
from flexfem.fem import (
    Fixed,
    Force,
    Model,
    PlaneStress,
    Solid3D,
    solve_modes,
    solve_static,
)
from flexfem.fem.export import write_result


@pytest.fixture(scope="module")
def solved_2d(steel):
    model = Model(beam_2d(1.0, 0.1, 0.05), steel, PlaneStress(0.01), order=2)
    result = solve_static(model, [Fixed("fixed")], [Force("tip", (0.0, -100.0))])
    return result, solve_modes(model, 4, [Fixed("fixed")])


@pytest.fixture(scope="module")
def solved_3d(steel):
    model = Model(beam_3d(1.0, 0.1, 0.1, 0.08), steel, Solid3D(), order=2)
    return solve_modes(model, 3, [Fixed("fixed")])


@pytest.mark.parametrize("suffix", [".vtu", ".xdmf"])
def test_static_fields_read_back_at_the_vertices(solved_2d, suffix, tmp_path):
    result, _ = solved_2d
    m = meshio.read(write_result(result, tmp_path / f"u{suffix}"))
    n = result.model.mesh.mesh.p.shape[1]
    # first-order mesh: the vertices only, with the P2 field sampled there
    assert len(m.points) == n and m.cells[0].type == "triangle"
    assert np.allclose(m.point_data["displacement"][:, :2], result.displacement, rtol=1e-12, atol=0)
    assert np.all(m.point_data["displacement"][:, 2] == 0.0)
    assert np.allclose(m.point_data["von_mises"], result.von_mises_nodal)
    assert np.allclose(m.cell_data["von_mises_element_max"][0], result.von_mises_element_max)


@pytest.mark.parametrize("suffix", [".vtu", ".xdmf"])
def test_every_mode_shape_is_written(solved_2d, solved_3d, suffix, tmp_path):
    for modes in (solved_2d[1], solved_3d):
        m = meshio.read(write_result(modes, tmp_path / f"modes{suffix}"))
        names = [k for k in m.point_data if k.startswith("mode_")]
        assert len(names) == len(modes.frequencies_hz)
        for k, f in enumerate(modes.frequencies_hz):
            name = f"mode_{k + 1} ("
            (field,) = [n for n in names if n.startswith(name)]
            # the frequency in the name, printed to 6 significant digits
            assert float(field[len(name):].split()[0]) == pytest.approx(f, rel=1e-5)
            shape = m.point_data[field][:, :modes.model.dim]
            assert np.allclose(shape, modes.vertex_shape(k), rtol=1e-12, atol=0)


def test_write_result_rejects_other_objects_and_formats(solved_2d, tmp_path):
    with pytest.raises(ValueError, match="StaticResult, NonlinearResult or Modes"):
        write_result(solved_2d[0].model, tmp_path / "x.vtu")
    with pytest.raises(ValueError, match=r"'\.msh'.*\.vtu, \.xdmf"):
        write_result(solved_2d[0], tmp_path / "x.msh")
