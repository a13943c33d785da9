"""The optimality-criteria update of top88 (Andreassen et al. 2011): a bisection on the
volume multiplier, the volume measured on the physical (filtered) densities."""
import numpy as np


def oc_update(z, dc, dv, volume_limit, volume, lower, upper, move=0.2) -> np.ndarray:
    """The next design variables. ``dc``, ``dv``: gradients of compliance and volume with
    respect to z; ``volume(z)``: the volume fraction of the physical densities;
    ``volume_limit``: solid fraction."""
    l1, l2 = 0.0, 1e9
    ratio = np.maximum(0.0, -dc) / np.maximum(dv, 1e-30)
    lo, hi = np.maximum(lower, z - move), np.minimum(upper, z + move)
    while (l2 - l1) / (l1 + l2) > 1e-3:
        lmid = 0.5 * (l2 + l1)
        znew = np.clip(z * np.sqrt(ratio / lmid), lo, hi)
        if volume(znew) > volume_limit:
            l1 = lmid
        else:
            l2 = lmid
    return znew
