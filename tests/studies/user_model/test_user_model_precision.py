"""[analysis] compliance, buckling and harmonic in a model file (the parallel guide): the rigid
stage's compliance against the guide's lateral stiffness, the FRF's static limit against the
static solve and its peak at the first natural frequency, a buckling factor, and the refusals."""
from pathlib import Path
import shutil

import pytest

from flexfem.geometry.user_model import load_spec
from flexfem.studies.user_model import analyze_model, cli
from flexfem.studies.user_model.analysis import flat_metrics

GUIDE = Path(__file__).resolve().parents[3] / "examples" / "parallel_guide"


def guide_with(tmp_path, analysis: str) -> Path:
    shutil.copy(GUIDE / "guide.geo", tmp_path / "guide.geo")
    text = (GUIDE / "guide.toml").read_text().replace("[analysis]\nmodes = 3",
                                                      "[analysis]\nmodes = 3\n" + analysis)
    path = tmp_path / "guide.toml"
    path.write_text(text)
    return path


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    path = guide_with(tmp_path_factory.mktemp("guide"),
                      'compliance = "stage"\nbuckling = 2\n'
                      'harmonic = { group = "stage", component = "x", f_max = 2000.0, '
                      'points = 401, damping = 0.02 }')
    return analyze_model(load_spec(path))


def test_compliance_of_the_rigid_stage_is_the_lateral_compliance(result):
    c = result["compliance"]
    k_lateral = result["stiffness"]["stage"]["x"]  # force / mean displacement (stage elastic)
    # the stage block is ~rigid against the leaves: the two agree within a few %
    assert 1 / c["matrix"][0][0] == pytest.approx(k_lateral, rel=0.03)
    assert len(c["matrix"]) == 3 and c["matrix"][0][1] == pytest.approx(c["matrix"][1][0])


def test_harmonic_static_limit_and_resonance(result):
    h = result["harmonic"]
    assert h["static"] == pytest.approx(result["mean_displacement"]["stage"][0], rel=1e-6)
    assert h["resonances_hz"][0] == pytest.approx(result["frequencies_hz"][0], rel=0.01)
    metrics = flat_metrics(result)
    assert metrics["harmonic_resonance_hz"] == h["resonances_hz"][0]
    assert metrics["buckling_factor_1"] == result["buckling"]["load_factors"][0] > 0
    assert "compliance_00" in metrics


def test_summary_names_them(result):
    text = cli.summarize(result)
    assert "compliance of 'stage'" in text and "buckling load factors" in text
    assert "harmonic response of 'stage'" in text


@pytest.mark.parametrize("analysis, message", [
    ('compliance = "nowhere"', "compliance group 'nowhere'"),
    ('compliance = "body"', "not a boundary group"),
    ("buckling = 0", "buckling = 0"),
    ('harmonic = { group = "stage", component = "q", f_max = 100.0 }', "component"),
    ('harmonic = { group = "stage", component = "x" }', "'f_max' is required"),
    ('harmonic = { group = "stage", component = "x", f_max = 1.0, speed = 2 }', "speed"),
])
def test_refusals_name_the_key(tmp_path, analysis, message):
    with pytest.raises(ValueError, match=message):
        load_spec(guide_with(tmp_path, analysis))
