"""The outline's necks (topopt/necks.py) on shapes whose narrowest widths are known, and
the body-fitted stress at the necks of an inverter."""
import numpy as np
import pytest
from shapely.geometry import Point, box

from flexfem.topopt.necks import find_necks, mirrored, outline_necks
from flexfem.topopt.outline import Outline


def test_rectangular_neck_between_two_blocks():
    shape = box(0, 0, 10, 10).union(box(10, 4, 14, 6)).union(box(14, 0, 24, 10))
    necks = find_necks(shape, 4.0)
    assert len(necks) == 1
    assert necks[0].width == pytest.approx(2.0, abs=1e-9)
    assert 10.0 <= necks[0].where[0] <= 14.0 and necks[0].where[1] == pytest.approx(5.0)


def test_circular_notch_hinge_and_a_notched_frame():
    """A notch hinge: two circles of radius 4 cut from a 20 x 10 block, their centres 12
    apart, leave 12 - 8 = 4; a frame's 3-wide bar with a 2-deep notch leaves 1. The
    frame's corners (slivers of the opening, one contact each) are no necks."""
    notch = box(0, 0, 20, 10).difference(Point(10, -1).buffer(4, 64)).difference(
        Point(10, 11).buffer(4, 64))
    (neck,) = find_necks(notch, 6.0)
    assert neck.width == pytest.approx(4.0, abs=1e-6)
    assert neck.where == pytest.approx((10.0, 5.0), abs=1e-6)
    frame = box(0, 0, 20, 20).difference(box(3, 3, 17, 17)).difference(box(8, 0, 12, 2))
    (neck,) = find_necks(frame, 2.5)
    assert neck.width == pytest.approx(1.0, abs=1e-9)
    assert find_necks(box(0, 0, 20, 20).difference(box(3, 3, 17, 17)), 2.5) == []


def test_a_hinge_cut_by_a_symmetry_line_is_measured_whole():
    """The upper half (y >= 0) of a 3-wide neck about y = 0: 1.5 on the half, 3 mirrored."""
    half = box(0, 0, 10, 5).union(box(10, 0, 14, 1.5)).union(box(14, 0, 24, 5))
    outline = Outline(half, (), 0.0)
    (neck,) = outline_necks(outline, 5.0, mirrors=[(1, 0.0)], domain=(0, 0, 24, 5))
    assert neck.width == pytest.approx(3.0, abs=1e-9)
    assert mirrored(half, [(1, 0.0)]).area == pytest.approx(2 * half.area)


def test_neck_report_of_a_drawn_inverter():
    """An inverter drawn by hand on the 24 x 12 unit problem: a column at the input and the
    clamp, a beam over the top with a 1-wide, 3-long neck, a column down to the output.
    The neck is found, 1 wide, with the body-fitted stress there; the wide members are no
    necks."""
    from problems import inverter

    from flexfem.topopt.neck_check import neck_report

    problem = inverter(24, 12, "density")
    shape = box(0, 0, 3, 12).union(box(3, 9, 10, 12)).union(box(10, 10, 13, 11)).union(
        box(13, 9, 24, 12)).union(box(21, 0, 24, 9))
    (row,) = neck_report(problem, Outline(shape, (), 0.0), 2.0)
    assert row["width"] == pytest.approx(1.0, abs=1e-9)
    assert 10.0 <= row["where"][0] <= 13.0 and row["where"][1] == pytest.approx(10.5)
    assert np.isfinite(row["peak_stress"]) and row["peak_stress"] > 0
