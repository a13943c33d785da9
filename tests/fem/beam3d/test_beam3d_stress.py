"""Stresses of the spatial beam model (fem/beam/spatial/stress.py): Saint-Venant's torsion shear of
a rectangle against Timoshenko & Goodier's table, a cantilever's section stresses against
statics, and both against flexfem's 3-D continuum at mid-span."""
import numpy as np
import pytest
import skfem

from beam3d_models import straight
from flexfem.data import load_toml
from flexfem.fem import Fixed as ContinuumFixed
from flexfem.fem import Force, Model, Solid3D, Traction, solve_static
from flexfem.fem.beam.spatial import NodalLoad, Section, solve_beam3d_static
from flexfem.fem.beam.supports import NodeFixed
from flexfem.fem.beam.section import rect_torsion_constant, rect_torsion_shear
from flexfem.fem.beam.spatial.stress import section_stresses
from flexfem.fem.mesh import FEMesh, facets_where

L, B, H = 0.2, 0.02, 0.01  # m: length, depth along local y, along local z
N, FY, FZ, TORQUE = 2000.0, 30.0, -20.0, 5.0  # N, N m


def test_torsion_shear_and_constant_of_rectangles_are_timoshenko_goodier():
    ref = load_toml("beam3d_benchmarks.toml")["rect_torsion"]
    a = np.array(ref["a_over_b"])
    # the table's three digits: tau_max = T / (k2 a b^2), J = k1 a b^3
    assert np.allclose(1.0 / (rect_torsion_shear(a, 1.0) * a), ref["k2"], atol=6e-4)
    assert np.allclose(rect_torsion_constant(a, 1.0) / a, ref["k1"], atol=6e-4)
    # thin strip: tau_max -> 3 T / (a t^2)
    assert rect_torsion_shear(1000.0, 1.0) * 1000.0 / 3.0 == pytest.approx(1.0, rel=1e-3)


def test_cantilever_section_stresses_are_statics(steel):
    """Tip loads on a cantilever: at distance s from the tip the moments are F s, so along
    element e the normal stress is N/A + |F_z| s H / (2 I_y) + |F_y| s B / (2 I_z) and the
    torsion shear is T times the rectangle's factor, at every point."""
    section = Section.rect(H, B)
    model, tip = straight(steel, section, length=L, n=4)
    state = solve_beam3d_static(model, [NodeFixed(0)], [NodalLoad(tip, fx=N, fy=FY, fz=FZ,
                                                              mx=TORQUE)])
    stresses = state.stresses(n_points=3)
    x = (np.arange(4)[:, None] + stresses["xi"][None, :]) * L / 4  # along the beam
    s = L - x
    normal = N / section.A + abs(FZ) * s * H / (2 * section.Iy) + abs(FY) * s * B / (2 * section.Iz)
    assert np.allclose(stresses["normal"], normal, rtol=1e-9)
    assert np.allclose(stresses["torsion"], TORQUE * rect_torsion_shear(B, H), rtol=1e-9)
    assert state.max_stress == pytest.approx(np.sqrt(normal.max() ** 2 + 3 * (
        TORQUE * rect_torsion_shear(B, H)) ** 2), rel=1e-12)


def test_general_sections_have_no_stress(steel):
    section = Section(A=1e-4, Iy=1e-9, Iz=2e-9, J=5e-10)
    model, tip = straight(steel, section, length=L, n=2)
    state = solve_beam3d_static(model, [NodeFixed(0)], [NodalLoad(tip, fz=1.0)])
    assert np.all(np.isnan(section_stresses(model, state.local_forces)["normal"]))
    assert np.isnan(state.max_stress)


def test_mid_span_stresses_beside_the_3d_continuum(steel):
    """A 200 x 20 x 10 mm bar, 40 x 6 x 3 Q2 hexahedra, clamped, tip face loaded by the same
    resultants (a uniform traction for the forces, one linear in position for the torque):
    at mid-span, far from both ends, the continuum's sigma_xx at the corner where the three
    normal stresses add up and its shear at the middle of a long side (torque alone) agree
    with the beam's within 1 % (measured +0.06 % and +0.67 %; on 40 x 10 x 5 elements +0.08 %
    and +0.24 %: the shear converges to Saint-Venant's)."""
    m = skfem.MeshHex.init_tensor(np.linspace(0, L, 41), np.linspace(-B / 2, B / 2, 7),
                                  np.linspace(-H / 2, H / 2, 4))
    mesh = FEMesh(m, {"fixed": facets_where(m, lambda x: np.isclose(x[0], 0.0)),
                      "tip": facets_where(m, lambda x: np.isclose(x[0], L))})
    model = Model(mesh, steel, Solid3D(), order=2)
    polar = B * H * (B**2 + H**2) / 12.0  # int (y^2 + z^2) dA, m^4
    twist = lambda x: TORQUE / polar * np.stack([0 * x[0], -x[2], x[1]])
    bent = solve_static(model, [ContinuumFixed("fixed")], [Force("tip", (N, FY, FZ))])
    twisted = solve_static(model, [ContinuumFixed("fixed")], [Traction("tip", twist)])
    # sigma_xx adds up at y = -B/2 (F_y bends towards +y: the -y side is in tension at the
    # root side of the load), z = +H/2 (F_z < 0: +z in tension)
    corner = bent.stress_at([[L / 2, -B / 2, H / 2]])[0, 0, 0]
    long_side = twisted.stress_at([[L / 2, 0.0, H / 2]])[0]  # the middle of a long side
    tau = np.hypot(long_side[0, 1], long_side[0, 2])

    beam, tip = straight(steel, Section.rect(H, B), length=L, n=2, shear=True)
    state = solve_beam3d_static(beam, [NodeFixed(0)], [NodalLoad(tip, fx=N, fy=FY, fz=FZ)])
    normal = state.stresses(n_points=2)["normal"][1, 0]  # mid-span: the second element's start
    torsion = solve_beam3d_static(beam, [NodeFixed(0)], [NodalLoad(tip, mx=TORQUE)]).stresses(
        n_points=2)["torsion"][1, 0]
    assert corner == pytest.approx(normal, rel=0.01)
    assert tau == pytest.approx(torsion, rel=0.01)
