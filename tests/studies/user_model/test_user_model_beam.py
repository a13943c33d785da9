"""The beam model a model file declares ([[beam]], [[rigid]]): the examples' parallel guide and
cross pivot against closed forms (24 E I / L^3 and the exact two-leaf frame; 8 E I / L) and
against the continuum FEM of the same file; the same keys from analyze, evaluate, the CLI and a
study; errors that name the file and line."""
import argparse
import json
import math
from pathlib import Path

import numpy as np
import pytest

from flexfem.geometry.user_model import load_spec
from flexfem.studies.engine.validate import normalise_options
from flexfem.studies.mechanisms import get_evaluator, model_mechanism
from flexfem.studies.user_model import analyze_model, cli, evaluate

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
GUIDE = EXAMPLES / "parallel_guide" / "guide.toml"
PIVOT = EXAMPLES / "cross_pivot" / "pivot.toml"
E, W = 200e9, 0.01  # structural_steel; out-of-plane width of both examples, m
# the beams alone, welded where they cross, no notch corrected: what beam theory describes
BARE = {"beam_model.root_extension": 0.0, "beam_model.crossings": "weld",
        "beam_model.notch_correction": False}


def frame_stiffness_x(L, t, d, hs, w=W):
    """Lateral stiffness (N/m) at the stage's top centre of two Euler-Bernoulli leaves (x =
    +-d/2, clamped at y = 0) under a rigid stage reaching hs above their tips: each tip's
    stiffness in (u_x, u_y, theta) is [[12EI/L^3, 0, 6EI/L^2], [0, EA/L, 0], [6EI/L^2, 0,
    4EI/L]], moved to the load point by the rigid offset (x_i, -hs). The leaves' axial
    compliance lets the stage tilt: 24 E I / L^3 is its inextensible limit."""
    I, A = w * t**3 / 12, w * t
    k_tip = np.array([[12 * E * I / L**3, 0, 6 * E * I / L**2], [0, E * A / L, 0],
                      [6 * E * I / L**2, 0, 4 * E * I / L]])
    K = sum(T.T @ k_tip @ T for T in (np.array([[1, 0, hs], [0, 1, x], [0, 0, 1.0]])
                                      for x in (-d / 2, d / 2)))
    return 1 / np.linalg.inv(K)[0, 0]


def pivot_stiffness(result, arm, force=1.0):
    """K = M / theta (N m/rad): couple 2 arm F, theta = (v_right - v_left) / (2 arm)."""
    u = result["mean_displacement"]
    return 2 * arm * force / ((u["right"][1] - u["left"][1]) / (2 * arm))


def test_guide_beam_against_closed_forms():
    spec = load_spec(GUIDE, {**BARE, "beam_model.shear": False})
    p = spec.constants
    k = analyze_model(spec, model="beam")["stiffness"]["stage"]["x"]
    assert k == pytest.approx(frame_stiffness_x(p["L"], p["t"], p["d"], p["hs"]), rel=1e-9)
    inextensible = 24 * E * W * p["t"] ** 3 / 12 / p["L"] ** 3
    assert k == pytest.approx(inextensible, rel=0.01)  # measured 0.9951 (the stage's tilt)
    # Timoshenko (the default): shear adds 2 (1 + nu) / kappa (t / L)^2 = 0.2 % compliance
    k_shear = analyze_model(load_spec(GUIDE, BARE), model="beam")["stiffness"]["stage"]["x"]
    assert k / k_shear - 1 == pytest.approx(3.12 * (p["t"] / p["L"]) ** 2, rel=0.05)


def test_pivot_beam_against_8EI_over_L():
    spec = load_spec(PIVOT, {**BARE, "beam_model.shear": False})
    p = spec.constants
    K = pivot_stiffness(analyze_model(spec, model="beam"), p["arm"])
    assert K == pytest.approx(8 * E * W * p["t"] ** 3 / 12 / p["L"], rel=2e-3)  # 0.99917


@pytest.fixture(scope="module")
def guide_both():
    spec = load_spec(GUIDE)
    return analyze_model(spec, model="beam"), analyze_model(spec)


def test_guide_beam_against_continuum(guide_both):
    """With the common root extension (0.38 t per root) the beam model has the continuum's
    root compliance: stiffness and first frequency within 1 %; the same keys."""
    beam, cont = guide_both
    assert set(beam) == set(cont)
    assert beam["solver"] == "beam" and beam["dofs"] < cont["dofs"] / 20
    k_b, k_c = beam["stiffness"]["stage"]["x"], cont["stiffness"]["stage"]["x"]
    assert k_b == pytest.approx(k_c, rel=0.01), k_b / k_c  # measured 0.996
    assert beam["frequencies_hz"][0] == pytest.approx(cont["frequencies_hz"][0], rel=0.01)
    assert beam["reactions"]["fixed"] == pytest.approx(cont["reactions"]["fixed"], abs=1e-6)
    # beam stress at the leaves' roots; the continuum's peak adds the corners' concentration
    assert 0.5 < beam["max_von_mises"] / cont["max_von_mises"] < 1.0


@pytest.mark.parametrize("beta, leaf_mesh, k_cont", [(math.pi / 4, 0.000125, 5.692),
                                                     (math.pi / 6, 0.0000625, 5.996)])
def test_pivot_beam_against_continuum(beta, leaf_mesh, k_cont):
    """The leaves' solid joint where they cross (reduced/crossings.py) against
    the point weld, beside the continuum (leaf mesh t/4 and t/8, N m/rad: t/2, t/4, t/8 give
    5.721, 5.692, 5.682 at 90 degrees, 6.060, 6.023, 5.996 at 60), with the leaves' oblique
    roots (reduced/roots.py): 90 and 60 degree crossings within 1 %; the weld is
    lower (it has no joint, which grows as the crossing gets shallower)."""
    spec = load_spec(PIVOT, {"beta": beta, "lc_leaf": leaf_mesh})
    arm = spec.constants["arm"]
    cont = pivot_stiffness(analyze_model(spec), arm)
    assert cont == pytest.approx(k_cont, rel=1e-3)
    beam = analyze_model(spec, model="beam")
    weld = analyze_model(load_spec(PIVOT, {"beta": beta, "beam_model.crossings": "weld"}),
                         model="beam")
    assert set(beam) == set(analyze_model(load_spec(PIVOT), model="beam"))
    ratio, ratio_weld = (pivot_stiffness(r, arm) / cont for r in (beam, weld))
    # measured 0.992 (90 deg), 1.003 (60 deg); 0.976, 0.973 with the leaves' roots at their
    # centre lines' meeting with the faces (before reduced/roots.py)
    assert abs(ratio - 1) < 0.01, ratio
    assert ratio_weld < ratio - 0.01, (ratio_weld, ratio)  # 0.976, 0.939


LEAF = EXAMPLES / "oblique_leaf" / "leaf.toml"


def leaf_stiffness(result, p):
    """K = M / theta (N m/rad) of the one-leaf example (its faces at +-arm, F = 1 N)."""
    arm = p["L"] / 2 * math.cos(p["phi"]) + p["t"] * (3 + 1 / math.tan(p["phi"]))
    return pivot_stiffness(result, arm)


@pytest.mark.parametrize("degrees", [90, 45, 30, 15])
def test_oblique_roots_against_the_continuum(degrees):
    """One leaf (L/t = 30) under a couple, leaving its blocks at phi to their faces: the beam
    begins where its whole section has left the block, (t/2) cot(phi) along it
    (reduced/roots.py), then the common root extension. Beam theory with that
    length, K = E I / (L - t cot(phi) + 2 x 0.38 t) (pure moment: exact for the beam model);
    against the continuum (leaf mesh t/4; t/8 within 0.1 %), K and f1 (measured +0.11, +1.40,
    +1.52, +1.65 % and +0.15, +0.86, +0.91, +0.98 %; roots at the centre line's meeting with
    the face: 0, -1.9, -4.2, -10.7 %): the continuum lies between the two, nearer this one."""
    spec = load_spec(LEAF, {"phi": math.radians(degrees)})
    p = spec.constants
    beam, cont = analyze_model(spec, model="beam"), analyze_model(spec)
    euler = analyze_model(load_spec(LEAF, {"phi": p["phi"], "beam_model.shear": False}),
                          model="beam")
    length = p["L"] - p["t"] / math.tan(p["phi"]) + 2 * 0.38 * p["t"]
    assert leaf_stiffness(euler, p) == pytest.approx(E * W * p["t"] ** 3 / 12 / length,
                                                     rel=1e-6)
    k = leaf_stiffness(beam, p) / leaf_stiffness(cont, p) - 1
    f = beam["frequencies_hz"][0] / cont["frequencies_hz"][0] - 1
    assert (-0.005 < k < 0.005) if degrees == 90 else (0 < k < 0.025), k
    assert abs(f) < 0.015, f


def test_beam_follows_the_parameters_in_evaluate_and_a_study():
    k = {L: evaluate({"L": L}, file=str(GUIDE), model="beam", **BARE)["stiffness_stage_x"]
         for L in (0.04, 0.05)}
    spec = load_spec(GUIDE)
    p = spec.constants
    for L, value in k.items():
        assert value == pytest.approx(frame_stiffness_x(L, p["t"], p["d"], p["hs"]), rel=0.005)
    study = get_evaluator(model_mechanism(GUIDE))
    options = normalise_options(study, {"model": "beam"}, "model")
    metrics = study({"L": 0.05}, **options)
    assert metrics["stiffness_stage_x"] < k[0.05]  # root extension on: softer
    assert metrics["dofs"] < 500 and "f1_hz" in metrics
    with pytest.raises(ValueError, match="model = 'shell'"):
        study({}, model="shell")


def test_cli_model_beam_json_keys(capsys):
    args = argparse.Namespace(model=str(GUIDE), set=["L=0.05"], reduced="beam",
                              allow_code=False)
    out = json.loads(json.dumps(cli.run(args)))
    assert out["solver"] == "beam" and out["parameters"]["L"] == 0.05
    assert "stiffness of 'stage' along x" in cli.summarize(out)


def _guide_copy(tmp_path, old, new):
    text = GUIDE.read_text()
    assert old in text
    (tmp_path / "guide.geo").write_text((GUIDE.parent / "guide.geo").read_text())
    path = tmp_path / "guide.toml"
    path.write_text(text.replace(old, new))
    return path, path.read_text().splitlines()


def _line_of(lines, fragment):
    return next(i + 1 for i, line in enumerate(lines) if fragment in line)


@pytest.mark.parametrize("old, new, fragment, match", [
    ('thickness = "t"', 'thickness = "tt"', '"tt"', "'tt' .* is not a parameter"),
    ('groups = { stage = [0, "L + hs"] }', 'groups = { top = [0, "L + hs"] }', "top =",
     "group 'stage' has no point in the beam model"),
    ('joins = [["-d / 2", "L"], ["d / 2", "L"]]', 'joins = [["-d / 2", "L"], ["d", "L"]]',
     '["d", "L"]', "joins .* which is no point of a \\[\\[beam\\]\\]"),
    ('[[rigid]]                  # the base, held on its bottom face "fixed"',
     '[[rigid]]\nbogus = 1\n[[rigid]]', "bogus",
     "unknown key 'bogus'"),
])
def test_errors_name_the_file_and_line(tmp_path, old, new, fragment, match):
    path, lines = _guide_copy(tmp_path, old, new)
    with pytest.raises(ValueError, match=match) as error:
        analyze_model(load_spec(path), model="beam")
    message = str(error.value)
    assert message.startswith(str(path)), message
    if "has no point" not in match:
        assert f"line {_line_of(lines, fragment)}" in message, message


def test_traction_and_missing_beams_refused(tmp_path):
    path, _ = _guide_copy(tmp_path, "force = [1.0, 0.0]", "traction = [100.0, 0.0]")
    with pytest.raises(ValueError, match="takes forces"):
        analyze_model(load_spec(path), model="beam")
    bare = tmp_path / "bare.toml"
    bare.write_text(GUIDE.read_text().split("# The reduced beam model")[0])
    with pytest.raises(ValueError, match="declares no beams"):
        analyze_model(load_spec(bare), model="beam")


def test_plane_strain_is_the_continuums_only(tmp_path):
    """The beams' depth contracts freely (plane stress): a plane-strain file's beam model is
    refused, by name, where it gave the plane-stress numbers; its continuum runs."""
    path, _ = _guide_copy(tmp_path, 'kind = "plane_stress"', 'kind = "plane_strain"')
    with pytest.raises(ValueError, match=r"kind = 'plane_strain': the beam model is plane "
                                         r"stress .* \(--model continuum\)"):
        analyze_model(load_spec(path), model="beam")
    strain = analyze_model(load_spec(path), model="continuum")
    stress = analyze_model(load_spec(GUIDE), model="continuum")
    (group, k), = stress["stiffness"].items()
    assert strain["stiffness"][group]["x"] > 1.05 * k["x"]  # 1 / (1 - nu^2) stiffer, at most


@pytest.mark.slow
def test_compliance_and_large_deflection_keys_and_values():
    """[analysis] compliance and steps: the continuum's keys; the lateral compliance and the
    centre of compliance (on the axis, 20 mm up: the leaves' mid-height) as the continuum's;
    the axial and rotational compliances within the issue's 3 % (the roots' axial spreading,
    which the extension carries where the blocks are declared: -6.0 % without it)."""
    spec = load_spec(GUIDE, {"analysis.compliance": "stage", "analysis.steps": 3})
    beam, cont = analyze_model(spec, model="beam"), analyze_model(spec)
    assert set(beam) == set(cont)
    for key in ("compliance", "nonlinear"):
        assert set(beam[key]) == set(cont[key])
    Cb, Cc = np.array(beam["compliance"]["matrix"]), np.array(cont["compliance"]["matrix"])
    assert Cb[0, 0] == pytest.approx(Cc[0, 0], rel=0.01)  # measured +0.5 %
    assert np.diag(Cb)[1:] == pytest.approx(np.diag(Cc)[1:], rel=0.03)  # +0.75 %, +0.74 %
    assert beam["compliance"]["centre_of_compliance_m"] == pytest.approx(
        cont["compliance"]["centre_of_compliance_m"], abs=2e-4)
    ub, uc = (r["nonlinear"]["mean_displacement"]["stage"] for r in (beam, cont))
    assert ub[0] == pytest.approx(uc[0], rel=0.01)
    assert ub[1] == pytest.approx(uc[1], rel=0.05)  # parasitic shortening, measured +2 %


def test_thickness_profile_against_the_unit_load_integral(tmp_path):
    """Leaves thickening as t(s) = t (1 + 4 (s/L - 1/2)^2), an expression of the arc length s:
    pushed through the guide's centre of compliance (mid-height: no tilt), each leaf bends
    antisymmetrically, M = (F/2)(L/2 - s), so k = 2 / int (L/2 - s)^2 / (E I(s)) ds
    (Euler-Bernoulli, bare beams)."""
    from scipy.integrate import quad

    path, _ = _guide_copy(tmp_path, 'groups = { stage = [0, "L + hs"] }',
                          'groups = { stage = [0, "L / 2"] }')
    path.write_text(path.read_text().replace('thickness = "t"',
                                             'thickness = "t * (1 + 4 * (s / L - 0.5)**2)"'))
    spec = load_spec(path, {**BARE, "beam_model.shear": False})
    L, t = spec.constants["L"], spec.constants["t"]
    flex = quad(lambda s: (L / 2 - s) ** 2 / (E * W * (t * (1 + 4 * (s / L - 0.5) ** 2)) ** 3
                                             / 12), 0, L, epsabs=0, epsrel=1e-12)[0]
    k = analyze_model(spec, model="beam")["stiffness"]["stage"]["x"]
    # measured 3.4e-12 with 20 elements: each element's stiffness is its exact flexibility's
    # inverse (the interpolated element before: 5.9e-6, order 4)
    assert k == pytest.approx(2 / flex, rel=1e-9), k * flex / 2
    with pytest.raises(ValueError, match="must be > 0 along the beam"):
        load_spec(path, {"t": -1e-3})


def test_a_block_is_held_once(tmp_path):
    (tmp_path / "pivot.geo").write_text((PIVOT.parent / "pivot.geo").read_text())
    path = tmp_path / "pivot.toml"
    path.write_text(PIVOT.read_text().replace(
        '[[loads]]\ngroup = "right"', '[[supports]]\ngroup = "right"\n\n[[supports]]\n'
        'group = "left"\n\n[[loads]]\ngroup = "right"', 1))
    with pytest.raises(ValueError, match=r"pivot.toml line \d+: \[\[supports\]\] 'left' and "
                                         "'right' are on the same"):
        analyze_model(load_spec(path), model="beam")


NOTCH = EXAMPLES / "notch_hinge" / "notch.toml"


def test_a_notch_beam_is_corrected_by_its_2d_model():
    """The example's notch (an expression profile, t/R = 0.2) carries its 2-D correction on
    every element (reduced/hinge_patch.py: profile_factors); the bar's uniform ends carry
    none; notch_correction = false leaves plain beam theory."""
    from flexfem.reduced.hinge_patch import profile_factors
    from flexfem.reduced.model_file import beam_model

    spec = load_spec(NOTCH)
    model, _ = beam_model(spec)
    notch = [s for s in model.sections if s.taper is not None and s.taper[0] != s.taper[1]]
    uniform = [s for s in model.sections if s not in notch]
    line = spec.beams.beams[1]
    f = profile_factors(line.thickness, line.thickness.length, spec.material.nu)
    assert len(notch) == 40 and 0.92 < f.bending < 0.95
    assert all(s.factors[0] == f.bending and s.factors[2] == f.axial for s in notch)
    assert all(s.factors[0] == 1.0 and s.factors[2] == 1.0 for s in uniform)
    bare, _ = beam_model(load_spec(NOTCH, {"beam_model.notch_correction": "false"}))
    assert all(s.factors[0] == 1.0 for s in bare.sections)
    with pytest.raises(ValueError, match="notch_correction = 'maybe' must be true or false"):
        load_spec(NOTCH, {"beam_model.notch_correction": "maybe"})


@pytest.mark.slow
@pytest.mark.parametrize("t", [0.5e-3, 1e-3])
def test_notch_hinge_example_against_the_continuum(t):
    """The right-circular notch hinge (t/R = 0.2 and 0.4) from its model file, beam against
    the continuum of the same file: the stage's axial, sideways and rotational compliance and
    the first mode within 1 % (measured within 0.15 %), where plain beam theory of the notch
    is 6-13 % stiff (the notch's correction includes its junction with a body of its own end
    height: here the bar)."""
    out = {}
    for name, model, extra in (("continuum", "continuum", {}), ("beam", "beam", {}),
                               ("bare", "beam", {"beam_model.notch_correction": False})):
        res = analyze_model(load_spec(NOTCH, {"t": t, **extra}), model=model)
        out[name] = (np.diag(res["compliance"]["matrix"]), res["frequencies_hz"][0])
    (cont, f_cont), (beam, f_beam), (bare, _) = out["continuum"], out["beam"], out["bare"]
    assert beam == pytest.approx(cont, rel=0.01)
    assert f_beam == pytest.approx(f_cont, rel=0.01)
    assert np.all(bare / cont - 1 < -0.05)


def test_the_harmonic_response_of_the_beam_model_beside_the_continuum(tmp_path):
    """[analysis] harmonic runs on the beam model through the same analysis: its static
    response is the inverse of its stiffness, and its resonance is its first mode."""
    from pathlib import Path

    source = Path(__file__).parents[3] / "examples" / "bodies" / "guide.toml"
    text = source.read_text().replace("[analysis]\nmodes = 3", "[analysis]\nmodes = 3\n"
                                      "harmonic = { group = \"stage\", component = \"x\", "
                                      "f_max = 400.0, points = 201, damping = 0.02 }")
    path = tmp_path / "guide.toml"
    path.write_text(text)
    out = analyze_model(load_spec(path), model="beam")
    h = out["harmonic"]
    assert h["static"] == pytest.approx(1.0 / out["stiffness"]["stage"]["x"], rel=1e-9)
    assert h["resonances_hz"][0] == pytest.approx(out["frequencies_hz"][0], rel=2e-3)
