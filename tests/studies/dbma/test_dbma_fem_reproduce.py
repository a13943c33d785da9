"""The DBMA report function in quick mode (about 15-20 s: marked slow)."""
import pytest
from flexfem.studies.dbma.report import reproduce


@pytest.mark.slow
def test_reproduce_quick_writes_its_files(tmp_path, section_contract):
    summary = reproduce(tmp_path, quick=True)
    section_contract(tmp_path, summary)
    rows = summary["comparisons"]
    assert rows and any(r["headline"] for r in rows)
    # the paragraph states the design's stress verdict with the run's own numbers
    assert f"{summary['max_von_mises'] / 1e6:.0f} MPa" in summary["paragraph"]
