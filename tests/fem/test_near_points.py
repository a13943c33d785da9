"""The spatial hash of fem/near_points.py finds exactly the point-centre pairs that a brute
force distance check finds, across radii of very different sizes, in 2-D and 3-D."""
import numpy as np
import pytest
from flexfem.fem.near_points import pairs_within


@pytest.mark.parametrize("dim", [2, 3])
def test_pairs_within_equals_brute_force(dim):
    rng = np.random.default_rng(dim)
    points = rng.uniform(-1.0, 3.0, (dim, 400))
    centres = np.concatenate([rng.uniform(-1.0, 3.0, (dim, 150)), points[:, :10]], axis=1)
    # radii over four decades, some zero (a point exactly on its centre still counts)
    radii = 10.0 ** rng.uniform(-3.0, 0.3, centres.shape[1])
    radii[-5:] = 0.0
    i, j = pairs_within(points, centres, radii)
    distance = np.linalg.norm(points[:, None, :] - centres[:, :, None], axis=0)  # (m, n)
    expected = np.argwhere(distance <= radii[:, None]).T
    assert np.array_equal(np.stack([i, j]), expected)
    assert len(i) > 200  # the radii do reach many points


def test_coordinates_far_from_the_origin_and_tiny_radii():
    rng = np.random.default_rng(7)
    points = 1e6 + rng.uniform(0.0, 1e-3, (3, 300))  # m: a millimetre part a kilometre away
    centres, radii = points[:, :50] + 1e-7, np.full(50, 2e-7)
    i, j = pairs_within(points, centres, radii)
    distance = np.linalg.norm(points[:, None, :] - centres[:, :, None], axis=0)
    assert np.array_equal(np.stack([i, j]), np.argwhere(distance <= radii[:, None]).T)
    assert np.array_equal(i, j)  # each centre near its own point only
