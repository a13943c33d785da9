"""The spatial beam model of the examples (studies/spatial/beam_model.py) against the closed
forms of issue 35: the four-wire guide's k_x = k_y = 4 * 12 E I / L^3, k_z = 4 E A / L and
torsion 4 (12 E I r^2 / L^3 + G J / L); a leaf in torsion G J / L with J = w t^3 / 3 (1 - 0.63
t / w) (a long one; a short one's roots restrain its warping); the cross-spring pivot's 2 E I / L (Wittrick) with its centre of compliance at the
crossing. The beam has shear (Timoshenko); the closed forms have none: the tolerances are
the shear's O((d/L)^2) share."""
import math
from pathlib import Path

import numpy as np
import pytest

from flexfem.fem import compliance_matrix
from flexfem.geometry.spatial.description import Plate, SolidBody, SpatialMechanism
from flexfem.geometry.user_model import load_spec
from flexfem.studies.spatial.beam_model import beam_model, supports_and_loads
from flexfem.studies.user_model.analysis import analyze_model

EXAMPLES = Path(__file__).resolve().parents[3] / "examples" / "spatial"


def _spec(name, **sets):
    return load_spec(EXAMPLES / f"{name}.toml", sets or None)


def _compliance(spec, body):
    beam = beam_model(spec.spatial, spec.material)
    return compliance_matrix(beam.model, supports_and_loads(spec)[0], body)


def test_wire_guide_against_its_closed_forms():
    spec = _spec("wire_guide")
    E, nu = spec.material.E, spec.material.nu
    L, d, a = (spec.constants[k] for k in ("L", "d", "a"))
    I, A = math.pi * d ** 4 / 64, math.pi * d ** 2 / 4
    k = 1 / np.diag(_compliance(spec, "stage").matrix)
    bending = 4 * 12 * E * I / L ** 3
    assert k[0] == pytest.approx(bending, rel=0.01) and k[1] == pytest.approx(k[0], rel=1e-9)
    assert k[2] == pytest.approx(4 * E * A / L, rel=1e-3)
    torsion = 4 * (12 * E * I * 2 * a * a / L ** 3 + E / (2 * (1 + nu)) * 2 * I / L)
    assert k[5] == pytest.approx(torsion, rel=0.01)


def test_the_wire_guide_follows_d_to_the_fourth_through_set():
    thin = analyze_model(_spec("wire_guide"), model="beam")["stiffness"]["stage"]["x"]
    thick = analyze_model(_spec("wire_guide", d="1.2 mm"), model="beam")["stiffness"]
    assert thick["stage"]["x"] / thin == pytest.approx(1.2 ** 4, rel=0.01)


def _one_leaf(t=0.001, w=0.01, L=0.03):
    base = SolidBody("base", ((( -0.01, -0.01, -0.005), (0.01, 0.01, 0.0)),))
    top = SolidBody("top", (((-0.01, -0.01, L), (0.01, 0.01, L + 0.005)),))
    leaf = Plate(("base", "top"), (0.0, 0.0, 0.0), (0.0, 0.0, L), t, w, (1.0, 0.0, 0.0))
    return SpatialMechanism((base, top), (leaf,))


def _torsion(t, w, L):
    from flexfem.fem import Fixed
    steel = _spec("leaf_guide").material
    beam = beam_model(_one_leaf(t, w, L), steel)
    c = compliance_matrix(beam.model, [Fixed("base")], "top")
    J = w * t ** 3 / 3 * (1 - 0.63 * t / w)
    return 1 / c.matrix[5, 5], steel.E / (2 * (1 + steel.nu)) * J / L


def test_a_long_leaf_in_torsion_is_g_j_over_l():
    k, closed = _torsion(0.001, 0.01, 1.0)  # w / L = 1/100: the roots' warping restraint 0.5 %
    assert k == pytest.approx(closed, rel=0.01)


def test_a_short_leaf_in_torsion_is_stiffened_by_its_restrained_roots():
    """w / L = 1/3: Vlasov's non-uniform torsion with the strip's Gamma = w^3 t^3 / 144
    (studies/spatial/roots.py) gives 1.19 G J / L."""
    from flexfem.studies.spatial.roots import warping_factor
    t, w, L = 0.001, 0.01, 0.03
    k, closed = _torsion(t, w, L)
    factor = warping_factor(w, t, L, 0.3, w * t ** 3 / 3 * (1 - 0.63 * t / w))
    assert factor == pytest.approx(1.19, abs=0.01)
    assert k == pytest.approx(factor * closed, rel=0.01)


def test_leaf_guide_against_two_guided_leaves():
    spec = _spec("leaf_guide")
    L, t, w = (spec.constants[k] for k in ("L", "t", "w"))
    k_y = analyze_model(spec, model="beam")["stiffness"]["stage"]["y"]
    assert k_y == pytest.approx(2 * 12 * spec.material.E * w * t ** 3 / 12 / L ** 3, rel=0.01)


def test_cross_pivot_rotates_about_the_crossing_at_2_e_i_over_l():
    spec = _spec("cross_pivot")
    h, t, w, g = (spec.constants[k] for k in ("h", "t", "w", "g"))
    c = _compliance(spec, "rotor")
    L = h * math.sqrt(2)
    assert 1 / c.matrix[5, 5] == pytest.approx(2 * spec.material.E * w * t ** 3 / 12 / L,
                                               rel=0.005)
    assert c.centre_of_compliance[:2] == pytest.approx([0.0, h / 2], abs=0.01 * h)


def test_the_analysis_gives_the_compliance_ratios_and_the_modes():
    spec = _spec("wire_guide")
    out = analyze_model(spec, model="beam")
    C = np.array(out["compliance"]["matrix"])
    assert out["compliance"]["point_m"] == pytest.approx([0, 0, 0.0325])
    assert np.allclose(C, C.T, rtol=1e-9, atol=1e-12 * np.abs(C).max())
    ratio = out["support_to_drive"]
    assert ratio["x"] == pytest.approx(1.0) and ratio["z"] > 1000
    m_stage = spec.material.rho * 0.032 * 0.032 * 0.005
    first = out["frequencies_hz"][0]
    k_x = out["stiffness"]["stage"]["x"]
    assert first == pytest.approx(math.sqrt(k_x / m_stage) / (2 * math.pi), rel=0.05)
    masses = np.array(out["modes"]["effective_mass_kg"])
    assert masses.shape == (3, 3) and masses[0].max() == pytest.approx(m_stage, rel=0.05)
    assert out["max_von_mises"] > 0 and out["stroke_limit_yield"] > 0


def test_a_traction_on_a_rigid_body_is_refused_in_one_line(tmp_path):
    text = (EXAMPLES / "wire_guide.toml").read_text().replace(
        "force = [1.0, 0.0, 0.0]", "traction = [1.0, 0.0, 0.0]")
    path = tmp_path / "traction.toml"
    path.write_text(text)
    with pytest.raises(ValueError, match="rigid nodes; give the body's total force"):
        analyze_model(load_spec(path), model="beam")


def test_a_moment_on_a_body_moves_it_by_the_compliance(tmp_path):
    text = (EXAMPLES / "cross_pivot.toml").read_text().replace(
        "force = [1.0, 0.0, 0.0]", "moment = [0.0, 0.0, 0.01]")
    path = tmp_path / "moment.toml"
    path.write_text(text + '\n[analysis]\ncompliance = "rotor"\n')
    spec = load_spec(path)
    out = analyze_model(spec, model="beam")
    C = np.array(out["compliance"]["matrix"])
    assert out["mean_displacement"]["rotor"] == pytest.approx(C[:3, 5] * 0.01, rel=1e-6)
    assert out["stiffness"] == {}
    with pytest.raises(ValueError, match="moment on 'rotor': the continuum takes forces"):
        analyze_model(spec)
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace("moment = [0.0, 0.0, 0.01]", "moment = [0.0, 0.01]"))
    with pytest.raises(ValueError, match=r"line \d+: \[\[loads\]\] moment .* must be 3 numbers"):
        load_spec(bad)


def test_a_study_evaluates_the_beam_model_of_a_spatial_file():
    from flexfem.studies.user_model.analysis import evaluate
    metrics = evaluate({"d": 0.0012}, model="beam", file=str(EXAMPLES / "wire_guide.toml"))
    assert metrics["stiffness_stage_x"] == pytest.approx(1 / metrics["compliance_00"])
    assert metrics["f1_hz"] > 0 and metrics["dofs"] > 0


def test_the_command_prints_the_beam_model_and_refuses_out_in_one_line(capsys, tmp_path):
    from flexfem.studies.cli import main
    assert main(["analyze", str(EXAMPLES / "leaf_guide.toml"), "--model", "beam",
                 "--set", "t=1.2 mm"]) == 0
    printed = capsys.readouterr().out
    assert "solver beam" in printed and "stiffness of 'stage' along y" in printed
    assert main(["analyze", str(EXAMPLES / "leaf_guide.toml"), "--model", "beam",
                 "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "no solved model to write" in err
