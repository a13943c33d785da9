"""From densities to an outline: holes kept, islands dropped, thin members measured, and
the DXF re-imports with the same rings."""
import ezdxf
import numpy as np
import pytest

from flexfem.topopt import Grid
from flexfem.topopt.outline import extract_outline, write_dxf


def _frame_and_island(grid):
    ix, iy = np.divmod(np.arange(grid.n_elements), grid.nely)
    frame = ((ix < 20) & (iy < 12) & ~((ix >= 4) & (ix < 16) & (iy >= 4) & (iy < 8)))
    island = (ix >= 26) & (ix < 29) & (iy >= 4) & (iy < 7)
    thin = (ix >= 20) & (ix < 30) & (iy == 11)  # one element thick
    return np.where(frame | island | thin, 1.0, 0.0)


def test_outline_keeps_holes_drops_islands_and_flags_thin_members(tmp_path):
    grid = Grid(30, 12, 0.03, 0.012)   # 1 mm elements
    out = extract_outline(_frame_and_island(grid), grid, anchors=[(0.0, 0.0)],
                          min_member=0.002)
    assert len(out.parts) == 1 and len(out.parts[0].interiors) == 1
    assert len(out.islands) == 1 and abs(out.islands[0] - 9e-6) < 3e-6
    assert out.thin_area > 0.5 * 10 * 1e-6  # the one-element strip
    frame_area = 20 * 12 - 12 * 4 + 10
    assert abs(out.shape.area / 1e-6 - frame_area) < 0.05 * frame_area
    path = tmp_path / "design.dxf"
    assert write_dxf(out, path) == 2
    polylines = list(ezdxf.readfile(path).modelspace().query("LWPOLYLINE"))
    assert len(polylines) == 2 and all(p.closed for p in polylines)
    xs = [x for p in polylines for x, *_ in p.get_points()]
    assert 0.0 - 0.6 <= min(xs) and max(xs) <= 30.0 + 0.6   # mm


def test_a_closing_joins_a_one_node_hinge_by_a_neck():
    grid = Grid(4, 4, 0.004, 0.004)    # two 2 x 2 mm blocks touching at (2, 2) mm
    ix, iy = np.divmod(np.arange(grid.n_elements), grid.nely)
    density = np.where(((ix < 2) & (iy < 2)) | ((ix >= 2) & (iy >= 2)), 1.0, 0.0)
    assert len(extract_outline(density, grid).parts) == 2
    closed = extract_outline(density, grid, close=0.5e-3)
    assert len(closed.parts) == 1
    from shapely import LineString
    neck = LineString([(0.0, 0.004), (0.004, 0.0)]).intersection(closed.shape).length
    assert abs(neck - 2 * 0.5e-3 * (np.sqrt(2) - 1)) < 0.1e-3   # m, the neck's width


def test_a_member_across_a_symmetry_line_keeps_its_width_there():
    """A bar 3 elements thick along the top edge, its left end on the line x = 0: with the
    line as a mirror the outline meets it square (3 elements across at x = 0); as a free
    edge the corners are cut by half an element (2 elements across at x = 0)."""
    from shapely.geometry import LineString

    grid = Grid(10, 10, 10.0, 10.0)
    density = np.zeros((10, 10))
    density[:, 7:] = 1.0          # [ix, iy]: the top three rows
    for mirrors, width in (([(0, 0.0)], 3.0), ([], 2.0)):
        shape = extract_outline(density.ravel(), grid, mirrors=mirrors).shape
        at_line = shape.intersection(LineString([(0.0, 0.0), (0.0, 10.0)])).length
        assert at_line == pytest.approx(width, abs=1e-9)
