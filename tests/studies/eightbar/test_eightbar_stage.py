"""The eight-bar as a stage (studies/eightbar/stage.py), quick mode: the compliance matrix's
drive stiffness against the prescribed-motion solve, mirror symmetry, the stroke trends, the
buckling factors, and the CLI."""
import json

import numpy as np
import pytest
from flexfem.geometry.eightbar.flexure import EightBarFlexureParams
from flexfem.studies.cli import main
from flexfem.studies.eightbar import cli as eightbar_cli

pytestmark = pytest.mark.slow  # the quick study (conftest.py's stage), ~2 min on a shared machine


def test_k_x_from_the_compliance_matrix_is_the_linear_k_x(stage):
    # 1 / C_xx (y and rotation free) against analysis.linear_analysis (x prescribed, y free):
    # the same linear stiffness by two routes
    k_c, k_lin = stage["linear"]["k_x"], stage["linear_analysis"]["k_x"]
    assert k_c == pytest.approx(k_lin, rel=1e-3)
    # and the middle of the stroke (the unloaded reference state) is the linear pose
    middle = min(stage["stroke"], key=lambda r: abs(r["x_m"]))
    assert middle["k_x"] == pytest.approx(k_c, rel=1e-4)  # tangent vs linear assembly


def test_support_stiffness_across_the_whole_stroke(stage):
    rows = stage["stroke"]
    assert len(rows) == 5 and rows[0]["x_m"] == pytest.approx(-rows[-1]["x_m"])
    assert stage["summary"]["support_ratio_min"] > 50
    # the suspension softens across the motion away from the middle (flexures turned)
    ratios = [r["support_ratio"] for r in rows]
    assert ratios[2] == max(ratios)
    # mirror symmetry: even quantities equal at +-x
    for key in ("k_x", "k_y", "k_theta", "f1_hz"):
        assert rows[0][key] == pytest.approx(rows[-1][key], rel=1e-9)
    C = np.array(rows[-1]["compliance"])
    assert np.allclose(C, C.T, rtol=1e-6, atol=1e-12 * np.abs(C).max())


def test_modes_and_buckling(stage):
    rows = stage["stroke"]
    assert all(0 < r["f1_hz"] < r["f2_hz"] <= r["f3_hz"] for r in rows)
    # the drive mode's frequency follows sqrt(k_x): within 1 % along the stroke
    assert stage["summary"]["f1_hz_max"] / stage["summary"]["f1_hz_min"] < 1.01
    b = stage["buckling"]
    assert b["drive_factor"] > 10 and b["drive_critical_n"] > b["drive_force_n"]
    assert b["off_axis_critical_plus_y_n"] > 0 and b["off_axis_critical_minus_y_n"] > 0
    assert b["off_axis_critical_n"] == min(b["off_axis_critical_plus_y_n"],
                                           b["off_axis_critical_minus_y_n"])
    assert b["drive_factor"] == pytest.approx(b["drive_critical_n"] / b["drive_force_n"])


def test_cli_stage_json(stage, capsys, monkeypatch):
    monkeypatch.setattr(eightbar_cli, "stage_study", lambda quick: stage)
    assert main(["eightbar", "stage", "--quick", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    for key in ("linear", "stroke", "buckling", "summary", "linear_analysis", "travel_m", "dofs"):
        assert key in out
    assert {"k_x", "k_y", "support_ratio", "k_theta", "parasitic_y", "parasitic_rotation",
            "f1_hz", "f2_hz", "f3_hz", "compliance"} <= set(out["stroke"][0])
    assert main(["eightbar", "stage", "--quick"]) == 0
    assert "k_y/k_x" in capsys.readouterr().out


def test_beam_modes_lanczos_dense_and_arpack_paths_agree():
    """The eight-bar beam model with 12 elements a flexure (639 unknowns: block Lanczos on the
    cached factor) against the dense eigensolver and the sparse shift-invert (ARPACK) path:
    the dense solve is done inverted, since the direct form lost 5e-5 of f1 to the nearly
    singular mass (tiny rotary inertias)."""
    import flexfem.fem.beam.modal as beam_modal
    from flexfem.fem.beam.supports import NodeFixed
    from flexfem.reduced.eightbar import eightbar_beam_model

    model, info = eightbar_beam_model(EightBarFlexureParams(), n_per_flexure=12)
    supports = [NodeFixed(tuple(info["ground"]))]
    lanczos = beam_modal.solve_beam_modes(model, supports, n=4)
    old = beam_modal.KRYLOV_FROM, beam_modal.DENSE_EIGEN_LIMIT
    try:
        beam_modal.KRYLOV_FROM = 10**6
        dense = beam_modal.solve_beam_modes(model, supports, n=4)
        beam_modal.DENSE_EIGEN_LIMIT = 0
        sparse = beam_modal.solve_beam_modes(model, supports, n=4)
    finally:
        beam_modal.KRYLOV_FROM, beam_modal.DENSE_EIGEN_LIMIT = old
    for other in (dense, sparse):
        assert lanczos.frequencies_hz == pytest.approx(other.frequencies_hz, rel=1e-7)
        assert lanczos.effective_mass == pytest.approx(other.effective_mass, rel=1e-5,
                                                       abs=1e-9)
    assert not np.array_equal(dense.frequencies_hz, sparse.frequencies_hz)  # three solvers


def test_out_of_plane_mode_of_the_stage_section():
    """The stage section's out-of-plane mode: the spatial model's in-plane drive mode is the
    planar beam model's f1 (two models, one design), and the first mode is out of plane
    (4.6-5.2 Hz with and without warping restraint; the 3-D continuum check is slow, in
    test_eightbar_modes3d.py); the paragraph says so (a comparison row would have only
    flexfem's own drive mode as its reference)."""
    from flexfem.studies.eightbar.beam import evaluate_beam
    from flexfem.studies.eightbar.stage_report import plane_modes, plane_sentence

    planes = plane_modes()
    assert planes["in_plane_hz"] == pytest.approx(evaluate_beam({})["f1_hz"], rel=1e-6)
    assert planes["out_of_plane_hz"] < planes["in_plane_hz"]
    assert f"{planes['out_of_plane_hz']:.3g} Hz" in plane_sentence(planes)
