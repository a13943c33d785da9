"""A support of bodies and flexures may hold z: the extruded solid (--dim 3) then cannot
slide out of the plane; in the plane z = 0 is what the plane holds already. The bridge
amplifier, held so, gives the planar R in 3-D, and its beam model still sizes its stroke."""
import json
from pathlib import Path

from flexfem.studies.cli import main

BRIDGE = Path(__file__).parents[3] / "examples" / "bodies" / "bridge.toml"


def _json(capsys, *argv) -> dict:
    assert main(["analyze", str(BRIDGE), *argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_the_bridge_in_3d_gives_the_planar_ratio(capsys):
    planar = _json(capsys)
    solid = _json(capsys, "--dim", "3", "--max-dofs", "150000")
    assert solid["dim"] == 3 and "chosen to fit" in solid["mesh_choice"]
    assert abs(solid["outputs"]["R"] / planar["outputs"]["R"] - 1) < 0.01
    assert solid["stroke_limit_yield"] > 0  # the planar beam model stands in for the root


def test_a_z_support_in_the_plane(tmp_path, capsys):
    text = BRIDGE.read_text()
    assert "z = 0.0" in text
    moved = tmp_path / "bridge.toml"
    moved.write_text(text.replace("z = 0.0", "z = 0.001", 1))
    assert main(["analyze", str(moved)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "z = 0.001: an out-of-plane displacement needs --dim 3" in err
