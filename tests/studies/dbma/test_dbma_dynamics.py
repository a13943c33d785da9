"""DBMA dynamics (studies/dbma/dynamics.py) on a coarse 2-D mesh: the FRF's static limit, the
half-power bandwidth against 2 zeta f_n, the actuator rod's effect, buckling, and the CLI."""
import json

import pytest
from flexfem.studies.cli import main
from flexfem.studies.dbma import cli as dbma_cli
from flexfem.studies.dbma.dynamics import assumed, frf_study

pytestmark = pytest.mark.slow  # ~15-40 s on a shared machine


@pytest.fixture(scope="module")
def dynamics():
    return frf_study(dim=2, size_factor=2.0)


def test_frf_static_limit_is_the_static_output_per_force(dynamics):
    assert dynamics["static_m_per_n"] == pytest.approx(dynamics["static_output_m_per_n"],
                                                       rel=1e-6)


def test_half_power_bandwidth_is_two_zeta_f_n(dynamics):
    for row in dynamics["sensitivity"]:
        expected = 2 * row["damping"] * row["resonance_hz"]
        assert row["half_power_bandwidth_hz"] == pytest.approx(expected, rel=0.03)
    # the peak amplification of one mode, 1 / (2 zeta), less the other modes' share
    one = next(r for r in dynamics["sensitivity"] if r["damping"] == 0.01)
    assert one["amplification_at_resonance"] == pytest.approx(50, rel=0.4)


def test_resonance_between_free_and_held_pads(dynamics):
    assert dynamics["damping"] == assumed()["damping"] == 0.02
    f = dynamics["resonance_hz"]
    assert f == pytest.approx(dynamics["working_frequency_hz"], rel=0.01)
    assert 110 < f < dynamics["working_frequency_pads_held_hz"]
    assert dynamics["bandwidth_minus3db_hz"] > f > dynamics["flat_bandwidth_hz"]


def test_output_compliance_and_buckling(dynamics):
    o = dynamics["output"]
    assert o["k_out"] > 0 and o["k_lateral"] > o["k_out"]
    # the output's stiffness is the inverse of the static output per unit output force
    assert 1 / o["matrix"][1][1] == pytest.approx(o["k_out"], rel=0.5)
    assert dynamics["buckling"]["factor"] > 1
    assert dynamics["buckling"]["critical_force_n"] == pytest.approx(
        800 * dynamics["buckling"]["factor"])


def test_cli_frf_json(dynamics, capsys, monkeypatch):
    seen = {}

    def fake(damping, dim, size_factor):
        seen.update(damping=damping, dim=dim)
        return dynamics
    monkeypatch.setattr(dbma_cli, "frf_study", fake)
    assert main(["dbma", "frf", "--damping", "0.05", "--dim", "2", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert seen == {"damping": 0.05, "dim": 2}
    for key in ("resonance_hz", "bandwidth_minus3db_hz", "half_power_bandwidth_hz",
                "flat_bandwidth_hz", "static_m_per_n", "output", "buckling", "paper",
                "sensitivity", "frf_frequencies_hz", "amplitude_m_per_n", "phase_rad"):
        assert key in out
    assert main(["dbma", "frf"]) == 0
    assert "bandwidth" in capsys.readouterr().out
    with pytest.raises(SystemExit) as refused:  # argparse refuses a ratio outside (0, 1)
        main(["dbma", "frf", "--damping", "2"])
    assert refused.value.code == 2
