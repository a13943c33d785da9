"""A body's pose (geometry/spatial/description.py Pose: a rotation about an axis through a
point): its parts turned alike in the description's checks, its mass properties and the
continuum's OpenCASCADE solid; a posed file that is the leaf guide gives its numbers; a
bad pose is refused at its line."""
from pathlib import Path
import re

import numpy as np
import pytest

from flexfem.fem import gmsh_session
from flexfem.geometry.spatial.continuum import body_shapes
from flexfem.geometry.spatial.description import Cylinder, Pose, SolidBody
from flexfem.geometry.spatial.export import solid_volume
from flexfem.geometry.spatial.mass import mass_properties
from flexfem.geometry.spatial.tables import load_spatial
from flexfem.geometry.user_model import load_spec
from flexfem.studies.user_model.analysis import analyze_model

EXAMPLES = Path(__file__).resolve().parents[3] / "examples" / "spatial"
LEAF_GUIDE = (EXAMPLES / "leaf_guide.toml").read_text()
TURNED = Pose((1.0, 2.0, 0.5), 0.7, (0.01, -0.02, 0.005))
PARTS = dict(boxes=(((0.0, 0.0, 0.0), (0.03, 0.01, 0.02)),),
             cylinders=(Cylinder((0.03, 0.005, 0.0), (0.05, 0.005, 0.0), 0.008),))


def test_a_pose_turns_points_and_back():
    p = np.array([[0.01, 0.02, 0.03], [-0.04, 0.0, 0.01]])
    assert TURNED.to_parts(TURNED.to_world(p)) == pytest.approx(p)
    R = TURNED.matrix
    assert R @ R.T == pytest.approx(np.eye(3)) and np.linalg.det(R) == pytest.approx(1.0)
    assert R @ np.array(TURNED.axis) == pytest.approx(np.array(TURNED.axis))  # the axis stays
    quarter = Pose((0, 0, 1), np.pi / 2, (0, 0, 0)).to_world([1.0, 0.0, 0.0])
    assert quarter == pytest.approx([0.0, 1.0, 0.0])                          # right-handed
    body = SolidBody("b", **PARTS, pose=TURNED)
    inside = TURNED.to_world([0.015, 0.005, 0.01])
    outside = TURNED.to_world([0.015, 0.005, -0.003])                         # under the box
    assert body.contains(inside, 1e-12) and not body.contains(outside, 1e-12)
    assert SolidBody("b", **PARTS).contains(TURNED.to_parts(outside), 1e-12) is False
    lo, hi = body.extent()
    assert np.all(lo <= inside) and np.all(inside <= hi)


def test_the_solid_and_the_mass_properties_turn_alike():
    """OpenCASCADE's centroid and inertia of the drawn, turned body against mass.py's."""
    body = SolidBody("b", **PARTS, pose=TURNED)
    props = mass_properties(body)
    with gmsh_session("pose") as gmsh:
        (dim, tag), = body_shapes(gmsh.model.occ, body)
        gmsh.model.occ.synchronize()
        volume = gmsh.model.occ.getMass(dim, tag)
        centroid = np.array(gmsh.model.occ.getCenterOfMass(dim, tag))
        inertia = np.array(gmsh.model.occ.getMatrixOfInertia(dim, tag)).reshape(3, 3)
    assert volume == pytest.approx(props.volume, rel=1e-6)   # the parts do not overlap
    assert centroid == pytest.approx(props.centroid, abs=1e-9)
    assert inertia == pytest.approx(props.inertia(1.0), rel=1e-5, abs=1e-15)


POSED = LEAF_GUIDE.replace(
    'box = [["-w / 2 - 2 mm", "-d / 2 - 3 mm", "L"], ["w / 2 + 2 mm", "d / 2 + 3 mm", "L + 5 mm"]]',
    'box = [["-d / 2 - 3 mm", "-w / 2 - 2 mm", "L"], ["d / 2 + 3 mm", "w / 2 + 2 mm", "L + 5 mm"]]\n'
    'pose = {axis = [0, 0, 1], angle = "90 deg"}')


def test_the_leaf_guide_with_its_stage_written_turned_is_the_leaf_guide(tmp_path):
    assert POSED != LEAF_GUIDE
    path = tmp_path / "posed.toml"
    path.write_text(POSED)
    out = {name: analyze_model(load_spec(p, {"analysis.compliance": "stage"}), model="beam")
           for name, p in (("posed", path), ("plain", EXAMPLES / "leaf_guide.toml"))}
    assert out["posed"]["stiffness"]["stage"]["y"] == pytest.approx(
        out["plain"]["stiffness"]["stage"]["y"], rel=1e-9)
    assert np.allclose(out["posed"]["compliance"]["matrix"], out["plain"]["compliance"]["matrix"],
                       rtol=1e-9)
    assert out["posed"]["frequencies_hz"] == pytest.approx(out["plain"]["frequencies_hz"], rel=1e-9)
    solids = [solid_volume(load_spatial(p)[0]) for p in (path, EXAMPLES / "leaf_guide.toml")]
    assert solids[0] == pytest.approx(solids[1], rel=1e-9)     # the continuum's fused solid


@pytest.mark.parametrize("pose, expected", [
    ('{axis = [0, 0, 1]}', "missing angle"),
    ('{axis = [0, 0, 1], angle = 0.1, turn = 2}', "unknown turn"),
    ('{axis = [0, 0, 0], angle = 0.1}', "must be a direction"),
    ('"90 deg"', "must be an inline table"),
])
def test_a_bad_pose_is_refused_at_its_line(tmp_path, pose, expected):
    path = tmp_path / "bad.toml"
    path.write_text(POSED.replace('pose = {axis = [0, 0, 1], angle = "90 deg"}', f"pose = {pose}"))
    with pytest.raises(ValueError) as info:
        load_spatial(path)
    message = str(info.value)
    assert re.match(rf"{re.escape(str(path))}:? line \d+", message) and expected in message
    assert "'stage' pose" in message
