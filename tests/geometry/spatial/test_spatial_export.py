"""``flexfem export FILE.toml OUT.step`` on a spatial file (geometry/spatial/export.py): the
fused solid through the one STEP writer (geometry/outline_files.py), re-imported by
OpenCASCADE as one solid whose volume is the description's (geometry/spatial/mass.py:
the bodies' and the flexures' free spans), in millimetres as the command says."""
import json
from pathlib import Path

import numpy as np
import pytest

from flexfem.fem import gmsh_session
from flexfem.geometry.spatial.mass import mechanism_volume
from flexfem.geometry.spatial.tables import load_spatial
from flexfem.studies.cli import main

EXAMPLES = Path(__file__).resolve().parents[3] / "examples" / "spatial"


def _reimported(path) -> tuple:
    """(number of solids, their volume (m^3), bounding box size (3,) m) of a STEP file."""
    with gmsh_session("reimport") as gmsh:
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")
        gmsh.model.occ.importShapes(str(path))
        gmsh.model.occ.synchronize()
        solids = gmsh.model.getEntities(3)
        volume = sum(gmsh.model.occ.getMass(*dt) for dt in solids)
        box = gmsh.model.getBoundingBox(-1, -1)
        return len(solids), volume, [box[3] - box[0], box[4] - box[1], box[5] - box[2]]


@pytest.mark.parametrize("name", ["wire_guide", "leaf_guide", "cross_pivot"])
def test_the_step_is_one_solid_of_the_descriptions_volume(tmp_path, capsys, name):
    out = tmp_path / f"{name}.step"
    assert main(["export", str(EXAMPLES / f"{name}.toml"), str(out), "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["format"] == "step" and result["units"] == "mm" and result["dim"] == 3
    assert "MILLI" in out.read_text()
    mechanism, _, _ = load_spatial(EXAMPLES / f"{name}.toml")
    solids, volume, size = _reimported(out)
    assert solids == 1
    assert volume == pytest.approx(mechanism_volume(mechanism), rel=1e-6)
    lows, highs = zip(*(b.extent() for b in mechanism.bodies))
    assert size == pytest.approx(np.max(highs, axis=0) - np.min(lows, axis=0), abs=1e-6)


def test_a_set_changes_the_solid_and_a_dxf_is_refused(tmp_path, capsys):
    out = tmp_path / "thick.step"
    assert main(["export", str(EXAMPLES / "wire_guide.toml"), str(out), "--set",
                 "d=0.0012"]) == 0
    assert capsys.readouterr().out.rstrip().endswith("(STEP, mm)")
    mechanism, _, _ = load_spatial(EXAMPLES / "wire_guide.toml", {"d": 0.0012})
    assert _reimported(out)[1] == pytest.approx(mechanism_volume(mechanism), rel=1e-6)
    assert main(["export", str(EXAMPLES / "wire_guide.toml"), str(tmp_path / "w.dxf")]) == 2
    err = capsys.readouterr().err
    assert "use .step" in err and len(err.strip().splitlines()) == 1
