"""Exact-constraint analysis: the examples' DOFs and over-constraints, against what the
constraint count says by hand (Blanding 1999: a wire 1 constraint, a leaf 3)."""
from pathlib import Path

import numpy as np
import pytest

from flexfem.geometry.spatial.tables import load_spatial
from flexfem.studies.spatial.exact_constraint import exact_constraint

EXAMPLES = Path(__file__).resolve().parents[3] / "examples" / "spatial"


def _report(name):
    mechanism, _, parameters = load_spatial(EXAMPLES / name)
    return exact_constraint(mechanism, {"base"}), parameters


def _dof_space(report) -> np.ndarray:
    return np.array([twist for dof in report.dofs for _, twist in dof])


def test_four_wire_guide_has_three_dofs_and_one_redundant_wire():
    report, _ = _report("wire_guide.toml")
    assert len(report.dofs) == 3 and len(report.over_constraints) == 1
    names = {label.split("'")[1] for label, _, _ in report.over_constraints[0]}
    assert names == {"w1", "w2", "w3", "w4"}
    twists = _dof_space(report)  # x, y translation and rotation about z: no v_z, w_x, w_y
    assert np.abs(twists[:, [2, 3, 4]]).max() < 1e-9
    assert np.linalg.matrix_rank(twists, 1e-9) == 3
    s = report.singular_values
    assert s[-1] < report.threshold < s[-2]
    assert "over-constrained by 1" in report.summary()


def test_parallel_leaf_guide_moves_along_y_and_is_over_constrained_by_one():
    report, _ = _report("leaf_guide.toml")
    assert len(report.dofs) == 1 and len(report.over_constraints) == 1
    (twist,) = _dof_space(report)
    assert abs(twist[1]) == pytest.approx(np.linalg.norm(twist))  # a pure y translation
    combo = report.over_constraints[0]
    assert {label.split("'")[1] for label, _, _ in combo} == {"front", "back"}
    assert all(what == "moment about its normal" for _, what, _ in combo)


def test_cross_spring_pivot_turns_about_its_crossing():
    report, parameters = _report("cross_pivot.toml")
    assert len(report.dofs) == 1
    summary = report.summary()
    h = parameters["h"]
    (twist,) = _dof_space(report)
    v, w = twist[:3], twist[3:]
    assert abs(w[2]) == pytest.approx(np.linalg.norm(w))
    centre = np.cross(w, v) / (w @ w)
    assert centre[:2] == pytest.approx([0.0, h / 2], abs=1e-9)
    assert "rotation about" in summary


def test_the_command_says_over_constrained_by_one(capsys):
    from flexfem.studies.cli import main

    assert main(["constraints", str(EXAMPLES / "wire_guide.toml")]) == 0
    out = capsys.readouterr().out
    assert "over-constrained by 1" in out and "singular values:" in out


def test_the_command_checks_the_whole_file(tmp_path, capsys):
    """A file analyze would refuse (a planar force on a spatial stage) is refused here too,
    by its line; a planar file is named as one."""
    from flexfem.studies.cli import main

    text = (EXAMPLES / "guide.toml").read_text()
    assert "force = [1.0, 0.0, 0.0]" in text
    bad = tmp_path / "guide.toml"
    bad.write_text(text.replace("force = [1.0, 0.0, 0.0]", "force = [1.0, 0.0]"))
    assert main(["constraints", str(bad)]) == 2
    assert "[[loads]] force = [1.0, 0.0] must be a list of 3 numbers" in capsys.readouterr().err
    assert main(["constraints", str(EXAMPLES.parent / "bodies" / "guide.toml")]) == 2
    assert "not a spatial mechanism" in capsys.readouterr().err
