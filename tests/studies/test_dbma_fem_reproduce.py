"""The DBMA report function in quick mode (about 15-20 s: marked slow)."""
import math

import pytest
from flexfem.studies.dbma.report import reproduce


@pytest.mark.slow
def test_reproduce_quick_writes_its_files(tmp_path):
    summary = reproduce(tmp_path, quick=True)
    for name in summary["figures"] + summary["tables"]:
        assert (tmp_path / name).stat().st_size > 0, name
    rows = summary["comparisons"]
    assert rows and all({"quantity", "flexfem", "published", "rel_diff", "note"} <= set(r) for r in rows)
    for r in rows:
        # rel_diff is recomputed from the two numbers it sits beside
        assert math.isclose(r["rel_diff"], (r["flexfem"] - r["published"]) / r["published"])
