"""Natural frequencies of a slender cantilever against Euler-Bernoulli and Saint-Venant theory,
and the algebra of the modal solution (M-orthonormal shapes, effective masses)."""
import numpy as np
import pytest
from meshes import beam_2d, beam_3d
from flexfem.fem import Fixed, Model, PlaneStress, Solid3D, solve_modes

L, H, W = 1.0, 0.05, 0.03  # L/H = 20, L/W = 33: slender, so the Timoshenko terms are small
BETA_L = np.array([1.875104, 4.694091, 7.854757])  # cantilever roots of cos(bL) cosh(bL) = -1
KAPPA = 5 / 6  # shear coefficient of a rectangle


def euler_bernoulli_hz(E, rho, I, A, length=L):
    """Bending frequencies (Hz) of a clamped-free Euler-Bernoulli beam."""
    return BETA_L**2 / (2 * np.pi) * np.sqrt(E * I / (rho * A * length**4))


def timoshenko_factor(E, nu, depth, length=L):
    """First-order shear + rotary inertia correction of the frequencies, omega_T / omega_EB =
    1 - (1/2) (beta_n r)^2 (1 + E / (kappa G)), r^2 = I / A = depth^2 / 12 (Timoshenko)."""
    G = E / (2 * (1 + nu))
    r2 = depth**2 / 12
    return 1 - 0.5 * (BETA_L / length) ** 2 * r2 * (1 + E / (KAPPA * G))


def effective_mass_fraction_eb():
    """Effective mass / total mass of the cantilever bending modes, (2 sigma_n / beta_n L)^2 with
    the mode shape cosh - cos - sigma (sinh - sin) normalised to mean square 1."""
    b = BETA_L
    sigma = (np.sinh(b) - np.sin(b)) / (np.cosh(b) + np.cos(b))
    return (2 * sigma / b) ** 2


def saint_venant_torsion_constant(a, b):
    """J (m^4) of an a x b rectangle, a >= b: the series solution of Saint-Venant torsion."""
    a, b = max(a, b), min(a, b)
    n = np.arange(1, 60, 2)
    return a * b**3 / 3 * (1 - 192 / np.pi**5 * b / a * np.sum(np.tanh(n * np.pi * a / (2 * b)) / n**5))


@pytest.fixture(scope="module")
def modes_2d(steel):
    model = Model(beam_2d(L, H, H / 4), steel, PlaneStress(thickness=W), order=2)
    return solve_modes(model, 12, [Fixed("fixed")])


@pytest.fixture(scope="module")
def modes_3d(steel):
    model = Model(beam_3d(L, H, W, W / 2), steel, Solid3D(), order=2)
    return solve_modes(model, 8, [Fixed("fixed")])


def test_plane_stress_bending_frequencies(steel, modes_2d):
    y_modes = [k for k in range(12) if modes_2d.dominant_direction(k) == 1][:3]
    f = modes_2d.frequencies_hz[y_modes]
    expected = euler_bernoulli_hz(steel.E, steel.rho, W * H**3 / 12, W * H)
    expected *= timoshenko_factor(steel.E, steel.nu, H)
    # The corrections themselves are 0.15, 0.95, 2.6 % for modes 1-3. The first-order formula is
    # exact for pinned ends only; for a clamped-free beam it is an estimate good to a fraction
    # (~20 %) of itself, i.e. <= 0.5 % on mode 3; the P2 discretisation (4 elements through the
    # depth) adds < 0.3 %. Allow 1 %.
    assert f == pytest.approx(expected, rel=0.01)
    # and the uncorrected Euler-Bernoulli value is clearly further away for mode 3
    eb = euler_bernoulli_hz(steel.E, steel.rho, W * H**3 / 12, W * H)
    assert abs(f[2] / eb[2] - 1) > 0.015


def test_plane_stress_axial_frequency(steel, modes_2d):
    x_modes = [k for k in range(12) if modes_2d.dominant_direction(k) == 0]
    # uniaxial stress in a slender bar: f = (2k - 1) / (4 L) sqrt(E / rho); the lateral inertia
    # (Rayleigh-Love) correction is nu^2 (pi r / 2L)^2 ~ 1e-5: exact to the P2 error (< 0.1 %)
    assert modes_2d.frequencies_hz[x_modes[0]] == pytest.approx(
        np.sqrt(steel.E / steel.rho) / (4 * L), rel=1e-3)
    # effective mass of the first axial mode of a clamped-free bar: 8 / pi^2 of the total
    assert modes_2d.effective_mass_fraction[x_modes[0], 0] == pytest.approx(8 / np.pi**2, rel=1e-3)


def test_bending_effective_masses_and_their_sum(modes_2d):
    frac = modes_2d.effective_mass_fraction
    y_modes = [k for k in range(12) if modes_2d.dominant_direction(k) == 1][:3]
    # mode shapes change by O(Timoshenko correction) ~ 1 %: effective masses within 2 %
    assert frac[y_modes, 1] == pytest.approx(effective_mass_fraction_eb(), rel=0.02)
    # cumulative effective mass grows toward the total and never exceeds it (Parseval in the
    # M inner product: the full set of modes sums to exactly the total mass)
    cumulative = np.cumsum(frac, axis=0)
    assert np.all(np.diff(cumulative, axis=0) >= -1e-12)
    assert np.all(cumulative[-1] <= 1 + 1e-9)
    # 12 modes hold the first 5-6 bending modes (sum of (2 sigma/beta L)^2 for n <= 5: 0.96)
    # and 1-2 axial ones (8/pi^2 (1 + 1/9) = 0.90)
    assert cumulative[-1, 1] > 0.93 and cumulative[-1, 0] > 0.80


def test_shapes_are_mass_orthonormal(modes_2d):
    M, K = modes_2d.model.mass, modes_2d.model.stiffness
    phi = modes_2d.shapes
    # the shapes are zero on the clamped DOFs, so the full M applies; eigsh's tol = 1e-10
    assert np.allclose(phi @ M @ phi.T, np.eye(len(phi)), atol=1e-8)
    omega2 = (2 * np.pi * modes_2d.frequencies_hz) ** 2
    assert np.allclose(phi @ K @ phi.T, np.diag(omega2), atol=1e-8 * omega2.max())


def test_3d_bending_in_both_planes_and_torsion(steel, modes_3d):
    frac = modes_3d.effective_mass_fraction
    f = modes_3d.frequencies_hz
    G = steel.E / (2 * (1 + steel.nu))
    A = H * W
    by_y = [k for k in range(8) if frac[k].max() > 1e-2 and modes_3d.dominant_direction(k) == 1]
    by_z = [k for k in range(8) if frac[k].max() > 1e-2 and modes_3d.dominant_direction(k) == 2]
    twist = [k for k in range(8) if frac[k].max() < 1e-3]
    # bending in y (depth H) and in z (depth W): the first two of each, with their own I and
    # Timoshenko factors; the coarse P2 tet mesh (2 elements through W) adds < 0.5 %: allow 1 %
    for modes, I, depth in ((by_y, W * H**3 / 12, H), (by_z, H * W**3 / 12, W)):
        expected = (euler_bernoulli_hz(steel.E, steel.rho, I, A)
                    * timoshenko_factor(steel.E, steel.nu, depth))[:2]
        assert f[modes[:2]] == pytest.approx(expected, rel=0.01)
    # torsion: no translational effective mass; f = (1 / 4L) sqrt(G J / (rho Ip)) for a
    # clamped-free shaft. The clamp also stops the warping of the rectangular section, which
    # stiffens a boundary layer ~ the section size: O(H / L) = 5 % of the length at most,
    # measured ~0.6 % in frequency on a finer mesh, plus ~1 % discretisation error: allow 3 %
    assert len(twist) >= 1
    J = saint_venant_torsion_constant(H, W)
    Ip = (W * H**3 + H * W**3) / 12
    assert f[twist[0]] == pytest.approx(np.sqrt(G * J / (steel.rho * Ip)) / (4 * L), rel=0.03)
    # torsion must not be mistaken for bending: its frequency lies above the second z-bending mode
    assert f[twist[0]] > f[by_z[1]]


def test_free_body_has_rigid_modes_first(steel):
    model = Model(beam_2d(0.2, 0.05, 0.025), steel, PlaneStress(0.01), order=2)
    modes = solve_modes(model, 5)
    first_elastic = modes.frequencies_hz[3]
    # three rigid-body modes in 2-D at ~0 Hz; numerically omega^2 ~ eigsh tolerance * shift
    assert np.all(modes.frequencies_hz[:3] < 1e-3 * first_elastic)
    # the rigid modes carry the whole mass in x and y between them
    assert modes.effective_mass[:3].sum(axis=0) == pytest.approx([modes.total_mass] * 2, rel=1e-8)
    assert modes.total_mass == pytest.approx(steel.rho * 0.2 * 0.05 * 0.01, rel=1e-12)
