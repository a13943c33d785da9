"""Stroke limits: a fixed-guided leaf's yield- and fatigue-limited stroke against beam theory
and the Goodman and Soderberg lines worked by hand; a sharp root's stress is singular (it grows
under refinement) and is not used, a filleted root's converges and is."""
import math
from pathlib import Path

import pytest
from flexfem.fem import material
from flexfem.fem.fatigue import fatigue_stroke, yield_stroke
from flexfem.geometry.user_model import load_spec
from flexfem.studies.user_model.analysis import analyze_model, evaluate

GUIDE = Path(__file__).parents[3] / "examples" / "bodies" / "guide.toml"


def _filleted(tmp_path, fillet: float) -> Path:
    path = tmp_path / "guide.toml"
    path.write_text(GUIDE.read_text().replace('thickness = "t"',
                                              f'thickness = "t"\nfillet = {fillet}'))
    return path


def test_fixed_guided_leaf_by_hand():
    """Each leaf of the guide bends as a fixed-guided beam: at a lateral stroke d its root
    bending stress is 3 E t d / L^2; the lateral force F, applied at the stage's point y_F, also
    pushes and pulls the two leaves (d apart) with N = F (y_F - L/2) / d about their
    inflection points. Euler-Bernoulli beams (no shear, no root extension) give exactly that;
    it yields at d = Sy / (n s), s the stress per stroke, and Goodman allows the amplitude
    d_a = Se (1/n - s d_m / Sut) / s."""
    overrides = {"beam_model.root_extension": 0.0, "beam_model.shear": False,
                 "analysis.safety_factor": 1.5, "analysis.mean_stroke": 2e-4}
    spec = load_spec(GUIDE, overrides)
    out = analyze_model(spec, model="beam")
    E, L, t, d = (spec.material.E, spec.constants["L"], spec.constants["t"],
                  spec.constants["d"])
    w = spec.section.thickness
    stroke = 1.0 * L ** 3 / (24 * E * w * t ** 3 / 12)  # F = 1 N
    y_force = spec.beams.rigid[1].groups["stage"][1]
    axial = 1.0 * (y_force - L / 2) / d / (w * t)
    s = 3 * E * t / L ** 2 + axial / stroke
    assert out["stress_per_stroke"] == pytest.approx(s, rel=5e-3)  # the leaves' stretch: 0.4 %
    steel = spec.material
    assert out["stroke_limit_yield"] == pytest.approx(steel.yield_strength / (1.5 * s), rel=5e-3)
    per = out["stress_per_stroke"]
    by_hand = steel.fatigue_strength * (1 / 1.5 - per * 2e-4 / steel.ultimate_strength) / per
    assert out["stroke_limit_fatigue"] == pytest.approx(by_hand, rel=1e-12)
    assert out["fatigue_cycles"] == steel.fatigue_cycles and "Shigley" in out["fatigue_source"]


def test_goodman_and_soderberg_lines():
    steel = material("structural_steel")  # Sy 250, Sut 400, Se 200 MPa
    s = 1e9  # Pa per m of stroke
    assert yield_stroke(s, steel.yield_strength, 2.0) == pytest.approx(0.125)
    assert fatigue_stroke(s, steel, 0.0) == pytest.approx(0.2)            # fully reversed
    assert fatigue_stroke(s, steel, 0.2) == pytest.approx(0.2 * (1 - 0.2 / 0.4))
    assert fatigue_stroke(s, steel, 0.2, "soderberg") == pytest.approx(0.2 * (1 - 0.2 / 0.25))
    assert fatigue_stroke(s, steel, 0.5) == 0.0                            # the mean uses it up
    assert fatigue_stroke(s, material("silicon_110")) is None              # no fatigue data


def _peak(path, size_factor):
    return evaluate({}, file=str(path), size_factor=size_factor)["max_von_mises"]


def test_a_sharp_root_is_singular_and_not_used(tmp_path):
    coarse, fine = _peak(GUIDE, 1.0), _peak(GUIDE, 0.5)
    assert fine / coarse > 1.1  # grows with refinement: a singularity, not a stress
    out = analyze_model(load_spec(GUIDE))
    assert "singular" in out["stroke_stress_basis"]
    nominal = analyze_model(load_spec(GUIDE), model="beam")
    assert out["stroke_limit_yield"] == pytest.approx(nominal["stroke_limit_yield"], rel=1e-9)


@pytest.mark.parametrize("fillet", [0.001, 0.0005])
def test_a_filleted_root_converges_to_the_published_concentration(tmp_path, fillet):
    """A fillet of radius r where a leaf of thickness t meets its body is a deep shoulder
    fillet: the peak is K_t (Roark's Table 17.1, case 17, fits to Peterson's charts) times
    the nominal stress where the straight leaf begins, r from the root: bending
    6 (F/2)(L/2 - r) / (w t^2) and the push-pull N / (w t), N = F (y_F - L/2) / d. The
    continuum converges to it (within 1 % on refinement, within 5 % of the fit), and the
    stroke limits are sized by it."""
    from flexfem.studies.dbma.beam_stress import shoulder_fillet_kt

    path = _filleted(tmp_path, fillet)
    coarse, fine = _peak(path, 1.0), _peak(path, 0.5)
    assert abs(fine / coarse - 1) < 0.01
    spec = load_spec(path)
    L, t, d, w = (spec.constants["L"], spec.constants["t"], spec.constants["d"],
                  spec.section.thickness)
    y_force = spec.beams.rigid[1].groups["stage"][1]
    deep = t + 2 * 40 * fillet  # a shoulder deeper than the fit's range: K_t saturated
    bending = shoulder_fillet_kt(t, deep, fillet, "bending") * 6 * 0.5 * (L / 2 - fillet)
    tension = shoulder_fillet_kt(t, deep, fillet, "tension") * (y_force - L / 2) / d * t
    published = (bending + tension) / (w * t ** 2)
    assert fine == pytest.approx(published, rel=0.05)
    out = analyze_model(spec)
    assert "converges under refinement" in out["stroke_stress_basis"]
    assert out["max_von_mises"] == pytest.approx(coarse, rel=1e-12)
    u = out["mean_displacement"]["stage"][0]
    assert out["stroke_limit_yield"] == pytest.approx(spec.material.yield_strength * u / coarse,
                                                      rel=1e-9)
    assert math.isfinite(out["stroke_limit_fatigue"])
