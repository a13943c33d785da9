"""[points]: named points of bodies, observed as their bodies move rigidly, in the continuum
and the beam model alike; bad entries refused naming the file, the line and the point."""
import json
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation
from flexfem.geometry.user_model import load_spec
from flexfem.studies.cli import main
from flexfem.studies.user_model.observe import carried

EXAMPLES = Path(__file__).parents[3] / "examples"
POINTS = ('[points]\ntip = { body = "stage", at = [0.0, "L + 0.008"] }\n'
          'far = { body = "stage", at = [0.1, "L + 0.004"] }\n\n'
          '[outputs]\nfar_y = "far.uy"\n\n')


def _guide(tmp_path, points=POINTS) -> Path:
    text = (EXAMPLES / "bodies" / "guide.toml").read_text()
    assert "[analysis]" in text
    path = tmp_path / "guide.toml"
    path.write_text(text.replace("[analysis]", points + "[analysis]"))
    return path


@pytest.mark.parametrize("model", ["continuum", "beam"])
def test_points_ride_on_their_body(tmp_path, capsys, model):
    assert main(["analyze", str(_guide(tmp_path)), "--model", model, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    tip, far, stage = (out["observations"][g] for g in ("tip", "far", "stage"))
    rz = stage["rz"]
    assert tip["rz"] == far["rz"] == rz
    # a rigid body's points differ by the rotation times their offset (0.1, -0.004) m
    assert far["uy"] - tip["uy"] == pytest.approx(rz * 0.1, rel=1e-9)
    assert far["ux"] - tip["ux"] == pytest.approx(-rz * -0.004, rel=1e-9)
    assert out["outputs"]["far_y"] == far["uy"]


def test_a_point_carried_by_a_finite_rotation_is_where_the_body_puts_it():
    t, c, p = 0.3, np.array([1.0, 2.0]), np.array([1.5, 2.5])
    R = np.array([[math.cos(t), -math.sin(t)], [math.sin(t), math.cos(t)]])
    shift = np.array([0.1, -0.2])
    moved = lambda x: R @ x + shift - x  # noqa: E731 - the rigid motion's displacement
    at_c = {"ux": moved(c)[0], "uy": moved(c)[1], "rz": t}
    assert [carried(at_c, c, p, large=True)[k] for k in ("ux", "uy")] == pytest.approx(moved(p))
    w = np.array([0.1, -0.2, 0.3])
    R3, c3, p3 = Rotation.from_rotvec(w), np.zeros(3), np.array([0.2, 0.1, -0.3])
    at_c3 = {"ux": 0.0, "uy": 0.0, "uz": 0.0, "rx": w[0], "ry": w[1], "rz": w[2]}
    got = carried(at_c3, c3, p3, large=True)
    assert [got[k] for k in ("ux", "uy", "uz")] == pytest.approx(R3.apply(p3) - p3)
    linear = carried(at_c3, c3, p3)
    assert [linear[k] for k in ("ux", "uy", "uz")] == pytest.approx(np.cross(w, p3))


@pytest.mark.parametrize("entry, message", [
    ('stage = { body = "stage", at = [0, 0] }', "'stage' is already a group"),
    ('p = { body = "stag", at = [0, 0] }', "body 'stag' is not a body; bodies: ground, stage"),
    ('p = { body = "stage", at = [0, 0, 0] }', r"at = \[0, 0, 0\] must be \[x, y\]"),
    ('p = { body = "stage" }', "write { body"),
])
def test_bad_points_are_refused_naming_the_line(tmp_path, entry, message):
    path = _guide(tmp_path, f"[points]\n{entry}\n\n")
    with pytest.raises(ValueError, match=rf"guide.toml line \d+: \[points\] .*{message}"):
        load_spec(path)


def test_a_geometry_file_has_no_points(tmp_path):
    folder = EXAMPLES / "parallel_guide"
    for f in folder.iterdir():
        (tmp_path / f.name).write_text(f.read_text())
    model = tmp_path / "guide.toml"
    model.write_text(model.read_text() + '\n[points]\np = { body = "stage", at = [0, 0] }\n')
    with pytest.raises(ValueError, match=r"\[points\] are points of bodies"):
        load_spec(model)


def test_points_take_units_like_every_other_value(tmp_path):
    """``at = ["100 mm", "L + 4 mm"]`` reads as its SI twin; a unit that is not a length is
    refused naming the point."""
    si = load_spec(_guide(tmp_path)).points
    units = POINTS.replace('at = [0.1, "L + 0.004"]', 'at = ["100 mm", "L + 4 mm"]')
    assert units != POINTS
    (tmp_path / "u").mkdir()
    with_units = load_spec(_guide(tmp_path / "u", units)).points
    assert with_units["far"][0] == si["far"][0]
    assert with_units["far"][1] == pytest.approx(si["far"][1], rel=1e-12)
    (tmp_path / "bad").mkdir()
    bad = _guide(tmp_path / "bad", POINTS.replace('at = [0.1,', 'at = ["0.1 kg",'))
    with pytest.raises(ValueError, match=r"\[points\] far at: '0.1 kg' is .*this value is a "
                                         "length"):
        load_spec(bad)
