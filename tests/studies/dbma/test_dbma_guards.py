"""The DBMA analysis (and the eight-bar's budget) refuses at once what it cannot do well: a
mesh above the memory budget (estimated from the size field, in seconds), h = 0, absurd
sizes, and a result outside its models' validity; Ctrl-C stops a running mesh with exit
status 130."""
import dataclasses
import os
import signal
import subprocess
import sys
import time

import pytest
from flexfem.fem.budget import BudgetError, check_budget
from flexfem.geometry.dbma.estimate import estimate_mesh
from flexfem.geometry.dbma.params import paper_design
from flexfem.studies.dbma.analysis import build_model, evaluate


def flexfem(*args, timeout=120) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "flexfem.studies.cli", *args],
                          capture_output=True, text=True, timeout=timeout)


@pytest.mark.parametrize("dim, size_factor", [(2, 1.0), (2, 0.5), (3, 1.0)])
def test_the_estimate_is_close_to_the_mesh_gmsh_makes(dim, size_factor):
    p = paper_design()
    estimate = estimate_mesh(p, None, dim, None, size_factor)
    model = build_model(p, None, dim, size_factor)
    assert 1.0 <= model.n_dofs / estimate["dofs"] < 1.6, (model.n_dofs, estimate)


def test_a_mesh_above_the_budget_is_refused_in_seconds():
    start = time.monotonic()
    run = flexfem("dbma", "analyze", "--size-factor", "0.05")
    assert time.monotonic() - start < 20
    assert run.returncode == 2 and "Traceback" not in run.stderr
    assert "DOFs" in run.stderr and "--max-dofs" in run.stderr and "GiB" in run.stderr
    with pytest.raises(BudgetError, match="above the budget of 1,000 DOFs"):
        evaluate({}, dim=2, size_factor=4.0, max_dofs=1000)
    with pytest.raises(ValueError, match="max_dofs"):
        check_budget({"elements": 1, "dofs": 1}, 2, max_dofs=1.5)
    assert BudgetError.environmental  # a study computes it again on a bigger machine


def test_h_is_checked_before_meshing_and_absurd_sizes_are_refused():
    start = time.monotonic()
    run = flexfem("dbma", "analyze", "--h", "0")
    assert run.returncode == 2 and "h = 0.0 m must be > 0" in run.stderr
    assert time.monotonic() - start < 15  # no mesh was made
    p = paper_design()
    for name, value in (("b", 1e-12), ("l", 1e100), ("rho", 1e-300), ("E", 1e300),
                        ("h", 1e-9), ("d", float("inf"))):
        with pytest.raises(ValueError, match=f"DBMAParams: {name} ="):
            dataclasses.replace(p, **{name: value})
    for value in (True, "0.6e-3", None, [1e-3], 1e-3j):
        with pytest.raises(ValueError, match="must be a finite number"):
            evaluate({"b": value})


def test_a_result_outside_the_models_validity_is_refused():
    # h = 1 um: the output moves against the input, R_fem < 0 (it printed R = -1.06, exit 0)
    with pytest.raises(ValueError, match=r"R_fem = -.*outside the validity"):
        evaluate({"h": 1e-6}, dim=2, size_factor=4.0)


def test_ctrl_c_stops_a_running_mesh_at_once():
    process = subprocess.Popen(
        [sys.executable, "-m", "flexfem.studies.cli", "dbma", "analyze", "--dim", "2",
         "--size-factor", "0.1", "--max-dofs", "100000000"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        time.sleep(6)  # imports done, gmsh meshing some 600 000 triangles
        assert process.poll() is None, process.communicate()
        os.kill(process.pid, signal.SIGINT)
        start = time.monotonic()
        _, err = process.communicate(timeout=10)
        assert time.monotonic() - start < 5
    finally:
        if process.poll() is None:
            process.kill()
    assert process.returncode == 130 and "interrupted" in err and "Traceback" not in err


def test_eq7_beyond_its_assumptions_is_flagged():
    from flexfem.studies.dbma.guards import validity_notes
    p = paper_design()
    assert validity_notes(p, {"R_eq7": 9.0}) == []
    notes = validity_notes(dataclasses.replace(p, h=0.3e-3), {"R_eq7": 90.0})
    assert len(notes) == 1 and "Eq. 7" in notes[0] and "h = 0.0003 m < b = 0.0006 m" in notes[0]


@pytest.mark.parametrize("size_factor", [1.0, 0.5])
def test_the_eightbar_estimate_is_close_to_its_mesh(size_factor):
    from flexfem.geometry.eightbar.estimate import estimate_mesh as estimate_eightbar
    from flexfem.geometry.eightbar.flexure import EightBarFlexureParams
    from flexfem.studies.eightbar.analysis import build_model as build_eightbar
    p = EightBarFlexureParams()
    estimate = estimate_eightbar(p, size_factor=size_factor)
    model, _ = build_eightbar(p, size_factor)
    assert 0.6 < model.n_dofs / estimate["dofs"] < 1.7, (model.n_dofs, estimate)


def test_an_eightbar_mesh_above_the_budget_is_refused_before_meshing():
    from flexfem.studies.eightbar.analysis import evaluate as evaluate_eightbar
    start = time.monotonic()
    with pytest.raises(BudgetError, match="eight-bar mesh.*above the budget of 10,000 DOFs"):
        evaluate_eightbar({}, size_factor=0.5, max_dofs=10_000)
    assert time.monotonic() - start < 5
