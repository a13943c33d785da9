"""Mechanisms written once as bodies and flexures (examples/bodies/), analysed by the
continuum and by the beam model derived from the same description: each against its closed
form, within the closed form's own accuracy, and the two models within 3 % of each other."""
import json
import math
from pathlib import Path

import pytest
from flexfem.geometry.user_model import load_spec
from flexfem.studies.cli import main
from flexfem.studies.run import run_convergence, sweep
from flexfem.studies.user_model.analysis import evaluate

BODIES = Path(__file__).parents[3] / "examples" / "bodies"


def _both(name: str, metric: str, **options) -> tuple[float, float]:
    file = str(BODIES / f"{name}.toml")
    return (evaluate({}, file=file, **options)[metric],
            evaluate({}, file=file, model="beam", **options)[metric])


def _EI(spec, t: float) -> float:
    return spec.material.E * spec.section.thickness * t ** 3 / 12


def test_parallel_guide_against_fixed_guided_leaves():
    spec = load_spec(BODIES / "guide.toml")
    L, t = spec.constants["L"], spec.constants["t"]
    continuum, beam = _both("guide", "stiffness_stage_x")
    closed = 24 * _EI(spec, t) / L ** 3  # two fixed-guided leaves
    # beam theory omits the roots' compliance, O(t/L) = 2.5 % here: the continuum is softer
    assert -3 * t / L < continuum / closed - 1 < 0
    assert beam == pytest.approx(continuum, rel=0.03)


def test_compound_parallelogram_is_two_guides_in_series():
    spec = load_spec(BODIES / "compound.toml")
    L, t = spec.constants["L"], spec.constants["t"]
    continuum, beam = _both("compound", "stiffness_stage_x")
    closed = 12 * _EI(spec, t) / L ** 3
    assert -3 * t / L * 2 < continuum / closed - 1 < 0  # two rows of roots in series
    assert beam == pytest.approx(continuum, rel=0.03)


def test_cross_pivot_against_the_welded_crossing():
    """Two leaves joined where they cross at their middles (a planar, monolithic cross
    pivot): each half bends as a fixed-guided beam about the joint, K = 8 E I / L."""
    spec = load_spec(BODIES / "cross_pivot.toml")
    L, t = spec.constants["L"], spec.constants["t"]
    continuum, beam = _both("cross_pivot", "compliance_22")
    closed = L / (8 * _EI(spec, t))
    # the solid joint and roots: within 3 t / L = 5 % of beam theory (stiffer: the joint)
    assert abs(continuum / closed - 1) < 3 * t / L
    assert beam == pytest.approx(continuum, rel=0.03)


def test_circular_notch_against_paros_weisbord():
    """Paros and Weisbord (1965), thin neck: K = 2 E w t^2.5 / (9 pi sqrt(R)), accurate to a
    few % at t/R = 0.1."""
    spec = load_spec(BODIES / "notch.toml")
    t, R = spec.constants["t"], spec.constants["R"]
    continuum, beam = _both("notch", "compliance_22")
    closed = 9 * math.pi * math.sqrt(R) / (2 * spec.material.E * spec.section.thickness
                                           * t ** 2.5)
    assert continuum == pytest.approx(closed, rel=0.05)
    assert beam == pytest.approx(continuum, rel=0.03)


def test_group_point_of_the_beam_model_carries_the_continuum_load():
    """A lateral force on the lever acts at the centroid of the lever's outline (less the
    notch's footprint), so both models agree on the displacement it causes too."""
    continuum, beam = _both("notch", "stiffness_lever_x")
    assert beam == pytest.approx(continuum, rel=0.03)


def test_the_same_groups_in_both_models_and_in_3d():
    spec = load_spec(BODIES / "guide.toml")
    assert spec.groups == {"ground": 1, "stage": 1, "solid": 2}
    assert set(spec.beams.groups) == {"ground", "stage"}
    solid = load_spec(BODIES / "guide.toml", dim=3)
    assert solid.groups == {"ground": 2, "stage": 2, "solid": 3}
    assert solid.section.kind == "solid" and solid.mechanism.depth == 0.01


@pytest.fixture(scope="module")
def guide_solid():
    """(spec, analysis) of the guide extruded to a solid (--dim 3: its statics and its first
    three modes), the most expensive model of this file: solved once for the two checks
    below, which read its modes and its stiffness."""
    from flexfem.studies.user_model.analysis import analyze_model

    spec = load_spec(BODIES / "guide.toml", {"analysis.modes": 3}, dim=3)
    return spec, analyze_model(spec)


@pytest.mark.slow
def test_the_spatial_beam_modes_against_the_solid(guide_solid):
    """--model beam --dim 3 (the planar model lifted by the depth, its bodies' out-of-plane
    inertias) against the extruded solid: the first three modes (in-plane, and the stage
    rocking and moving out of the plane) within 6 %: the leaves, 10 t wide, bend in the solid
    partly as plates (up to 1/(1 - nu^2) stiffer), which a beam does not."""
    from flexfem.studies.user_model.analysis import analyze_model

    spec, solid = guide_solid
    beam = analyze_model(spec, model="beam")["frequencies_hz"]
    assert beam == pytest.approx(solid["frequencies_hz"], rel=0.06)


@pytest.mark.slow
def test_the_extruded_solid_agrees_with_the_plane_model(guide_solid):
    """3-D: the guide's leaves are 10 t wide, between plane stress and plane strain
    (E / (1 - nu^2) = 1.09 E): the solid is stiffer than the plane-stress model by less."""
    plane = evaluate({}, file=str(BODIES / "guide.toml"))["stiffness_stage_x"]
    spec, solid = guide_solid
    nu = spec.material.nu
    assert plane < solid["stiffness"]["stage"]["x"] < plane / (1 - nu ** 2)


def test_cli_models_and_dims(capsys):
    assert main(["analyze", str(BODIES / "guide.toml"), "--model", "beam", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["solver"] == "beam" and out["stiffness"]["stage"]["x"] > 0
    assert main(["analyze", str(BODIES / "guide.toml"), "--model", "beam", "--dim", "3",
                 "--json"]) == 0
    solid_beam = json.loads(capsys.readouterr().out)
    assert solid_beam["dim"] == 3 and len(solid_beam["mean_displacement"]["stage"]) == 3
    # the lifted model has out-of-plane modes: its second lies far below the planar second
    assert solid_beam["frequencies_hz"][1] < 0.5 * out["frequencies_hz"][1]
    assert main(["analyze", str(BODIES.parent / "parallel_guide" / "guide.toml"),
                 "--dim", "3"]) == 2
    assert "2-D" in capsys.readouterr().err


def test_sweep_and_convergence_of_a_bodies_file(tmp_path):
    study = tmp_path / "study.toml"
    model = tmp_path / "guide.toml"
    model.write_text((BODIES / "guide.toml").read_text())
    study.write_text('mechanism = { model = "guide.toml" }\n[grid]\nt = [0.0008, 0.001]\n')
    summary = sweep(study, tmp_path / "out", workers=1, progress=False)
    k = [row["stiffness_stage_x"] for row in summary["results"]]
    assert summary["failed"] == 0 and k[1] / k[0] == pytest.approx(1.25 ** 3, rel=0.03)
    result = run_convergence(str(model), "stiffness_stage_x", n_levels=3, start=2.0)
    assert result["dofs"][0] < result["dofs"][-1]
    assert result["values"][-1] == pytest.approx(k[1], rel=0.005)


@pytest.mark.parametrize("angle", [90.0, 60.0])
def test_remote_centre_pivot_in_python_against_beam_theory(angle):
    """Two leaves that never meet, on lines through a pivot beyond the stage: axially stiff
    leaves make the stage turn about that point, and each leaf resists with
    (E I / L)(4 - 12 p + 12 p^2), p = -0.25 (library.pivot_stiffness)."""
    from flexfem.fem import material
    from flexfem.geometry.mechanism.library import cross_pivot, pivot_stiffness
    from flexfem.geometry.user_model import mechanism_spec
    from flexfem.geometry.user_model.tables import Analysis
    from flexfem.studies.user_model import analyze_model

    steel, L, t, w = material("structural_steel"), 0.03, 0.0005, 0.01
    mechanism = cross_pivot(L, t, w, angle, crossing=False)
    spec = mechanism_spec(mechanism, steel, ["ground"], {"stage": (1.0, 0.0)},
                          Analysis(compliance="stage"))
    closed = 1 / (2 * pivot_stiffness(steel.E * w * t ** 3 / 12, L, -0.25))
    continuum, beam = (analyze_model(spec, model=m)["compliance"]["matrix"][2][2]
                       for m in ("continuum", "beam"))
    assert continuum == pytest.approx(closed, rel=3 * t / L)
    assert beam == pytest.approx(continuum, rel=0.03)


def test_elliptical_notch_against_the_refined_continuum():
    """No closed form of equal standing: the continuum on a mesh twice as fine is the
    reference; the beam model's notch (its profile corrected by its own 2-D model) within 3 %."""
    file = str(BODIES / "elliptical_notch.toml")
    fine = evaluate({}, file=file, size_factor=0.5)["compliance_22"]
    coarse, beam = _both("elliptical_notch", "compliance_22")
    assert coarse == pytest.approx(fine, rel=0.01)
    assert beam == pytest.approx(fine, rel=0.03)
    circular = evaluate({}, file=str(BODIES / "notch.toml"))["compliance_22"]
    assert fine < circular  # the same neck, wider cut-outs: less compliant near the neck


@pytest.mark.slow
def test_the_guide_front_screened_by_the_beam_and_confirmed(tmp_path):
    """examples/bodies/guide_front.toml: every front design keeps its stroke margin, a softer
    drive comes with a lower first mode, and the continuum confirms the beam's front: the
    beam model's roots leave it softer by less than t/L (0.9 % at L/t = 110, 3.3 % at 28)."""
    from flexfem.studies.run import run_front

    result = run_front(BODIES / "guide_front.toml", tmp_path / "out")
    designs = result["designs"]
    assert len(designs) >= 5 and all(d["margins"]["stroke_limit_yield"] >= 0 for d in designs)
    k = [d["objectives"]["stiffness_stage_x"] for d in designs]
    f = [d["objectives"]["f1_hz"] for d in designs]
    assert k == sorted(k) and f == sorted(f)
    for d in designs:
        slenderness = d["params"]["t"] / d["params"]["L"]
        for metric, value in d["objectives"].items():
            assert 0 < d["confirmed"][metric] / value - 1 < slenderness, metric


def test_remote_centre_pivot_of_polygon_bodies():
    """examples/bodies/remote_centre.toml: a V-block ground and a keel stage (polygons) whose
    faces meet the two leaves square; the stage turns about the leaves' meeting point beyond
    it, each leaf resisting with (E I / L)(4 - 12 p + 12 p^2), p = -1/4 (library
    pivot_stiffness): the rotation compliance is L / (15.5 E I) within the roots' O(t/L), and
    the beam model (its blocks' chords, masses and faces from the polygons) within 3 %."""
    from flexfem.geometry.mechanism.library import pivot_stiffness

    file = BODIES / "remote_centre.toml"
    spec = load_spec(file)
    L, t = spec.constants["L"], spec.constants["t"]
    continuum, beam = (evaluate({}, file=str(file), model=m) for m in ("continuum", "beam"))
    closed = 1 / (2 * pivot_stiffness(_EI(spec, t), L, -0.25))
    assert 0 < continuum["compliance_22"] / closed - 1 < t / L  # the roots: softer, O(t/L)
    for metric in ("compliance_22", "stiffness_stage_x", "f1_hz"):
        assert beam[metric] == pytest.approx(continuum[metric], rel=0.03), metric


def test_an_out_of_plane_force_on_the_spatial_beam_model(tmp_path):
    """A force with an F_z component: refused in 2-D, naming --dim 3; with --model beam --dim 3
    the spatial model's statics: the reaction balances the force, and the in-plane part of
    the stage's motion is the planar model's under the in-plane part of the force (the lift
    is exact in the plane; a tilted force superposes)."""
    text = (BODIES / "guide.toml").read_text()
    tilted = tmp_path / "guide.toml"
    tilted.write_text(text.replace("force = [1.0, 0.0]", "force = [1.0, 0.0, 2.0]"))
    with pytest.raises(ValueError, match="out-of-plane force .* needs --dim 3"):
        load_spec(tilted)
    from flexfem.studies.user_model.analysis import analyze_model

    spatial = analyze_model(load_spec(tilted, dim=3), model="beam")
    planar = analyze_model(load_spec(BODIES / "guide.toml"), model="beam")
    assert spatial["reactions"]["ground"] == pytest.approx([-1.0, 0.0, -2.0], abs=1e-9)
    u, u_planar = spatial["mean_displacement"]["stage"], planar["mean_displacement"]["stage"]
    assert u[0] == pytest.approx(u_planar[0], rel=1e-6)
    assert u[2] > 0 and spatial["stiffness"]["stage"]["along"] > 0
