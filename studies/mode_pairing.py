"""Modes of a part and of its spatial beam model side by side, in plane and out of plane
(shared by the mechanisms' 3-D modal comparisons: studies/eightbar/eightbar_modes3d.py,
studies/dbma/dbma_modes3d.py).

A part symmetric about its mid-plane z = 0 has each mode either in plane (u_x, u_y even in z,
u_z odd) or out of plane (u_x, u_y odd, u_z even): the share of a mode's vertex motion in the
out-of-plane parts sorts it (0 or 1 up to the mesh's asymmetry; a planar beam model's are
exactly 0 or 1). Within each family the k-th continuum mode is paired with the k-th beam mode.
"""
import numpy as np
from scipy.spatial import cKDTree


SPLIT = 0.5  # out-of-plane share above which a mode is out of plane


def mirror_vertices(p: np.ndarray) -> np.ndarray:
    """Index of each vertex's mirror image about z = 0 (``p`` (3, n) m). Raises ValueError
    if the mesh is not mirror-symmetric (a vertex without its image within 1e-9 of the
    part's size)."""
    tree = cKDTree(p.T)
    mirrored = p.T * np.array([1.0, 1.0, -1.0])
    dist, index = tree.query(mirrored)
    size = np.ptp(p, axis=1).max()
    if dist.max() > 1e-9 * size:
        raise ValueError(f"the mesh is not symmetric about z = 0 (a vertex {dist.max():.3g} m "
                         "from its image); extrude the part symmetrically")
    return index


def out_of_plane_share(vertex_shapes, mirror: np.ndarray) -> np.ndarray:
    """Share (0-1) of each mode's vertex motion in the out-of-plane parts: u_x, u_y odd and
    u_z even in z. ``vertex_shapes``: (n_modes, n_vertices, 3)."""
    u = np.asarray(vertex_shapes)
    even, odd = (u + u[:, mirror]) / 2, (u - u[:, mirror]) / 2
    out = np.sum(odd[:, :, :2] ** 2, axis=(1, 2)) + np.sum(even[:, :, 2] ** 2, axis=1)
    inp = np.sum(even[:, :, :2] ** 2, axis=(1, 2)) + np.sum(odd[:, :, 2] ** 2, axis=1)
    return out / (out + inp)


def working_index(out: dict) -> int:
    """0-based index of the mode (of a beam_modes3d / continuum_modes3d output) with the
    largest effective mass fraction along y, the output axis."""
    return int(np.argmax(np.asarray(out["mass_fraction"])[:, 1]))


def pair_modes(beam: dict, continuum: dict, split: float = SPLIT) -> list:
    """Rows pairing the k-th beam and continuum mode of each family ("in plane", "out of
    plane"), as far as both have one: {"family", "k", "beam_mode", "continuum_mode"
    (1-based), "beam_hz", "continuum_hz", "diff_pct" (beam over continuum - 1),
    "beam_mass_fraction", "continuum_mass_fraction" (x, y, z)}."""
    rows = []
    for family, out in (("in plane", False), ("out of plane", True)):
        b = [i for i, s in enumerate(beam["out_of_plane_share"]) if (s > split) == out]
        c = [i for i, s in enumerate(continuum["out_of_plane_share"]) if (s > split) == out]
        for k, (i, j) in enumerate(zip(b, c)):
            fb, fc = beam["f_hz"][i], continuum["f_hz"][j]
            rows.append({"family": family, "k": k + 1, "beam_mode": i + 1,
                         "continuum_mode": j + 1, "beam_hz": fb, "continuum_hz": fc,
                         "diff_pct": 100 * (fb / fc - 1),
                         "beam_mass_fraction": list(beam["mass_fraction"][i]),
                         "continuum_mass_fraction": list(continuum["mass_fraction"][j])})
    return rows
