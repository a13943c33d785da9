"""A spatial body's volume, centroid and inertia (geometry/spatial/mass.py) against the
solids' closed forms."""
import math

import numpy as np
import pytest

from flexfem.geometry.spatial.description import Cylinder, Prism, SolidBody
from flexfem.geometry.spatial.mass import mass_properties


def test_a_box_and_its_parallel_axes():
    box = SolidBody("b", (((0.0, 0.0, 0.0), (0.02, 0.04, 0.01)),))
    p = mass_properties(box)
    m = 8000 * 0.02 * 0.04 * 0.01
    assert p.mass(8000) == pytest.approx(m)
    assert p.centroid == pytest.approx([0.01, 0.02, 0.005])
    assert np.diag(p.inertia(8000)) == pytest.approx(
        [m * (0.04 ** 2 + 0.01 ** 2) / 12, m * (0.02 ** 2 + 0.01 ** 2) / 12,
         m * (0.02 ** 2 + 0.04 ** 2) / 12])
    two = SolidBody("two", (((0.0, 0.0, 0.0), (0.01, 0.01, 0.01)),
                            ((0.02, 0.0, 0.0), (0.03, 0.01, 0.01))))
    q = mass_properties(two)
    cube = 1e-6 / 6 * 1e-4  # a 10 mm cube's (m^3) side^2 / 6 (m^5 per axis)
    assert q.centroid == pytest.approx([0.015, 0.005, 0.005])
    assert q.second_moments[0, 0] == pytest.approx(2 * cube / 2 + 2 * 1e-6 * 0.01 ** 2)


def test_a_tilted_cylinder_and_a_prism():
    r, L = 0.005, 0.02
    axis = np.array([1.0, 1.0, 0.0]) / math.sqrt(2)
    c = SolidBody("c", cylinders=(Cylinder((0.0, 0.0, 0.0), tuple(axis * L), 2 * r),))
    p = mass_properties(c)
    m = math.pi * r * r * L
    J = p.inertia(1.0)
    assert p.volume == pytest.approx(m)
    assert axis @ J @ axis == pytest.approx(m * r * r / 2)
    assert J[2, 2] == pytest.approx(m * (3 * r * r + L * L) / 12)
    tri = SolidBody("t", prisms=(Prism(((0.0, 0.0), (0.03, 0.0), (0.0, 0.03)), "x",
                                      (0.0, 0.01)),))
    q = mass_properties(tri)
    assert q.volume == pytest.approx(0.5 * 0.03 * 0.03 * 0.01)
    assert q.centroid == pytest.approx([0.005, 0.01, 0.01])  # (y, z) of the triangle's
