"""Bodies and flexures: bad descriptions are refused with the model file, the line and the body
or flexure named; the outline's geometry (roots, footprints, the outline centre) checked by
hand; the DXF and STEP exports read back with the same area and the fillets as arcs."""
import math
from pathlib import Path

import numpy as np
import pytest
from flexfem.geometry.mechanism import Body, Leaf, Mechanism, Notch
from flexfem.geometry.mechanism.beams import profile
from flexfem.geometry.mechanism.export import area, export
from flexfem.geometry.outline_files import polyline_area
from flexfem.geometry.user_model import load_spec
from flexfem.studies.cli import main

GUIDE = Path(__file__).parents[3] / "examples" / "bodies" / "guide.toml"


def _edited(tmp_path, old: str, new: str, count: int = 1) -> Path:
    text = GUIDE.read_text()
    assert text.count(old) >= count, old
    path = tmp_path / "guide.toml"
    path.write_text(text.replace(old, new, count))
    return path


def _line(path: Path, text: str, nth: int = 0) -> int:
    lines = [i + 1 for i, line in enumerate(path.read_text().splitlines()) if text in line]
    return lines[nth]


@pytest.mark.parametrize("old, new, message, where", [
    ('to = ["-d / 2", "L"]', 'to = ["-d / 2", "L + 0.02"]',
     "to = .* is not inside body 'stage'", ("[[flexure]]", 0)),
    ('from = ["d / 2", 0.0]\nto = ["d / 2", "L"]',
     'from = ["-d / 2 + 0.0005", 0.0]\nto = ["-d / 2 + 0.0005", "L"]',
     "overlaps flexure 1", ("[[flexure]]", 1)),
    ('from = ["d / 2", 0.0]\nto = ["d / 2", "L"]',
     'from = ["-d / 2 + 0.001", 0.0]\nto = ["-d / 2 + 0.001", "L"]',
     r"touches flexure 1 .* \(no gap between them: the continuum would fuse", ("[[flexure]]", 1)),
    ('box = [["-d / 2 - 0.005", -0.005], ["d / 2 + 0.005", 0.0]]',
     'box = [["-d / 2 - 0.005", -0.005, 0.0], ["d / 2 + 0.005", 0.0]]',
     "'ground' box: .* must be two opposite corners", ('-0.005, 0.0]', 0)),
    ('[[supports]]\ngroup = "ground"', '[[supports]]\ngroup = "groun"',
     "group = 'groun' is no body .*; bodies: ground, stage", ('group = "groun"', 0)),
    ('thickness = "t"', 'thickness = 0.05', "thicker .* than long", ("[[flexure]]", 0)),
    ('between = ["ground", "stage"]', 'between = ["ground", "stag"]',
     "no body is named 'stag'", ("[[flexure]]", 0)),
    ('[[supports]]\ngroup = "ground"', '[[supports]]\ngroup = "stage"\n[[body]]\nname = "loose"\n'
     'box = [[0.1, 0.1], [0.11, 0.11]]', "body 'loose' is joined to nothing", ("name = \"loose\"", 0)),
])
def test_bad_descriptions_name_file_line_and_part(tmp_path, old, new, message, where):
    path = _edited(tmp_path, old, new)
    with pytest.raises(ValueError, match=message) as error:
        load_spec(path)
    text, nth = where
    assert f"{path} line {_line(path, text, nth)}" in str(error.value)


def test_a_mechanism_with_no_support_or_a_floating_body(tmp_path):
    path = _edited(tmp_path, '[[supports]]\ngroup = "ground"', "")
    with pytest.raises(ValueError, match="no support"):
        load_spec(path)
    bodies = (Body("ground", (((0, 0), (1, 1)),)), Body("a", (((0, 2), (1, 3)),)),
              Body("b", (((3, 0), (4, 1)),)), Body("c", (((3, 2), (4, 3)),)))
    flexures = (Leaf(("ground", "a"), (0.5, 1), (0.5, 2), 0.05),
                Leaf(("b", "c"), (3.5, 1), (3.5, 2), 0.05))
    with pytest.raises(ValueError, match="body 'b' is not connected .* held body"):
        Mechanism(bodies, flexures, 0.01).check({"ground"})


def test_crossing_leaves_are_a_joint_not_an_overlap():
    bodies = (Body("ground", (((-1, -1), (1, 0)),)), Body("stage", (((-1, 1), (1, 2)),)))
    leaves = (Leaf(("ground", "stage"), (-0.5, 0), (0.5, 1), 0.02),
              Leaf(("ground", "stage"), (0.5, 0), (-0.5, 1), 0.02))
    Mechanism(bodies, leaves, 0.01).check({"ground"})


def test_notch_span_must_be_two_radii():
    bodies = (Body("ground", (((-1, -1), (1, 0)),)), Body("lever", (((-1, 0.3), (1, 1)),)))
    with pytest.raises(ValueError, match="2 radius"):
        Mechanism(bodies, (Notch(("ground", "lever"), (0, 0), (0, 0.3), 0.01, 0.1),),
                  0.01).check({"ground"})


def test_outline_centre_and_footprint_by_hand():
    """A 2 x 1 box with a leaf of width 0.2 leaving its top face at x = 0.5: the outline is the
    perimeter (6, centroid (1, 0.5)) less the leaf's footprint (0.2 long, centred at (0.5, 1)):
    its centroid is (6 (1, 0.5) - 0.2 (0.5, 1)) / 5.8."""
    bodies = (Body("base", (((0, 0), (2, 1)),)), Body("top", (((0, 3), (2, 4)),)))
    leaf = Leaf(("base", "top"), (0.5, 1), (0.5, 3), 0.2)
    m = Mechanism(bodies, (leaf,), 0.01)
    (_, p0, p1), _ = m.footprint(0)
    assert sorted([p0[0], p1[0]]) == pytest.approx([0.4, 0.6]) and p0[1] == pytest.approx(1)
    assert m.outline_centre("base") == pytest.approx([(6 - 0.1) / 5.8, (3 - 0.2) / 5.8])


def test_leaf_and_notch_profiles_by_hand():
    leaf = Leaf(("a", "b"), (0, 0), (0, 1), 0.001, fillet=0.002)
    t = profile(leaf, 0.04)
    assert t(0.0) == pytest.approx(0.005) and t(0.02) == pytest.approx(0.001)
    assert t(0.001) == pytest.approx(0.001 + 2 * (0.002 - math.sqrt(0.002**2 - 0.001**2)),
                                     rel=1e-3)
    notch = Notch(("a", "b"), (0, 0), (0, 1), 0.0005, 0.005)
    t = profile(notch, 0.01)
    assert t(0.005) == pytest.approx(0.0005) and t(0.0) == pytest.approx(0.0105)


def test_dxf_has_true_arcs_in_mm_and_the_area_of_the_model(tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    path = _edited(tmp_path, 'thickness = "t"', 'thickness = "t"\nfillet = 0.0005', 2)
    mechanism = load_spec(path).mechanism
    export(mechanism, tmp_path / "guide.dxf")
    doc = ezdxf.readfile(tmp_path / "guide.dxf")
    assert doc.units == ezdxf.units.MM
    (x0, y0, _), (x1, y1, _) = doc.header["$EXTMIN"], doc.header["$EXTMAX"]
    assert (x0, y0, x1, y1) == pytest.approx((-15.0, -5.0, 15.0, 48.0))  # mm, "zoom extents"
    loops = [list(p.get_points("xyb")) for p in doc.modelspace().query("LWPOLYLINE")]
    assert all(p.closed for p in doc.modelspace().query("LWPOLYLINE"))
    assert sum(1 for loop in loops for x, y, b in loop if b) == 8  # two leaves, four fillets
    areas = sorted((abs(polyline_area(loop)) for loop in loops), reverse=True)
    assert (areas[0] - sum(areas[1:])) * 1e-6 == pytest.approx(area(mechanism), rel=1e-6)
    # a fillet of radius r adds (1 - pi / 4) r^2 at each of the eight corners
    square = area(load_spec(GUIDE).mechanism)
    assert area(mechanism) - square == pytest.approx(8 * (1 - math.pi / 4) * 0.0005**2, rel=1e-6)


def test_step_reimports_with_the_same_area(tmp_path, capsys):
    from flexfem.fem import gmsh_session

    assert main(["export", str(GUIDE), str(tmp_path / "guide.step"), "--json"]) == 0
    assert capsys.readouterr().out.startswith("{")  # OpenCASCADE's chatter kept off stdout
    with gmsh_session() as gmsh:
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")
        gmsh.model.occ.importShapes(str(tmp_path / "guide.step"))
        gmsh.model.occ.synchronize()
        imported = sum(gmsh.model.occ.getMass(*dt) for dt in gmsh.model.getEntities(2))
    assert imported == pytest.approx(area(load_spec(GUIDE).mechanism), rel=1e-9)
    assert main(["export", str(GUIDE), str(tmp_path / "guide.igs")]) == 2
    assert np.isfinite(imported)
