"""The workspace fitted on Table III: the fit finds a workspace the paper's numbers come from
when there is one (a synthetic Table III made from a known workspace), and refuses what the
robot cannot reach."""
import pytest

from flexfem.studies.balancing import calibration
from flexfem.studies.balancing.calibration import (NOT_ASSEMBLED, calibrate_workspace, misfit,
                                                   rms_reductions, workspace_of)


def test_the_fit_recovers_a_known_workspace(monkeypatch):
    known = (0.35, -0.10, 0.30)
    synthetic = rms_reductions("spring", workspace_of(known, quick=True))
    monkeypatch.setattr(calibration, "paper_table", lambda method: [
        {"motor": m, "rms_reduction_pct": v} for m, v in synthetic.items()])
    assert misfit(known, quick=True) == pytest.approx(0.0, abs=1e-20)
    fit = calibrate_workspace(quick=True)
    # four reductions fitted by three numbers: the misfit vanishes at the known workspace
    assert fit["rms_misfit_after_pp"] < 0.2 < fit["rms_misfit_before_pp"]


def test_an_unreachable_workspace_is_the_worst_misfit():
    assert misfit((5.0, 5.0, 0.5), quick=True) == NOT_ASSEMBLED
    assert misfit((0.25, -0.25, -0.1), quick=True) == NOT_ASSEMBLED
