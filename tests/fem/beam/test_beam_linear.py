"""Linear statics: exactness of the cubic (IIE) element under end loads, the compliance
matrix of a cantilever tip, convergence of a tapered cantilever, stresses and reactions."""
import numpy as np
import pytest
from scipy.integrate import quad

from beam_models import cantilever
from flexfem.fem.beam import (BeamModel, NodalLoad, Section, beam_chain, beam_from_profile,
                              compliance, solve_beam_static)
from flexfem.fem.beam.supports import NodeFixed, NodePrescribed

L, W, T = 0.1, 0.01, 1e-3


def tip_compliance(E, A, I, length):
    return np.array([[length / (E * A), 0, 0],
                     [0, length**3 / (3 * E * I), length**2 / (2 * E * I)],
                     [0, length**2 / (2 * E * I), length / (E * I)]])


@pytest.mark.parametrize("n", [1, 3, 10])
def test_tip_compliance_is_exact(steel, n):
    model, tip = cantilever(steel, L, W, T, n=n)
    C = compliance(model, [NodeFixed(0)], tip)
    assert C == pytest.approx(tip_compliance(steel.E, W * T, W * T**3 / 12, L), rel=1e-10,
                              abs=1e-14)


def test_rotated_cantilever_compliance(steel):
    """The same cantilever along 30 degrees: C = R C_local R^T."""
    a = np.radians(30.0)
    mesh = beam_chain([(0, 0), (L * np.cos(a), L * np.sin(a))], Section.rect(W, T), 4)
    model = BeamModel(mesh.nodes, mesh.elements, mesh.sections, steel)
    R = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
    expected = R @ tip_compliance(steel.E, W * T, W * T**3 / 12, L) @ R.T
    assert compliance(model, [NodeFixed(0)], 4) == pytest.approx(expected, rel=1e-9, abs=1e-14)


def test_timoshenko_single_element_is_exact(steel):
    """Thick cantilever (L/h = 2): delta = P L^3 / 3EI + P L / (kappa G A) from one element."""
    h, P = 0.05, 1e3
    model, tip = cantilever(steel, L, W, h, n=1, shear=True)
    res = solve_beam_static(model, [NodeFixed(0)], [NodalLoad(tip, fy=P)])
    G, A, I = steel.E / 2.6, W * h, W * h**3 / 12
    delta = P * L**3 / (3 * steel.E * I) + P * L / (5 / 6 * G * A)
    assert res.q[tip, 1] == pytest.approx(delta, rel=1e-12)
    assert res.q[tip, 2] == pytest.approx(P * L**2 / (2 * steel.E * I), rel=1e-12)


def test_stress_reactions_and_prescribed_motion(steel):
    P = 2.0
    model, tip = cantilever(steel, L, W, T, n=8)
    res = solve_beam_static(model, [NodeFixed(0)], [NodalLoad(tip, fx=10.0, fy=P)])
    assert res.reactions[0] == pytest.approx([-10.0, -P, -P * L], rel=1e-12)
    sigma = 10.0 / (W * T) + P * L * 6 / (W * T**2)          # N/A + M c / I at the root
    assert res.max_stress == pytest.approx(sigma, rel=1e-12)
    element, xi, where = res.max_stress_location
    assert (element, xi) == (0, 0.0) and where == pytest.approx([0.0, 0.0])
    assert res.axial_force == pytest.approx(np.full(8, 10.0), rel=1e-12)
    # a prescribed tip deflection: reaction = stiffness 3EI/L^3 x delta
    delta = 1e-3
    res = solve_beam_static(model, [NodeFixed(0), NodePrescribed(tip, "y", delta)])
    assert res.reactions[tip][1] == pytest.approx(3 * steel.E * W * T**3 / 12 / L**3 * delta,
                                                  rel=1e-10)


def _tapered_tip(steel, n, tapered=True, shear=False):
    thickness = lambda s: T * (1.0 - 0.6 * s / L)
    if tapered:
        mesh = beam_from_profile((0, 0), (L, 0), thickness, W, n)
    else:  # constant sections at the element mid-points
        s = (np.arange(n) + 0.5) * L / n
        mesh = beam_chain(np.column_stack([np.linspace(0, L, n + 1), np.zeros(n + 1)]),
                          [Section.rect(W, thickness(si)) for si in s], 1)
    model = BeamModel(mesh.nodes, mesh.elements, mesh.sections, steel, shear=shear)
    res = solve_beam_static(model, [NodeFixed(0)], [NodalLoad(n, fy=1.0)])
    G = steel.E / (2 * (1 + steel.nu))
    bending = lambda x: (L - x)**2 / (steel.E * W * thickness(x)**3 / 12)
    shearing = lambda x: 1.0 / (5 / 6 * G * W * thickness(x)) if shear else 0.0
    truth = quad(lambda x: bending(x) + shearing(x), 0, L, epsabs=0, epsrel=1e-13)[0]
    return abs(res.q[n, 1] / truth - 1.0)


def test_tapered_elements_are_exact_in_statics(steel):
    """Tapered cantilever, t = t0 (1 - 0.6 s / L), tip load: the tapered element's stiffness
    is the inverse of its exact flexibility, so the tip deflection is the closed form
    int (L - x)^2 / EI dx (+ int dx / kappa G A with Timoshenko shear) with any number of
    elements, up to the 6-point quadrature of 1 / EI; constant-section steps converge at h^2."""
    for shear in (False, True):
        errors = [_tapered_tip(steel, n, shear=shear) for n in (1, 2, 4, 8, 32)]
        # measured: 3.6e-6 with one element (the quadrature of 1 / t^3 over a 2.5:1 taper),
        # 1.1e-8 with two, 1e-11 with four; the Hermite element before: 6.1e-4 with four
        assert errors[0] < 1e-5 and errors[1] < 1e-7 and max(errors[2:]) < 1e-10, (shear, errors)
    stepped = [_tapered_tip(steel, n, tapered=False) for n in (4, 8, 16, 32)]
    rate_s = np.log2(np.array(stepped[:-1]) / stepped[1:])
    # measured: 3.7e-2, 8.9e-3, 2.2e-3, 5.5e-4 (rates 2.03, 2.01, 2.00)
    assert np.all((rate_s > 1.8) & (rate_s < 2.3)), (stepped, rate_s)


def test_circular_notch_hinge_rotational_compliance(steel):
    """A circular notch hinge (radius R, waist t_min) from beam_from_profile converges to the
    beam-theory compliance theta / M = 12 / (E w) int ds / t(s)^3 (Paros & Weisbord's exact
    integral), evaluated here by quadrature, with and without Timoshenko shear (a pure
    moment shears nothing; the interpolated Timoshenko element this replaced was 1.4 % stiff
    with 40 elements)."""
    R, t_min, w = 2e-3, 0.1e-3, 5e-3
    profile = lambda s: t_min + 2 * R - 2 * np.sqrt(max(R**2 - (s - R)**2, 0.0))
    exact = 12 / (steel.E * w) * quad(lambda s: profile(s)**-3, 0, 2 * R, points=[R],
                                      epsabs=0, epsrel=1e-12, limit=200)[0]
    for shear in (False, True):
        errors = []
        for n in (10, 20, 40):
            mesh = beam_from_profile((0, 0), (2 * R, 0), profile, w, n)
            model = BeamModel(mesh.nodes, mesh.elements, mesh.sections, steel, shear=shear)
            errors.append(compliance(model, [NodeFixed(0)], n)[2, 2] / exact - 1)
        # the thickness quadratic within each element; measured 7.0e-4, 3.4e-5, 2.1e-6 (the
        # Hermite element before: -7.0e-3, -1.3e-3, -9.1e-5)
        assert abs(errors[1]) < 1e-4 and abs(errors[2]) < 1e-5, (shear, errors)
        assert abs(errors[2]) < abs(errors[1]) < abs(errors[0]), (shear, errors)
