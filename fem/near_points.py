"""Which points lie within a given radius of which centres: a spatial hash, one grid per size
class of the radii, in NumPy alone (the mesh checks run on every mesh, and SciPy's KD-tree
would import scipy.spatial, ~7 MiB resident, into every process that reads a mesh)."""
from itertools import product

import numpy as np

# large primes of the spatial hash (Teschner et al. 2003, "Optimized spatial hashing for
# collision detection of deformable objects"); a collision only adds candidates, checked after
_PRIMES = np.array([73856093, 19349663, 83492791], dtype=np.int64)


def _hash(cells: np.ndarray) -> np.ndarray:
    """int64 key of each integer cell ((dim, n)); wraps around on overflow, as intended."""
    with np.errstate(over="ignore"):
        return (_PRIMES[:len(cells), None] * cells).sum(axis=0)


def pairs_within(points: np.ndarray, centres: np.ndarray, radii: np.ndarray):
    """Index arrays (i, j), each pair once, of every centre i and point j with
    |points[:, j] - centres[:, i]| <= radii[i]; points (dim, n), centres (dim, m), radii (m,)
    >= 0, in one unit."""
    dim = points.shape[0]
    positive = radii[radii > 0]
    size = np.maximum(radii, positive.min() if len(positive) else 1.0)  # grid cells: > 0
    level = np.floor(np.log2(size / size.min())).astype(np.int64)
    offsets = np.array(list(product((-1, 0, 1), repeat=dim)), dtype=np.int64)
    found_i, found_j = [], []
    for k in np.unique(level):
        mine = np.flatnonzero(level == k)
        cell = size[mine].max()  # every sphere of this class within its centre's 3^dim cells
        keys = _hash(np.floor(points / cell).astype(np.int64))
        order = np.argsort(keys, kind="stable")
        keys = keys[order]
        home = np.floor(centres[:, mine] / cell).astype(np.int64)
        for offset in offsets:
            wanted = _hash(home + offset[:, None])
            lo, hi = np.searchsorted(keys, wanted, "left"), np.searchsorted(keys, wanted, "right")
            count = hi - lo
            first = np.repeat(lo - (np.cumsum(count) - count), count)
            found_i.append(np.repeat(mine, count))
            found_j.append(order[first + np.arange(count.sum())])
    i, j = np.concatenate(found_i), np.concatenate(found_j)
    keep = np.sum((points[:, j] - centres[:, i]) ** 2, axis=0) <= radii[i] ** 2
    pairs = np.unique(np.stack([i[keep], j[keep]]), axis=1)  # hash collisions repeat some
    return pairs[0], pairs[1]
