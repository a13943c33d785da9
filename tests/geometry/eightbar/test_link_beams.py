"""Link plates as spatial beams (geometry/eightbar/link_beams.py): the skeleton of a union
of rectangles, its mass against the plate's, and a plate bar's free-free frequencies against
the closed forms."""
import numpy as np
import pytest

from flexfem.fem import material
from flexfem.fem.beam.spatial import Beam3DModel, Section, solve_beam3d_modes
from flexfem.fem.beam.spatial.inertia import mass_properties
from flexfem.reduced.layout import link_moments
from flexfem.geometry.eightbar.link_beams import link_skeleton, mesh_skeleton
from flexfem.geometry.flexure_linkage import Part

W, T = 5e-3, 6e-3  # the eight-bar's link width and thickness
BETA_L_FREE = np.array([4.7300408, 7.8532046])  # free-free beam, first two bending modes


def _model(parts, link, size, stations=(), shear=False):
    xy, elements, pairs, at = mesh_skeleton(link_skeleton(parts, link), stations, size)
    nodes = np.column_stack([xy, np.zeros(len(xy))])
    return Beam3DModel(nodes, elements, Section.rect(T, W), material("aluminium_6061_t6"),
                       shear=shear), pairs, at


def test_a_tee_is_cut_where_its_arms_enter_the_stem():
    """The coupler's T: a 115 mm stem and two 17.5 mm arms overlapping it (and each other):
    the stem whole, each arm ending at the stem's edge with a rigid offset to the stem's
    centre-line; the beams' area is the union's."""
    parts = [Part("arm0", "t", "bar", (-15.0e-3, 0.0), (2.5e-3, 0.0), W),
             Part("arm1", "t", "bar", (-2.5e-3, 0.0), (15.0e-3, 0.0), W),
             Part("stem", "t", "bar", (0.0, 2.5e-3), (0.0, -112.5e-3), W)]
    sk = link_skeleton(parts, "t")
    assert [np.round(np.array(p) * 1e3, 9).tolist() for p in sk.pieces] == [
        [[0.0, 2.5], [0.0, -112.5]], [[-15.0, 0.0], [-2.5, 0.0]], [[2.5, 0.0], [15.0, 0.0]]]
    assert [np.round(np.array(o) * 1e3, 9).tolist() for o in sk.offsets] == [
        [[-2.5, 0.0], [0.0, 0.0]], [[2.5, 0.0], [0.0, 0.0]]]
    length = sum(np.linalg.norm(b - a) for a, b in sk.pieces)
    assert length * W == pytest.approx(link_moments(parts, "t")[0], rel=1e-12)


def test_an_oblique_bar_into_a_hub_and_the_mass_of_the_plate():
    """A bar tilted 4.13 degrees (the eight-bar's crank) ending on a hub's centre: the bar
    stops at the hub's edge, offset along itself to the hub's centre-line. Mass exact (the
    trapezoid's mean length), the centroid and inertia to the sliver (< 1e-3)."""
    hub = Part("hub", "c", "hub", (-90e-3, 69.166e-3), (-100e-3, 69.166e-3), W)
    bar = Part("bar", "c", "bar", (-99.567e-3, 5.984e-3), (-95e-3, 69.166e-3), W)
    model, pairs, _ = _model([bar, hub], "c", W)
    sk = link_skeleton([bar, hub], "c")
    assert sk.offsets[0][1] == pytest.approx([-95e-3, 69.166e-3], abs=1e-12)
    assert sk.offsets[0][0][1] == pytest.approx(69.166e-3 - W / 2, abs=1e-12)
    assert len(pairs) == 1
    A, Sx, Sy, Ixx, Iyy = link_moments([bar, hub], "c")
    rho = model.material.rho
    m, c, J = mass_properties(model)
    assert m == pytest.approx(rho * T * A, rel=1e-12)
    assert c[:2] == pytest.approx([Sx / A, Sy / A], abs=1e-3 * W)
    jz = rho * T * (Ixx + Iyy - (Sx**2 + Sy**2) / A)
    assert J[2, 2] == pytest.approx(jz, rel=1e-3)


@pytest.mark.parametrize("shear", [False, True])
def test_a_free_plate_bar_rings_at_the_closed_form_frequencies(shear):
    """A free-free 0.4 m bar of the links' 5 x 6 mm section (aluminium), 40 elements.
    Bending in plane (I_z = t W^3/12) and out of plane (I_y = W t^3/12) against Euler-
    Bernoulli, beta_n^2 sqrt(EI / rho A) / (2 pi L^2): rotary inertia lowers mode n by
    about (beta_n r)^2 (r^2 = I / A; measured 0.88-1.10 times it), shear by about E / (kappa
    G) times more (measured 2.0-2.1 times it with both): below, within 1.2 and 4.2 times it.
    Torsion, n / 2L sqrt(G J / rho I_p) with the series J: the linear elements' consistent-
    mass dispersion, (6 / h^2)(1 - cos kh) / (2 + cos kh) c^2 (+2.6e-4, +1.0e-3), to 1e-9."""
    L, n_el = 0.4, 40
    bar = Part("bar", "b", "bar", (0.0, 0.0), (L, 0.0), W)
    model, _, _ = _model([bar], "b", L / n_el, shear=shear)
    modes = solve_beam3d_modes(model, [], n=30)
    f, s = modes.frequencies_hz, modes.shapes
    elastic = f > 1.0  # the six rigid-body modes at 0
    assert np.count_nonzero(~elastic) == 6
    mat, sec = model.material, model.sections[0]
    G = mat.E / (2 * (1 + mat.nu))
    kind = np.array(["y" if np.abs(v[:, 1]).max() > np.abs(v[:, 2]).max() else "z"
                     for v in s])
    twist = np.abs(s[:, :, 3]).max(axis=1) * 1e-2 > np.abs(s[:, :, :3]).max(axis=(1, 2))
    factor = 4.2 if shear else 1.2
    for name, I in (("y", sec.Iz), ("z", sec.Iy)):
        exact = BETA_L_FREE**2 / (2 * np.pi * L**2) * np.sqrt(mat.E * I / (mat.rho * sec.A))
        err = f[elastic & ~twist & (kind == name)][:2] / exact - 1
        r2 = (BETA_L_FREE / L) ** 2 * I / sec.A
        assert np.all(err < 0) and np.all(err > -factor * r2), (name, err / r2)
    c = np.sqrt(G * sec.J / (mat.rho * sec.Ip))
    kh = np.array([1, 2]) * np.pi / n_el
    discrete = np.sqrt(6 * (1 - np.cos(kh)) / (2 + np.cos(kh))) * n_el / L * c / (2 * np.pi)
    assert f[elastic & twist][:2] == pytest.approx(discrete, rel=1e-9)
    assert discrete == pytest.approx(np.array([1, 2]) / (2 * L) * c, rel=1.1e-3)


def test_bad_input_is_named():
    with pytest.raises(ValueError, match="no bars or hubs"):
        link_skeleton([], "x")
    bar = Part("bar", "b", "bar", (0.0, 0.0), (0.1, 0.0), W)
    with pytest.raises(ValueError, match="size"):
        mesh_skeleton(link_skeleton([bar], "b"), [], 0.0)
