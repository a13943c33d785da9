"""Polygon bodies: a [[body]]'s polygon (geometry/polygon.py, description.Body) checked by hand
(area moments of a rectangle, an L-shape and a frame with a hole; chords; the outline centre
of a box-and-polygon union), against the box it replaces (a rectangle written as a polygon
gives the box's models to rounding; an L written as one polygon the continuum of its two
boxes), refused with the file, line and body named where it is no simple polygon, and
exported to DXF and STEP with the area of its parts."""
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from flexfem.geometry import polygon
from flexfem.geometry.mechanism import Body, Leaf, Mechanism
from flexfem.geometry.mechanism.beams import beam_spec
from flexfem.geometry.mechanism.export import area, export
from flexfem.geometry.outline_files import polyline_area
from flexfem.geometry.user_model import load_spec
from flexfem.reduced.model_file import _body_mass, _block_height
from flexfem.studies.cli import main

BODIES = Path(__file__).parents[3] / "examples" / "bodies"
L_SHAPE = ((0, 0), (3, 0), (3, 1), (1, 1), (1, 3), (0, 3))


def test_rectangle_moments_by_hand():
    w, h = 0.03, 0.008
    a, c, (xx, yy, xy) = polygon.moments([((0.01, 0.04), (0.01 + w, 0.04 + h))])
    assert a == pytest.approx(w * h, rel=1e-12)
    assert c == pytest.approx([0.01 + w / 2, 0.04 + h / 2], rel=1e-12)
    assert (xx, yy) == pytest.approx((h * w ** 3 / 12, w * h ** 3 / 12), rel=1e-9)
    assert abs(xy) < 1e-9 * xx


def test_l_shape_moments_by_hand():
    """The L of a 3 x 1 bar and a 1 x 2 bar on it: area 5, centroid (1.1, 1.1); about it
    int (x - cx)^2 dA = 27/12 + 3 (0.4)^2 + 2/12 + 2 (0.6)^2 = 217/60 (and the same in y by
    symmetry), int (x - cx)(y - cy) dA = 3 (0.4)(-0.6) + 2 (-0.6)(0.9) = -1.8."""
    for vertices in (L_SHAPE, L_SHAPE[::-1]):  # either orientation
        a, c, (xx, yy, xy) = polygon.moments([vertices])
        assert a == pytest.approx(5.0) and c == pytest.approx([1.1, 1.1])
        assert (xx, yy, xy) == pytest.approx((217 / 60, 217 / 60, -1.8))
    # the beam model's body: mass rho t A, rotary inertia rho t (xx + yy) about the centroid
    body = type("Rigid", (), {"blocks": (L_SHAPE,)})()
    m, c, J = _body_mass(body, 2.0)
    assert (m, J) == pytest.approx((10.0, 2 * 217 / 30)) and c == pytest.approx([1.1, 1.1])


def test_a_frame_of_boxes_and_polygons_has_its_hole():
    """Four bars around a 2 x 2 hole in a 4 x 4 square: the union's moments are the square's
    less the hole's (a polygon among the blocks makes the union count)."""
    bars = [((0, 0), (4, 1)), ((0, 3), (4, 4)), ((0, 1), (1, 3)),
            ((3, 1), (4, 1), (4, 3), (3, 3))]
    a, c, (xx, yy, xy) = polygon.moments(bars)
    assert a == pytest.approx(12.0) and c == pytest.approx([2.0, 2.0])
    assert (xx, yy) == pytest.approx((4 ** 4 / 12 - 2 ** 4 / 12,) * 2) and xy == pytest.approx(0)


def test_chords_and_edges_by_hand():
    # along the L's inner edge y = 1 the line runs through the foot (x 0..1) and the edge
    assert polygon.chord(L_SHAPE, (2.0, 1.0), (1.0, 0.0), 1e-9) == pytest.approx(3.0)
    assert polygon.chord(L_SHAPE, (2.0, 1.0), (0.0, 1.0), 1e-9) == pytest.approx(1.0)
    assert polygon.chord(L_SHAPE, (0.5, 2.0), (1.0, 0.0), 1e-9) == pytest.approx(1.0)
    assert polygon.chord(L_SHAPE, (5.0, 5.0), (1.0, 0.0), 1e-9) is None
    # the beam model's block height: a rectangle as a polygon gives the box's chord
    box, square = ((0.0, 0.0), (2.0, 1.0)), ((0, 0), (2, 0), (2, 1), (0, 1))
    for point, d in (((0.5, 1.0), (0.0, -1.0)), ((2.0, 0.3), (-1.0, 0.0))):
        assert _block_height(point, d, [square]) == pytest.approx(
            _block_height(point, d, [box]), rel=1e-8)
    keel = ((0, 0), (1, 1), (1, 2), (-1, 2), (-1, 1))
    assert polygon.edge_at(keel, (0.5, 0.5), 1e-9) == pytest.approx(np.array([1, 1]) / 2 ** 0.5)
    assert polygon.edge_at(keel, (1.0, 1.0), 1e-9, corners=False) is None


def test_outline_centre_of_a_box_and_polygon_union_by_hand():
    """A house: the box (0, 0)-(2, 1) and the roof triangle (0, 1) (2, 1) (1, 2). Its outline
    is the union's (the shared edge y = 1 is inside): the bottom 2, the walls 1 and 1, the
    roof 2 sqrt(2); a leaf 0.2 wide leaves the bottom at x = 0.5."""
    house = Body("house", (((0, 0), (2, 1)),), polygons=(((0, 1), (2, 1), (1, 2)),))
    ground = Body("ground", (((0, -3), (2, -2)),))
    m = Mechanism((ground, house), (Leaf(("ground", "house"), (0.5, -2), (0.5, 0), 0.2),), 0.01)
    m.check({"ground"})
    r2 = math.sqrt(2)
    total = 2 + 1 + 1 + 2 * r2 - 0.2
    expected = [(2 * 1 + 1 * 2 + r2 * 1.5 + r2 * 0.5 - 0.2 * 0.5) / total,
                (1 * 0.5 + 1 * 0.5 + 2 * r2 * 1.5) / total]
    assert m.outline_centre("house") == pytest.approx(expected)
    assert house.area == pytest.approx(3.0)


def test_a_box_in_the_notch_of_an_l_is_no_overlap():
    """Overlap is the polygons' own, not their convex hulls': a box in the L's notch is
    accepted, one that reaches 0.1 into the L's arm refused."""
    ell = Body("ell", polygons=(L_SHAPE,))
    for corner, overlaps in (((1.2, 1.2), False), ((0.9, 1.2), True)):
        nook = Body("nook", ((corner, (3, 3)),))
        m = Mechanism((ell, nook), (Leaf(("ell", "nook"), (2, 0.5), (2, 2), 0.05),), 0.01)
        if overlaps:
            with pytest.raises(ValueError, match="bodies 'ell' and 'nook' overlap"):
                m.check({"ell"})
        else:
            m.check({"ell"})
            assert m.span(0).length == pytest.approx(0.2)


def _as_polygons(mechanism: Mechanism) -> Mechanism:
    """Every box of every body as the polygon of its four corners."""
    bodies = tuple(Body(b.name, (), b.source, tuple(((x0, y0), (x1, y0), (x1, y1), (x0, y1))
                                                    for (x0, y0), (x1, y1) in b.boxes))
                   for b in mechanism.bodies)
    return Mechanism(bodies, mechanism.flexures, mechanism.depth, mechanism.source)


def _outputs(result: dict) -> dict:
    keys = ("stiffness", "mean_displacement", "frequencies_hz", "compliance", "max_von_mises")
    return {k: result[k] for k in keys if k in result}


def _numbers(value) -> list:
    if isinstance(value, dict):
        return [x for k in sorted(value) for x in _numbers(value[k])]
    if isinstance(value, (list, tuple)):
        return [x for v in value for x in _numbers(v)]
    return [float(value)] if isinstance(value, (int, float)) else []


def _close(a: dict, b: dict, rel: float) -> None:
    """Each output of ``a`` and ``b`` equal within ``rel`` of its largest entry."""
    for key in a:
        x, y = np.array(_numbers(a[key])), np.array(_numbers(b[key]))
        assert np.allclose(y, x, rtol=rel, atol=rel * np.abs(x).max()), key


@pytest.mark.parametrize("name", ["guide", "cross_pivot", "notch"])
def test_a_rectangle_written_as_a_polygon_is_the_box(name):
    """The guide (square roots), the cross pivot (oblique roots: the acute edge on a polygon's
    face) and the notch: the same continuum mesh and results, and the same beam model, to
    rounding."""
    from flexfem.studies.user_model.analysis import analyze_model

    spec = load_spec(BODIES / f"{name}.toml")
    poly = _as_polygons(spec.mechanism)
    options = {k: getattr(spec.beams, k) for k in ("elements", "shear", "root_extension",
                                                   "crossings", "roots", "notch_correction")}
    twin = replace(spec, mechanism=poly, beams=beam_spec(poly, **options))
    for model in ("continuum", "beam"):
        box, written = (_outputs(analyze_model(s, model=model)) for s in (spec, twin))
        _close(box, written, 1e-7)


def test_an_l_as_one_polygon_is_the_l_of_two_boxes():
    """The guide's stage grown to an L (a leg down its right side): as one polygon and as two
    boxes the continuum is the same; the beam model's block has the same mass and inertia."""
    from flexfem.studies.user_model.analysis import analyze_model

    spec = load_spec(BODIES / "guide.toml")
    L = spec.constants["L"]
    boxes = Body("stage", (((-0.015, L), (0.015, L + 0.008)), ((0.015, L - 0.01),
                                                               (0.025, L + 0.008))))
    ell = Body("stage", polygons=(((-0.015, L), (0.015, L), (0.015, L - 0.01),
                                   (0.025, L - 0.01), (0.025, L + 0.008),
                                   (-0.015, L + 0.008)),))
    results, masses = [], []
    for stage in (boxes, ell):
        m = replace(spec.mechanism, bodies=(spec.mechanism.bodies[0], stage))
        s = replace(spec, mechanism=m, beams=beam_spec(m))
        results.append(_outputs(analyze_model(s)))
        masses.append(_body_mass(s.beams.rigid[1], 1.0))
    _close(*results, 1e-7)
    (m0, c0, j0), (m1, c1, j1) = masses
    assert m0 == pytest.approx(0.03 * 0.008 + 0.01 * 0.018) and m1 == pytest.approx(m0)
    assert c1 == pytest.approx(c0) and j1 == pytest.approx(j0)


def _with_stage(tmp_path, key_value: str) -> Path:
    text = (BODIES / "guide.toml").read_text()
    old = 'box = [["-d / 2 - 0.005", "L"], ["d / 2 + 0.005", "L + 0.008"]]'
    path = tmp_path / "guide.toml"
    path.write_text(text.replace(old, key_value))
    return path


@pytest.mark.parametrize("polygon_line, message", [
    ('polygon = [[-0.015, "L"], [0.015, "L"]]', "2 distinct vertices; a polygon needs at least 3"),
    ('polygon = [[-0.015, "L"], [0.0, "L"], [0.015, "L"]]', "zero area"),
    ('polygon = [[-0.015, "L"], [0.015, "L + 0.008"], [0.015, "L"], [-0.015, "L + 0.008"]]',
     "crosses itself"),
    ('polygon = [[-0.015, "L"], [0.015, "L"], [0.015, nan]]', "not a finite number"),
    ('polygon = [[-0.015, "L"], [0.015, "L"], [0.015, "L * 1e308 * 1e308"]]', "not finite"),
    ('polygon = [[[-0.015, "L"], [0.015, "L"], [0, "L + 0.01"]], [[0, 0], [1, 1]]]',
     "polygon 2 .* 2 distinct vertices"),
    ('polygon = [[-0.015, "L"], [0.015], [0.015, 1]]', "must be a list of vertices"),
])
def test_a_bad_polygon_names_the_file_line_and_body(tmp_path, polygon_line, message):
    path = _with_stage(tmp_path, polygon_line)
    with pytest.raises(ValueError, match=message) as error:
        load_spec(path)
    line = next(i + 1 for i, text in enumerate(path.read_text().splitlines())
                if text.startswith("polygon ="))
    assert f"{path} line {line}" in str(error.value) and "'stage'" in str(error.value)


def test_a_body_needs_a_box_or_a_polygon_and_may_have_both(tmp_path):
    with pytest.raises(ValueError, match="'stage' needs box = .* or polygon ="):
        load_spec(_with_stage(tmp_path, ""))
    both = _with_stage(tmp_path, 'box = [[-0.015, "L"], [0.015, "L + 0.008"]]\n'
                                 'polygon = [[-0.015, "L + 0.008"], [0.015, "L + 0.008"], '
                                 '[0.0, "L + 0.02"]]')
    stage = load_spec(both).mechanism.body("stage")
    assert stage.area == pytest.approx(0.03 * 0.008 + 0.03 * 0.012 / 2)
    with pytest.raises(ValueError, match="bodies 'ground' and 'stage' overlap"):
        load_spec(_with_stage(tmp_path, 'polygon = [[-0.015, -0.002], [0.015, "L"], '
                                        '[0.015, "L + 0.008"], [-0.015, "L + 0.008"]]'))


def test_polygon_bodies_export_to_dxf_and_step_with_their_area(tmp_path, capsys):
    """The remote-centre pivot: a V-block and a keel, leaves meeting their faces square. The
    face is the bodies' polygons plus the two leaves' free spans (L x t each); the DXF holds
    it as straight segments (the outer loop and the hole between the leaves), the STEP
    re-imports with it."""
    ezdxf = pytest.importorskip("ezdxf")
    from flexfem.fem import gmsh_session

    file = BODIES / "remote_centre.toml"
    spec = load_spec(file)
    L, t = spec.constants["L"], spec.constants["t"]
    by_hand = sum(polygon.moments(b.polygons)[0] for b in spec.mechanism.bodies) + 2 * L * t
    assert area(spec.mechanism) == pytest.approx(by_hand, rel=1e-9)
    export(spec.mechanism, tmp_path / "pivot.dxf")
    doc = ezdxf.readfile(tmp_path / "pivot.dxf")
    lines = list(doc.modelspace().query("LWPOLYLINE"))
    loops = [list(p.get_points("xyb")) for p in lines]
    assert len(loops) == 2 and all(p.closed for p in lines)
    assert all(b == 0 for loop in loops for _, _, b in loop)
    areas = sorted((abs(polyline_area(loop)) for loop in loops), reverse=True)
    assert (areas[0] - areas[1]) * 1e-6 == pytest.approx(by_hand, rel=1e-9)
    assert main(["export", str(file), str(tmp_path / "pivot.step"), "--json"]) == 0
    capsys.readouterr()
    with gmsh_session() as gmsh:
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")
        gmsh.model.occ.importShapes(str(tmp_path / "pivot.step"))
        gmsh.model.occ.synchronize()
        imported = sum(gmsh.model.occ.getMass(*dt) for dt in gmsh.model.getEntities(2))
    assert imported == pytest.approx(by_hand, rel=1e-9)
