"""The material library and the elastic constants derived from it."""
import math

import numpy as np
import pytest
from meshes import beam_2d
from flexfem.data import load_toml
from flexfem.fem import (
    Material,
    Model,
    PlaneStrain,
    PlaneStress,
    material,
    material_names,
)


def test_library_entries_are_valid_and_sourced():
    names = material_names()
    assert names == sorted(load_toml("materials.toml"))
    assert {"structural_steel", "aluminium_6061_t6"} <= set(names)
    for name in names:
        m = material(name)  # runs the validation of every entry
        assert m.name == name and len(m.source) > 20
        # handbook ranges of engineering solids: E 1 MPa - 1.2 TPa, rho 500 - 23000 kg/m^3
        assert 1e6 < m.E < 1.2e12 and 500 < m.rho < 23000
        assert isinstance(m.E, float) and isinstance(m.rho, float)


def test_library_values_are_the_table_values():
    table = load_toml("materials.toml")["structural_steel"]
    steel = material("structural_steel")
    assert (steel.E, steel.nu, steel.rho, steel.yield_strength) == (
        table["E"], table["nu"], table["rho"], table["yield_strength"])


def test_unknown_material_lists_the_known_ones():
    with pytest.raises(ValueError, match="unknown material 'unobtainium'; known: .*structural_steel"):
        material("unobtainium")


def test_lame_parameters():
    m = Material("m", E=210e9, nu=0.25, rho=1.0)
    lam, mu = m.lame
    # nu = 1/4 is the Poisson solid: lambda = mu = E / 2.5
    assert lam == pytest.approx(210e9 / 2.5, rel=1e-14)
    assert mu == pytest.approx(210e9 / 2.5, rel=1e-14)
    # and they give back E and nu: E = mu (3 lam + 2 mu) / (lam + mu), nu = lam / (2 (lam + mu))
    for nu in (-0.5, 0.0, 0.3, 0.49):
        lam, mu = Material("m", E=1.0, nu=nu, rho=1.0).lame
        assert mu * (3 * lam + 2 * mu) / (lam + mu) == pytest.approx(1.0, rel=1e-12)
        assert lam / (2 * (lam + mu)) == pytest.approx(nu, abs=1e-12)


def test_plane_stress_lambda_gives_the_plane_stress_law():
    """Plane stress: sigma = E / (1 - nu^2) [[1, nu], [nu, 1]] eps; with lambda* = 2 lam mu /
    (lam + 2 mu) the 2-D law 2 mu eps + lambda* tr(eps) I gives exactly that."""
    m = Material("m", E=70e9, nu=0.33, rho=2700.0)
    mesh = beam_2d(1.0, 0.1, 0.1)
    lam_s, mu = Model(mesh, m, PlaneStress(0.01)).lame
    lam_e, _ = Model(mesh, m, PlaneStrain()).lame
    assert lam_e == pytest.approx(m.lame[0], rel=1e-14)
    assert lam_s + 2 * mu == pytest.approx(m.E / (1 - m.nu**2), rel=1e-12)
    assert lam_s == pytest.approx(m.E * m.nu / (1 - m.nu**2), rel=1e-12)


def test_numbers_of_any_real_type_are_accepted_and_stored_as_float():
    m = Material("m", E=np.float32(1e9), nu=np.float64(0.3), rho=np.int64(1000))
    assert type(m.E) is float and type(m.nu) is float and type(m.rho) is float
    assert m.yield_strength == math.inf  # no failure stress given
    assert m.as_dict()["E"] == pytest.approx(1e9)


def test_material_is_frozen():
    m = material("structural_steel")
    with pytest.raises(AttributeError):
        m.E = 1.0


def test_the_flexure_materials_are_there_and_consistent():
    flexure = {"spring_steel_aisi1095", "maraging_steel_300", "titanium_ti6al4v",
               "beryllium_copper_c17200", "aluminium_7075_t6", "silicon_110", "invar_36"}
    assert flexure <= set(material_names())
    for name in flexure:
        m = material(name)
        assert m.yield_strength <= m.ultimate_strength, name
        if m.fatigue_strength is not None:  # an amplitude a polished specimen survives
            assert m.fatigue_strength < m.ultimate_strength and m.fatigue_cycles >= 1e6, name
