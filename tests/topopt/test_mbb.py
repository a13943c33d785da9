"""The MBB beam against a port of top88 at the same settings (the issue's first check)."""
import numpy as np
import pytest
from problems import mbb
from top88_port import top88

from flexfem.topopt import optimize
from flexfem.topopt.element import element_stiffness


def test_element_stiffness_is_top88s():
    nu = 0.3
    A11 = np.array([[12, 3, -6, -3], [3, 12, 3, 0], [-6, 3, 12, -3], [-3, 0, -3, 12]])
    A12 = np.array([[-6, -3, 0, 3], [-3, -6, -3, -6], [0, -3, -6, 3], [3, -6, 3, -6]])
    B11 = np.array([[-4, 3, -2, 9], [3, -4, -9, 4], [-2, -9, -4, -3], [9, 4, -3, -4]])
    B12 = np.array([[2, -3, 4, -9], [-3, 2, 9, -2], [4, 9, 2, 3], [-9, -2, 3, 2]])
    KE = 1 / (1 - nu**2) / 24 * (np.block([[A11, A12], [A12.T, A11]])
                                 + nu * np.block([[B11, B12], [B12.T, B11]]))
    # top88 numbers its nodes from the top-left, clockwise seen with y down: the same element
    perm = [6, 7, 4, 5, 2, 3, 0, 1]
    flip = np.array([1, -1] * 4)
    ours = element_stiffness()
    assert np.allclose(ours, (KE[np.ix_(perm, perm)] * np.outer(flip, flip)), atol=1e-14)


@pytest.mark.parametrize("ft, kind", [(1, "sensitivity"), (2, "density")])
def test_mbb_compliance_matches_the_top88_port(ft, kind):
    c_ref, loops_ref, x_ref = top88(60, 20, 0.5, 3.0, 1.5, ft)
    result = optimize(mbb(filter_kind=kind))
    assert result.converged
    assert abs(result.history[-1, 0] - c_ref) / c_ref < 0.01
    assert abs(result.objective - c_ref) / c_ref < 0.01
    assert abs(result.iterations - loops_ref) <= 0.1 * loops_ref
    assert result.volume_fraction == pytest.approx(0.5, abs=1e-3)
    # the same layout: top88's image has y down, ours y up
    ours = result.problem.grid.image(result.density)
    assert np.mean(np.abs(ours - x_ref)) < 0.02
