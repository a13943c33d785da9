"""The continuum's analysis face on a spatial beam model with groups, checked against beam
theory (a cantilever along x: in-plane bending in y, out-of-plane bending in z, torsion)."""
import math

import numpy as np
import pytest

from flexfem.fem import (Fixed, Force, Prescribed, compliance_matrix, material,
                         solve_buckling, solve_harmonic, solve_modes, solve_nonlinear,
                         solve_static)
from flexfem.fem.beam import BeamGroup, BeamModel, Section as PlanarSection, beam_chain
from flexfem.fem.beam.spatial import Beam3DModel, Section
from flexfem.fem.beam.face import held_rotations
from flexfem.reduced.spatial import lifted_model

L, W, T, N = 0.05, 0.01, 0.5e-3, 40
STEEL = material("structural_steel")
EI_IN = STEEL.E * W * T ** 3 / 12     # bending in y (in the plane)
EI_OUT = STEEL.E * T * W ** 3 / 12    # bending in z (out of it)


def cantilever(tip_span=(0.0, 0.0, 0.0)) -> Beam3DModel:
    x = np.linspace(0.0, L, N + 1)
    nodes = np.column_stack([x, np.zeros_like(x), np.zeros_like(x)])
    elements = np.column_stack([np.arange(N), np.arange(1, N + 1)])
    return Beam3DModel(nodes, elements, Section.rect(W, T), STEEL,
                       groups={"root": [0], "tip": BeamGroup(N, tip_span)})


def test_static_by_group_matches_beam_theory_in_and_out_of_the_plane():
    model = cantilever()
    out = solve_static(model, [Fixed("root")], [Force("tip", (0.0, 0.0, -1.0))])
    assert out.mean_displacement("tip") == pytest.approx([0.0, 0.0, -L ** 3 / (3 * EI_OUT)],
                                                         rel=1e-9, abs=1e-15)
    assert out.reactions["root"] == pytest.approx([0.0, 0.0, 1.0], abs=1e-9)
    assert out.max_von_mises == pytest.approx(L * (W / 2) / (T * W ** 3 / 12), rel=1e-9)
    assert out.max_von_mises_location == pytest.approx([0.0, 0.0, 0.0], abs=1e-12)
    planar_force = solve_static(model, [Fixed("root")], [Force("tip", (0.0, -1.0))])
    assert planar_force.mean_displacement("tip")[1] == pytest.approx(-L ** 3 / (3 * EI_IN),
                                                                      rel=1e-9)


def test_a_held_translation_holds_the_rotations_its_face_spans():
    """x held on a face spanning y holds the turn about z (e_x x e_y): a y force then bends
    the beam as a guided one (12 EI / L^3) while a z force still sees the free tip (3 EI /
    L^3); on a face spanning z it is the other way round."""
    assert held_rotations(0, (0.0, 0.004, 0.0)) == [2]
    assert held_rotations(0, (0.0, 0.004, 0.01)) == [1, 2]
    assert held_rotations(2, (0.004, 0.0, 0.0)) == [1]
    cases = (((0.0, 0.004, 0.0), 12 * EI_IN, 3 * EI_OUT),
             ((0.0, 0.0, 0.004), 3 * EI_IN, 12 * EI_OUT),
             ((0.0, 0.0, 0.0), 3 * EI_IN, 3 * EI_OUT))
    for span, k_y, k_z in cases:
        model = cantilever(span)
        held = [Fixed("root"), Prescribed("tip", x=0.0)]
        u_y = solve_static(model, held, [Force("tip", (0.0, 1.0, 0.0))]).mean_displacement("tip")
        u_z = solve_static(model, held, [Force("tip", (0.0, 0.0, 1.0))]).mean_displacement("tip")
        assert 1.0 / u_y[1] == pytest.approx(k_y / L ** 3, rel=1e-9)
        assert 1.0 / u_z[2] == pytest.approx(k_z / L ** 3, rel=1e-9)


def test_modes_compliance_nonlinear_and_harmonic_by_group():
    model = cantilever()
    m = STEEL.rho * W * T
    f_in = 1.8751 ** 2 / (2 * math.pi) * math.sqrt(EI_IN / (m * L ** 4))
    modes = solve_modes(model, 2, [Fixed("root")])
    assert modes.frequencies_hz[0] == pytest.approx(f_in, rel=1e-4)
    assert modes.effective_mass.shape == (2, 3)
    assert modes.effective_mass[0, 1] == pytest.approx(0.613 * m * L, rel=2e-3)
    c = compliance_matrix(model, [Fixed("root")], "tip")
    G = STEEL.E / (2 * (1 + STEEL.nu))
    J = Section.rect(W, T).J
    assert np.diag(c.matrix) == pytest.approx(
        [L / (STEEL.E * W * T), L ** 3 / (3 * EI_IN), L ** 3 / (3 * EI_OUT), L / (G * J),
         L / EI_OUT, L / EI_IN], rel=1e-9)
    moved = compliance_matrix(model, [Fixed("root")], "tip", point=(0.0, 0.0, 0.0))
    assert moved.matrix[2, 2] == pytest.approx(L ** 3 / (3 * EI_OUT) - L ** 3 / EI_OUT
                                               + L ** 3 / EI_OUT, rel=1e-9)
    small = solve_nonlinear(model, [Fixed("root")], [Force("tip", (0.0, 0.0, -1e-3))], steps=2)
    assert small.mean_displacement("tip")[2] == pytest.approx(-1e-3 * L ** 3 / (3 * EI_OUT),
                                                               rel=1e-5)
    assert small.reactions[-1]["root"] == pytest.approx([0.0, 0.0, 1e-3], abs=1e-10)
    h = solve_harmonic(model, [Fixed("root")], [Force("tip", (0.0, 1.0, 0.0))],
                       [0.0, 0.999 * f_in, 1.001 * f_in], damping=0.0)
    assert h.frf("tip", "y").response[0].real == pytest.approx(L ** 3 / (3 * EI_IN), rel=1e-9)
    below, above = h.frf("tip", 1).response[1:].real
    assert below > 100 * L ** 3 / (3 * EI_IN) and above < 0  # through the first resonance


def test_a_lifted_planar_model_keeps_its_groups_and_its_in_plane_answers():
    """The spatial lift of a grouped planar cantilever: the same groups (a face of some extent
    spans the depth too) and the same in-plane tip stiffness as the planar face gives."""
    mesh = beam_chain([(0, 0), (L, 0)], PlanarSection.rect(W, T), N)
    planar = BeamModel(mesh.nodes, mesh.elements, mesh.sections, STEEL,
                       groups={"root": [0], "tip": BeamGroup(N, (0.0, 0.004))})
    spatial = lifted_model(planar, W)
    assert spatial.groups["tip"].span == (0.0, 0.004, W)
    assert spatial.groups["root"].span == (0.0, 0.0, 0.0)
    held = [Fixed("root"), Prescribed("tip", x=0.0)]
    u2 = solve_static(planar, held, [Force("tip", (0.0, 1.0))]).mean_displacement("tip")
    u3 = solve_static(spatial, held, [Force("tip", (0.0, 1.0))]).mean_displacement("tip")
    assert u3[:2] == pytest.approx(u2, rel=1e-9, abs=1e-15)


def test_bad_input_on_the_spatial_face_names_the_problem():
    model = cantilever()
    with pytest.raises(ValueError, match="'stage' is not one of"):
        solve_static(model, [Fixed("stage")])
    with pytest.raises(ValueError, match="takes \\(F_x, F_y\\) or \\(F_x, F_y, F_z\\)"):
        solve_static(model, [Fixed("root")], [Force("tip", (0.0, 0.0, 1.0, 0.0))])
    with pytest.raises(TypeError, match="rigid_faces"):
        solve_nonlinear(model, [Fixed("root")], [Force("tip", (0.0, 1.0))], rigid_faces=["tip"])
    with pytest.raises(ValueError, match="no beam in compression"):
        solve_buckling(model, [Fixed("root")], [Force("tip", (1.0, 0.0))])
