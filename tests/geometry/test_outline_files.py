"""The one DXF and STEP writer (geometry/outline_files.py): the guide example written by
``flexfem export`` reads back (ezdxf, OpenCASCADE) with its known dimensions in the unit the
command states; arcs stay arcs; the 3-D solid has the depth; an elliptical notch's arcs lie
on its ellipse."""
import json
import math
from pathlib import Path

import numpy as np
import pytest

from flexfem.fem import gmsh_session
from flexfem.geometry.mechanism.export import area, outline_loops, write_step
from flexfem.geometry.outline_files import (UNIT, arc_midpoint, polyline_area, write_dxf)
from flexfem.geometry.user_model import load_spec
from flexfem.studies.cli import main

GUIDE = Path(__file__).parents[2] / "examples" / "bodies" / "guide.toml"
# the guide's outline: the ground's and stage's boxes are d + 10 mm wide; from the ground's
# bottom (-5 mm) to the stage's top (L + 8 mm); the depth is [section] thickness
WIDTH, HEIGHT, DEPTH = 0.03, 0.053, 0.01  # m
PER_UNIT = {"mm": 1e-3, "m": 1.0}  # m per stated unit


def _export(tmp_path, capsys, name, *extra) -> dict:
    assert main(["export", str(GUIDE), str(tmp_path / name), "--json", *extra]) == 0
    return json.loads(capsys.readouterr().out)


def _step_box(path, target_unit: str) -> np.ndarray:
    """(dx, dy, dz) of a STEP file's bounding box read by OpenCASCADE in ``target_unit``,
    without gmsh's 1e-7 padding, and the number of volumes."""
    with gmsh_session() as gmsh:
        gmsh.option.setString("Geometry.OCCTargetUnit", target_unit.upper())
        gmsh.model.occ.importShapes(str(path))
        gmsh.model.occ.synchronize()
        x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(-1, -1)
        volumes = len(gmsh.model.getEntities(3))
    return np.array([x1 - x0, y1 - y0, z1 - z0]) - 2e-7, volumes


def test_step_and_dxf_hold_the_guide_in_the_unit_the_command_states(tmp_path, capsys):
    ezdxf = pytest.importorskip("ezdxf")
    step = _export(tmp_path, capsys, "guide.step")
    dxf = _export(tmp_path, capsys, "guide.dxf")
    assert step["units"] == dxf["units"] == UNIT == "mm"
    assert main(["export", str(GUIDE), str(tmp_path / "again.step")]) == 0
    assert capsys.readouterr().out.rstrip().endswith("(STEP, mm)")
    unit = PER_UNIT[step["units"]]
    text = (tmp_path / "guide.step").read_text()
    assert "SI_UNIT(.MILLI.,.METRE.)" in text.replace(" ", "")  # what the file declares
    (dx, dy, _), _ = _step_box(tmp_path / "guide.step", step["units"])
    assert (dx * unit, dy * unit) == pytest.approx((WIDTH, HEIGHT), rel=1e-6)
    doc = ezdxf.readfile(tmp_path / "guide.dxf")
    assert doc.units == ezdxf.units.MM
    xy = np.array([p[:2] for e in doc.modelspace().query("LWPOLYLINE") for p in e.get_points()])
    span = (xy.max(axis=0) - xy.min(axis=0)) * PER_UNIT[dxf["units"]]
    assert span == pytest.approx((WIDTH, HEIGHT), rel=1e-9)


def test_the_solid_has_the_depth_and_the_faces_area(tmp_path, capsys):
    _export(tmp_path, capsys, "solid.step", "--dim", "3")
    (dx, dy, dz), volumes = _step_box(tmp_path / "solid.step", "M")
    assert volumes == 1
    assert (dx, dy, dz) == pytest.approx((WIDTH, HEIGHT, DEPTH), rel=1e-6)
    with gmsh_session() as gmsh:
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")
        gmsh.model.occ.importShapes(str(tmp_path / "solid.step"))
        gmsh.model.occ.synchronize()
        volume = gmsh.model.occ.getMass(3, gmsh.model.getEntities(3)[0][1])
    assert volume == pytest.approx(area(load_spec(GUIDE).mechanism) * DEPTH, rel=1e-9)


def test_arcs_are_arcs_in_both_files(tmp_path):
    """A disc of radius 1 cm as two half circles (bulge 1): its DXF keeps the bulges, its
    STEP re-imports with the disc's area pi r^2 (an arc, not a chord)."""
    ezdxf = pytest.importorskip("ezdxf")
    r = 0.01
    loop = [(r, 0.0, 1.0), (-r, 0.0, 1.0)]
    assert arc_midpoint((r, 0.0), (-r, 0.0), 1.0) == pytest.approx((0.0, r))
    assert polyline_area(loop) == pytest.approx(math.pi * r ** 2)
    assert write_dxf([loop], tmp_path / "disc.dxf") == 1
    (polyline,) = ezdxf.readfile(tmp_path / "disc.dxf").modelspace().query("LWPOLYLINE")
    assert [b for *_, b in polyline.get_points("xyb")] == [1.0, 1.0]
    from flexfem.geometry.outline_files import write_step as write_faces

    write_faces([[loop]], tmp_path / "disc.step")
    with gmsh_session() as gmsh:
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")
        gmsh.model.occ.importShapes(str(tmp_path / "disc.step"))
        gmsh.model.occ.synchronize()
        (face,) = gmsh.model.getEntities(2)
        assert gmsh.model.occ.getMass(*face) == pytest.approx(math.pi * r ** 2, rel=1e-9)
        assert {gmsh.model.getType(*c) for c in gmsh.model.getEntities(1)} == {"Circle"}


def test_an_elliptical_notch_is_written_close_to_its_ellipse(tmp_path):
    """The ellipse's sides as ELLIPSE_ARCS circular arcs each: the STEP's area within 1e-7
    of OpenCASCADE's own (true ellipses)."""
    mechanism = load_spec(GUIDE.parent / "elliptical_notch.toml").mechanism
    loops = outline_loops(mechanism)
    assert sum(1 for loop in loops for *_, b in loop if b) > 32
    write_step(mechanism, tmp_path / "notch.step")
    with gmsh_session() as gmsh:
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")
        gmsh.model.occ.importShapes(str(tmp_path / "notch.step"))
        gmsh.model.occ.synchronize()
        written = sum(gmsh.model.occ.getMass(*f) for f in gmsh.model.getEntities(2))
    assert written == pytest.approx(area(mechanism), rel=1e-7)


@pytest.mark.parametrize("name", ["out.step", "out.dxf"])
def test_a_folder_that_is_not_there_is_one_line_naming_the_file(tmp_path, capsys, name):
    target = tmp_path / "no_such_folder" / name
    assert main(["export", str(GUIDE), str(target)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("flexfem export: error:") and name in err[0]
