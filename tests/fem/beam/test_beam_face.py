"""The continuum's analysis face on a beam model with groups, checked against beam theory."""
import math

import numpy as np
import pytest

from flexfem.fem import (Fixed, Force, Gravity, Prescribed, Rayleigh, compliance_matrix,
                         material, solve_buckling, solve_harmonic, solve_modes,
                         solve_nonlinear, solve_static)
from flexfem.fem.beam import BeamGroup, BeamModel, Section, beam_chain

L, W, T, N = 0.05, 0.01, 0.5e-3, 40
STEEL = material("structural_steel")
EI = STEEL.E * W * T ** 3 / 12


def cantilever(tip_span=(0.0, 0.0)) -> BeamModel:
    mesh = beam_chain([(0, 0), (L, 0)], Section.rect(W, T), N)
    return BeamModel(mesh.nodes, mesh.elements, mesh.sections, STEEL,
                     groups={"root": [0], "tip": BeamGroup(N, tip_span)})


def test_static_by_group_matches_beam_theory():
    model = cantilever()
    r = solve_static(model, [Fixed("root")], [Force("tip", (0.0, -1.0))])
    assert r.mean_displacement("tip")[1] == pytest.approx(-L ** 3 / (3 * EI), rel=1e-9)
    assert r.reactions["root"] == pytest.approx([0.0, 1.0], abs=1e-9)
    assert r.max_von_mises == pytest.approx(1.0 * L * T / 2 / (W * T ** 3 / 12), rel=1e-9)
    assert r.max_von_mises_location == pytest.approx([0.0, 0.0], abs=1e-12)


def test_prescribed_on_a_spanning_face_holds_its_rotation():
    """x held on a face that spans y: the face cannot turn, so a y force bends the leaf as a
    guided one (k = 12 EI / L^3); on a point the rotation stays free (3 EI / L^3)."""
    for span, k in (((0.0, 0.004), 12 * EI / L ** 3), ((0.0, 0.0), 3 * EI / L ** 3)):
        model = cantilever(span)
        r = solve_static(model, [Fixed("root"), Prescribed("tip", x=0.0)],
                         [Force("tip", (0.0, 1.0))])
        assert 1.0 / r.mean_displacement("tip")[1] == pytest.approx(k, rel=1e-9)


def test_modes_compliance_and_nonlinear_by_group():
    model = cantilever()
    m = STEEL.rho * W * T
    f1 = 1.8751 ** 2 / (2 * math.pi) * math.sqrt(EI / (m * L ** 4))
    modes = solve_modes(model, 2, [Fixed("root")])
    assert modes.frequencies_hz[0] == pytest.approx(f1, rel=1e-4)
    c = compliance_matrix(model, [Fixed("root")], "tip")
    assert c.matrix[1, 1] == pytest.approx(L ** 3 / (3 * EI), rel=1e-9)
    assert c.matrix[2, 2] == pytest.approx(L / EI, rel=1e-9)
    moved = compliance_matrix(model, [Fixed("root")], "tip", point=(0.0, 0.0))
    assert moved.matrix[1, 1] == pytest.approx(L ** 3 / (3 * EI) - 2 * L * L ** 2 / (2 * EI)
                                               + L ** 2 * L / EI, rel=1e-9)
    small = solve_nonlinear(model, [Fixed("root")], [Force("tip", (0.0, -1e-4))], steps=2)
    assert small.mean_displacement("tip")[1] == pytest.approx(-1e-4 * L ** 3 / (3 * EI),
                                                               rel=1e-5)
    assert small.reactions[-1]["root"] == pytest.approx([0.0, 1e-4], abs=1e-12)


def test_harmonic_static_limit_and_resonance():
    model = cantilever()
    f1 = solve_modes(model, 1, [Fixed("root")]).frequencies_hz[0]
    freqs = np.concatenate([[0.0], np.linspace(0.8 * f1, 1.2 * f1, 401)])
    h = solve_harmonic(model, [Fixed("root")], [Force("tip", (0.0, 1.0))], freqs,
                       damping=0.01, n_modes=6)
    frf = h.frf("tip", "y")
    assert frf.response[0].real == pytest.approx(L ** 3 / (3 * EI), rel=1e-9)
    assert frf.peaks()[0] == pytest.approx(f1 * math.sqrt(1 - 2 * 0.01 ** 2), rel=1e-3)
    rayleigh = solve_harmonic(model, [Fixed("root")], [Force("tip", (0.0, 1.0))], [0.0],
                              damping=Rayleigh(0.0, 1e-6))
    assert rayleigh.frf("tip", 1).response[0].real == pytest.approx(L ** 3 / (3 * EI), rel=1e-9)


def test_a_rigid_face_of_the_static_solve_carries_its_moment_and_holds_its_values():
    """A pure moment M on the tip's rigid face turns it by M L / EI; with the face's
    rotation held instead, a tip force bends the leaf as a guided one (12 EI / L^3)."""
    from flexfem.fem import RigidFace

    model = cantilever()
    turned = solve_static(model, [Fixed("root")], [], rigid_faces=[RigidFace("tip", moment=1.0)])
    assert turned.face_motion["tip"] == pytest.approx([0.0, L ** 2 / (2 * EI), L / EI],
                                                      rel=1e-9, abs=1e-15)
    guided = solve_static(model, [Fixed("root")], [],
                          rigid_faces=[RigidFace("tip", rotation=0.0, force=(0.0, 1.0))])
    assert guided.face_motion["tip"][1] == pytest.approx(L ** 3 / (12 * EI), rel=1e-9)


def test_what_the_beam_model_cannot_take_is_named():
    model = cantilever()
    with pytest.raises(ValueError, match="'nowhere' is not one of"):
        solve_static(model, [Fixed("nowhere")], [])
    with pytest.raises(ValueError, match="continuum's"):
        solve_static(model, [Fixed("root")], [Gravity((0.0, -9.81))])
    with pytest.raises(ValueError, match="takes 2-D RigidFace"):
        solve_static(model, [Fixed("root")], [], rigid_faces=[object()])
    with pytest.raises(ValueError, match="no beam in compression"):
        solve_buckling(model, [Fixed("root")], [Force("tip", (1.0, 0.0))])
    with pytest.raises(ValueError, match="outside"):
        model.add_group("bad", [N + 5])
