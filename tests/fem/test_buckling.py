"""Verification of linear buckling (flexfem.fem.buckling): Euler's loads of the four classic
end conditions on a slender strip (L / H = 100, plane stress, P2 triangles)."""
import numpy as np
import pytest
import skfem

from flexfem.fem import Fixed, Force, Material, Model, PlaneStress, Prescribed
from flexfem.fem.buckling import solve_buckling
from flexfem.fem.mesh import FEMesh, facets_where

L, H, T = 1.0, 0.01, 0.01  # m
E_MOD = 200e9  # Pa
EI = E_MOD * T * H ** 3 / 12
STEEL = Material("test steel", E=E_MOD, nu=0.3, rho=7800.0, yield_strength=250e6)


def strip(length, nx):
    """[0, length] x [0, H] (m), P2 triangles, groups left (x = 0) and right (x = length)."""
    m = skfem.MeshTri.init_tensor(np.linspace(0, length, nx + 1), np.linspace(0, H, 3))
    groups = {"left": facets_where(m, lambda x: np.isclose(x[0], 0.0)),
              "right": facets_where(m, lambda x: np.isclose(x[0], length))}
    return Model(FEMesh(m, groups), STEEL, PlaneStress(T), order=2)


# y held on a whole end section leaves the section free to rotate (a pin); x held on it
# stops the rotation (a clamp). Symmetric first modes are computed on half the column with
# the mid-span section's x held (pinned-pinned) or prescribed (fixed-fixed: the critical
# load is the load factor times the reaction of that shortening).
CASES = {
    "fixed-free": (L, 100, [Fixed("left")], np.pi ** 2 / 4),
    "pinned-pinned": (L / 2, 50, [Prescribed("left", x=0.0), Prescribed("right", y=0.0)], np.pi ** 2),
    "fixed-pinned": (L, 100, [Fixed("left"), Prescribed("right", y=0.0)], 4.493409 ** 2),
    "fixed-fixed": (L / 2, 50, [Fixed("left"), Prescribed("right", x=-1e-6)], 4 * np.pi ** 2),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_euler_buckling_loads(case):
    # P_cr = c EI / L^2 (c: pi^2/4, pi^2, 20.19 = 4.4934^2, 4 pi^2). The continuum's shear
    # lowers it by ~pi^2 E H^2 / (12 kappa G L_e^2) <= 0.1 % here, the mesh by less:
    # measured 0.03 %, -0.26 %, -0.21 %, -0.05 %; 1 % allowed
    length, nx, supports, c = CASES[case]
    model = strip(length, nx)
    driven = case == "fixed-fixed"
    loads = [] if driven else [Force("right", (-1.0, 0.0))]
    result = solve_buckling(model, supports, loads, n=2)
    critical = abs(result.critical_reaction("left")[0]) if driven else result.load_factors[0]
    assert critical == pytest.approx(c * EI / L ** 2, rel=0.01)
    assert np.all(np.diff(result.load_factors) > 0)
    assert np.abs(result.shapes).max() == pytest.approx(1.0)


def test_higher_modes_and_export(tmp_path):
    # fixed-free: P_n = (2n - 1)^2 P_1; to 1 % as above
    model = strip(L, 100)
    result = solve_buckling(model, [Fixed("left")], [Force("right", (-1.0, 0.0))], n=3)
    assert result.load_factors / result.load_factors[0] == pytest.approx([1, 9, 25], rel=0.01)
    path = result.write(tmp_path / "buckling.vtu")
    assert path.stat().st_size > 0


def test_tension_buckles_only_at_absurd_factors():
    # pulled, the strip is compressed only across its width near the clamp (Poisson): the
    # only positive factors are ~1e8, i.e. stresses of ~1e12 Pa, against 412 in compression
    model = strip(L, 20)
    pulled = solve_buckling(model, [Fixed("left")], [Force("right", (1.0, 0.0))])
    assert pulled.load_factors[0] > 1e5 * np.pi ** 2 * EI / (4 * L ** 2)
    with pytest.raises(ValueError, match="unstressed"):
        solve_buckling(model, [Fixed("left")], [])
    with pytest.raises(ValueError, match="n = 0"):
        solve_buckling(model, [Fixed("left")], [Force("right", (-1.0, 0.0))], n=0)
