"""The generated beam models of the mechanisms: against their continuum FEM on slender
designs, the ``model = "beam"`` study option and ``--model beam`` on the CLI."""
import dataclasses
import json

import pytest

from flexfem.reduced.layout import axial_root_compliance, check_root_extension
from flexfem.geometry.dbma.params import paper_design
from flexfem.studies.cli import main
from flexfem.studies.mechanisms import get_evaluator


def test_eightbar_beam_evaluate_has_the_continuum_metric_names():
    from flexfem.studies.eightbar.beam import evaluate_beam

    out = evaluate_beam({})
    assert {"k_x", "k_y", "k_x_prbm", "max_von_mises", "f1_hz", "dofs"} <= set(out)
    assert all(isinstance(v, float) for v in out.values())
    assert 0.85 < out["k_x"] / out["k_x_prbm"] < 1.0  # the PRBM neglects shear and axial
    assert out["k_y"] > 50 * out["k_x"]
    nl = evaluate_beam({"flexure_width": 0.35e-3}, nonlinear=True, steps=4)
    assert nl["k_x"] > out["k_x"] and 0 < nl["fem_deviation_pct"] < 1


def test_dbma_beam_evaluate_has_the_continuum_metric_names():
    from flexfem.studies.dbma.beam import evaluate_beam

    out = evaluate_beam({"b": 0.5e-3}, modes=True)
    assert {"R_fem", "R_fem_per_side", "k_in", "max_von_mises", "dofs", "R_eq7", "k_out",
            "fn_working", "working_mode"} <= set(out)
    assert out["R_fem_per_side"] == pytest.approx(2 * out["R_fem"])
    assert out["working_mode"] == 2  # as the continuum's: a lateral mode comes first


def test_the_registry_evaluate_dispatches_on_model():
    for name in ("eightbar", "dbma"):
        evaluate = get_evaluator(name)
        out = evaluate({}, model="beam")
        assert out["dofs"] < 3000  # the beam model, not a mesh
        with pytest.raises(ValueError, match="model"):
            evaluate({}, model="shell")
        with pytest.raises(TypeError):
            evaluate({}, model="beam", bogus=1.0)
        evaluate({}, model="beam", size_factor=2.0)  # continuum-only: accepted, ignored


def test_a_study_with_model_beam_runs_the_beam_model(tmp_path):
    from flexfem.studies.run import study_from_dict, sweep

    study = study_from_dict({"mechanism": "eightbar", "name": "beam_study",
                             "options": {"model": "beam"},
                             "grid": {"flexure_width": [0.3e-3, 0.35e-3]}})
    out = sweep(study, tmp_path / "s", workers=1, progress=False)
    assert out["failed"] == 0 and out["cases"] == 2
    rows = sorted(out["results"], key=lambda r: r["flexure_width"])
    assert all(r["dofs"] < 3000 for r in rows)  # beam models, not meshes
    from flexfem.studies.eightbar.beam import evaluate_beam

    assert rows[1]["k_x"] == pytest.approx(evaluate_beam({"flexure_width": 0.35e-3})["k_x"],
                                           rel=1e-9)
    assert rows[1]["k_x"] > 1.2 * rows[0]["k_x"]


@pytest.mark.parametrize("argv", [["eightbar", "analyze", "--model", "beam", "--json"],
                                  ["dbma", "analyze", "--model", "beam", "--json"]])
def test_cli_model_beam(argv, capsys):
    assert main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    assert out.get("model") == "beam" or out.get("dim") == "beam"
    assert out["dofs"] < 3000


def test_cli_model_beam_text(capsys):
    assert main(["eightbar", "analyze", "--model", "beam"]) == 0
    assert "beam model" in capsys.readouterr().out
    with pytest.raises(SystemExit) as error:
        main(["dbma", "analyze", "--model", "nope"])
    assert error.value.code == 2


def test_root_extension_rules():
    assert check_root_extension(0.38) == 0.38
    with pytest.raises(ValueError, match="root_extension"):
        check_root_extension(-1)
    # at H = t the root enters a block no taller than itself: the plain root extension
    # (its value at taller blocks is checked against the continuum, not against its own fit:
    # tests/geometry/test_root_axial_compliance.py)
    assert axial_root_compliance(1.0, 1.0) == pytest.approx(0.38)


def test_leaf_hinge_within_3_percent_of_the_continuum_over_slenderness():
    from flexfem.reduced.specimen import slenderness_rows

    rows = slenderness_rows((3.0, 10.0), ("leaf",))
    for r in rows:
        assert abs(r["bending_error"]) < 0.03 and abs(r["axial_error"]) < 0.03
        assert r["bending_error_bare"] < -0.05  # the bare beam is too stiff


@pytest.mark.slow
@pytest.mark.parametrize("height", [1.5, 3.0, 10.0])
def test_the_root_axial_compliance_fits_a_leaf_between_tall_blocks(height):
    """A sharp-cornered leaf (t = 1 mm, l/t = 10) pulled between blocks ``height`` t tall and
    2 H long (at least 5 mm): with the roots' axial compliance (the fit over H/t = 1.1-40)
    the beam's extension is within 1 % of the 2-D continuum's (measured: the fit's residual
    within 0.03 / (E w) a root); the fit it replaced (0.61 ln(H/t) - 0.24, from H/t = 5) was
    5 % stiff at H/t = 1.5."""
    from unittest import mock

    from flexfem.reduced import specimen as bs

    specimen = {"b": 1e-3, "H": height * 1e-3, "block": max(5e-3, 2 * height * 1e-3)}
    with mock.patch.dict(bs.SPECIMEN, specimen):
        axial = bs.beam_specimen("leaf", 10e-3, 0.38)[1]
        assert axial == pytest.approx(bs.continuum_specimen("leaf", 10e-3)[1], rel=0.01)


def test_cross_spring_pivot_beam_matches_the_continuum():
    from flexfem.studies.balancing.pivot_beam import pivot_beam_check
    from flexfem.studies.balancing.pivot_fem import pivot_fem_check, positive_stiffness_pivots

    _, _, pivot = positive_stiffness_pivots()[0]
    beam, fem = pivot_beam_check(pivot, steps=4), pivot_fem_check(pivot, steps=4)
    for key in ("stiffness_linear_Nm_per_rad", "stiffness_secant_Nm_per_rad"):
        assert beam[key] == pytest.approx(fem[key], rel=0.005)
    assert beam["stress_fem_peak_Pa"] == pytest.approx(fem["stress_fem_peak_Pa"], rel=0.02)


@pytest.mark.slow
def test_compressed_leaf_beam_matches_the_continuum():
    from flexfem.studies.balancing.negative_pivot_study import (negative_pivot_designs,
                                                                negative_pivot_fem_check)
    from flexfem.studies.balancing.pivot_beam import compressed_leaf_beam_check

    pivot = negative_pivot_designs()[0][-1]
    beam = compressed_leaf_beam_check(pivot, (1.0,), 4)
    fem = negative_pivot_fem_check(pivot, (1.0,), 4)
    assert beam["stiffness_fem_small_Nm_per_rad"] == pytest.approx(
        fem["stiffness_fem_small_Nm_per_rad"], rel=0.01)
    assert beam["curve_moment_fem_Nm"][-1] == pytest.approx(fem["curve_moment_fem_Nm"][-1], rel=0.01)
    assert beam["stress_fem_peak_nodal_Pa"] == pytest.approx(fem["stress_fem_peak_nodal_Pa"],
                                                             rel=0.02)


@pytest.mark.slow
def test_eightbar_beam_matches_the_continuum():
    from flexfem.studies.eightbar.analysis import analyze_eightbar
    from flexfem.studies.eightbar.beam import analyze_eightbar_beam

    cont = analyze_eightbar(steps=4, n_modes=2, both_halves=False)
    beam = analyze_eightbar_beam(steps=8, n_modes=2)
    for key in ("k_x", "k_y", "end_force_n"):
        assert beam[key] == pytest.approx(cont[key], rel=0.03), key
    for mb, mc in zip(beam["modes"], cont["modes"]):
        assert mb["f_hz"] == pytest.approx(mc["f_hz"], rel=0.03)
    for key in ("max_von_mises", "peak_von_mises_travel", "fem_deviation_m"):
        assert beam[key] == pytest.approx(cont[key], rel=0.10), key


@pytest.mark.slow
def test_dbma_beam_matches_the_continuum_on_a_slender_design():
    """l/b = 20: R, k_in, the working mode and k_out within 3 % (the issue's target; k_out,
    the input-blocked load path through the stubby input members, is the beam model's weakest,
    see docs/beam.md)."""
    from flexfem.studies.dbma.beam_report import continuum_metrics
    from flexfem.studies.dbma.beam import analyze_dbma_beam

    p = dataclasses.replace(paper_design(), b=0.3e-3, l=6e-3)
    cont = continuum_metrics(p, 1.0)
    beam = analyze_dbma_beam(p)
    for key in ("R_fem_per_side", "k_in", "fn_working", "k_out"):
        assert beam[key] == pytest.approx(cont[key], rel=0.03), key


def _beam_as_fem(params: dict, size_factor: float) -> dict:
    """Raw metrics in fem_metrics' form from the beam model (a fast stand-in for the FEM)."""
    from flexfem.studies.dbma.analysis import (dbma_material, modal_response, output_stiffness,
                                               static_response)
    from flexfem.studies.dbma.beam import beam_model

    p = dataclasses.replace(paper_design(), **params)
    model, _ = beam_model(p)
    s = static_response(model, 100.0)
    modal = modal_response(model, 4)[0]
    return {"force": 100.0, "elongation": s["elongation"], "R_fem": s["R_fem"],
            "k_in": s["k_in"], "max_von_mises": s["max_von_mises"],
            "max_von_mises_element": s["max_von_mises"],
            "k_out": output_stiffness(model), "fn_working": modal["fn_working"],
            "working_mode": modal["working_mode"],
            "yield_strength": dbma_material(p).yield_strength, "dofs": int(model.n_dofs)}


@pytest.mark.slow
def test_dbma_optimizer_screens_with_the_beam_model():
    from flexfem.studies.dbma import optimize as opt
    from flexfem.studies.dbma.beam import beam_estimates
    from flexfem.studies.dbma.optimize_spec import OptimizeSpec

    spec = OptimizeSpec(n_seed=16, max_evaluations=8)
    r = opt.optimize(spec, evaluator=_beam_as_fem, estimator=beam_estimates)
    assert r["feasible"] and r["n_screened"] == 16
    # the screening model is the deciding model here: the seed's estimate is exact
    assert all(abs(v) < 1e-9 for k, v in r["seed"]["analytical_vs_fem"].items()
               if k in ("R_fem", "k_out", "fn_working")), r["seed"]["analytical_vs_fem"]


def test_optimize_cli_has_the_screen_option():
    from flexfem.studies.dbma.optimize_output import run

    with pytest.raises(ValueError, match="screen"):
        run(None, screen="nope")


def test_link_inertia_is_the_union_of_overlapping_rectangles():
    from flexfem.reduced.layout import link_inertia
    from flexfem.geometry.flexure_linkage import Part

    # an L of two 1 x 0.2 bars overlapping in a 0.2 x 0.2 corner square, and a third bar
    # through the same corner (triple overlap)
    parts = [Part("a", "k", "bar", (0.0, 0.0), (1.0, 0.0), 0.2),
             Part("b", "k", "bar", (0.0, -0.1), (0.0, 1.0), 0.2),
             Part("c", "k", "bar", (-0.1, 0.0), (0.1, 0.0), 0.2)]
    m, c, J = link_inertia(parts, "k", 1.0, 1.0)
    # union: [-0.1, 1] x [-0.1, 0.1] plus [-0.1, 0.1] x [0.1, 1]
    assert m == pytest.approx(1.1 * 0.2 + 0.2 * 0.9)
    cx = (1.1 * 0.2 * 0.45 + 0.18 * 0.0) / m
    cy = (0.22 * 0.0 + 0.18 * 0.55) / m
    assert c == pytest.approx([cx, cy])
    assert J > 0


def test_unchecked_params_skips_only_the_checks():
    from flexfem.reduced.eightbar import unchecked_params
    from flexfem.geometry.eightbar.flexure import EightBarFlexureParams

    base = EightBarFlexureParams()
    fast = unchecked_params(base, flexure_width=0.35e-3)
    assert fast == dataclasses.replace(base, flexure_width=0.35e-3)
    with pytest.raises(ValueError, match="unknown"):
        unchecked_params(base, nonsense=1.0)
