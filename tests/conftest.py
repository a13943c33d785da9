"""Checks shared by the tests of every report section, and the memory every test plans for."""
import json
import math
import os

import pytest

from flexfem.fem.budget import MEMORY_VARIABLE

# Budgets of "half the available memory" would otherwise depend on what other jobs hold at
# the moment; 20 GiB (of the 24 GiB test machine) fixes them (inherited by the CLI runs in subprocesses too).
os.environ.setdefault(MEMORY_VARIABLE, "20")

from flexfem.studies.report.comparison import KINDS, rel_diff


def check_section_summary(out, summary: dict) -> None:
    """A report section's summary keeps its contract: JSON-able; every figure and table file
    exists and is not empty; every figure has a caption that is not its file name; every
    comparison row's difference is recomputed from the two numbers it sits beside."""
    json.dumps(summary)
    for fig in summary.get("figures", []):
        assert isinstance(fig, dict) and fig["caption"] and fig["caption"] != fig["file"], fig
        assert (out / fig["file"]).stat().st_size > 0, fig["file"]
    for name in summary.get("tables", []):
        assert (out / name).stat().st_size > 0, name
    for row in summary.get("comparisons", []):
        assert row["kind"] in KINDS and row["unit"] and row["source"], row
        expected = (row["flexfem"] - row["reference"] if row["difference_kind"] == "absolute"
                    else rel_diff(row["flexfem"], row["reference"]))
        assert math.isclose(row["difference"], expected, rel_tol=1e-12) or (
            math.isnan(row["difference"]) and math.isnan(expected)), row
        assert not (row["unit"] == "deg" and row["difference_kind"] == "relative"), row


@pytest.fixture
def section_contract():
    return check_section_summary
