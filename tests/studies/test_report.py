"""The reproduction report: sections that fail do not stop the others, and the HTML renders
in a real browser with every figure decoded and every table filled."""
import json
import re
import shutil
import subprocess
import sys
import types

import numpy as np
import pytest
from flexfem.studies.cli import main
from flexfem.studies.mechanisms import Mechanism, Section
from flexfem.studies.report import reproduce as reproduce_module


def _fake_section(out_dir, quick=False):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    ax.plot(np.arange(3), np.arange(3) ** 2)
    fig.savefig(out_dir / "curve.png")
    plt.close(fig)
    (out_dir / "table.csv").write_text("x,y\n0,0\n1,1\n2,4\n")
    (out_dir / "field.vtu").write_text("<VTKFile/>")
    return {"comparisons": [{"quantity": "y(2)", "flexfem": 4.0, "published": 4.1,
                             "rel_diff": 4.0 / 4.1 - 1, "note": "fake"}],
            "figures": ["curve.png", "field.vtu"], "tables": ["table.csv"]}


def _broken_section(out_dir, quick=False):
    raise RuntimeError("deliberately broken")


@pytest.fixture
def fake_sections(monkeypatch):
    module = types.ModuleType("flexfem.studies.fake.sections")
    module.good, module.bad = _fake_section, _broken_section
    monkeypatch.setitem(sys.modules, "flexfem.studies.fake.sections", module)
    fake = Mechanism("fake", "A fake mechanism", "fake",
                     sections=(Section("good", "A good section", "sections:good"),
                               Section("bad", "A broken section", "sections:bad")))
    monkeypatch.setattr(reproduce_module, "report_sections",
                        lambda: [(fake, s) for s in fake.sections])


def test_failing_section_is_reported_and_others_kept(tmp_path, fake_sections):
    report = reproduce_module.reproduce(tmp_path)
    by_name = {s["section"]: s for s in report["sections"]}
    assert "deliberately broken" in by_name["bad"]["error"]
    assert by_name["good"]["comparisons"][0]["flexfem"] == 4.0
    assert (tmp_path / "good" / "summary.json").exists()
    assert "This section failed" in (tmp_path / "report.md").read_text()


def test_field_files_are_linked_not_shown_as_images(tmp_path, fake_sections):
    reproduce_module.reproduce(tmp_path)
    page = (tmp_path / "index.html").read_text()
    assert "<img src='good/curve.png'" in page
    assert "<a href='good/field.vtu'>" in page and "<img src='good/field.vtu'" not in page
    assert "Field file [field.vtu](good/field.vtu)" in (tmp_path / "report.md").read_text()


def test_resume_skips_finished_sections(tmp_path, fake_sections):
    reproduce_module.reproduce(tmp_path)
    (tmp_path / "good" / "curve.png").unlink()
    reproduce_module.reproduce(tmp_path, resume=True)
    assert not (tmp_path / "good" / "curve.png").exists()  # not recomputed
    reproduce_module.reproduce(tmp_path)
    assert (tmp_path / "good" / "curve.png").exists()


def test_cli_json_is_one_object(tmp_path, fake_sections, capsys):
    assert main(["reproduce", "--out", str(tmp_path), "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert [s["section"] for s in report["sections"]] == ["good", "bad"]


def rendered_counts(index_html) -> dict:
    """Load the page in headless Chromium; return the counts its load script wrote."""
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    if chromium is None:
        pytest.skip("chromium is not installed (Debian package 'chromium'; .ci/run installs it)")
    profile = index_html.parent / ".chromium-profile"
    dom = subprocess.run(
        [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
         "--no-first-run", "--disable-background-networking", "--disable-component-update",
         "--disable-sync", f"--user-data-dir={profile}", "--allow-file-access-from-files",
         "--virtual-time-budget=5000", "--dump-dom", index_html.as_uri()],
        capture_output=True, text=True, timeout=120).stdout
    body = re.search(r"<body([^>]*)>", dom)
    assert body, "chromium returned no document"
    return {k: int(v) for k, v in re.findall(r'data-([a-z-]+)="(\d+)"', body.group(1))}


def test_html_renders_in_chromium(tmp_path, fake_sections):
    reproduce_module.reproduce(tmp_path)
    counts = rendered_counts(tmp_path / "index.html")
    assert counts["images-total"] == 1
    assert counts["images-loaded"] == counts["images-total"]
    assert counts["tables-total"] == 2  # the summary and table.csv
    assert counts["tables-with-rows"] == counts["tables-total"]


@pytest.mark.slow
def test_quick_reproduction_report_renders(tmp_path):
    """The real main job (--quick): every section runs, every figure loads, every table has rows."""
    report = reproduce_module.reproduce(tmp_path, quick=True)
    failed = {s["section"]: s["error"] for s in report["sections"] if "error" in s}
    assert not failed, failed
    # every section that reproduces a source compares with it; the others say what they did
    sourced = {"dbma_analytical", "dbma_fem", "eightbar_rigid", "eightbar_fem", "balancing"}
    assert sourced <= {s["section"] for s in report["sections"]}
    assert all(s.get("comparisons") for s in report["sections"] if s["section"] in sourced)
    assert all(s.get("comparisons") or s.get("notes") for s in report["sections"])
    counts = rendered_counts(tmp_path / "index.html")
    assert counts["images-total"] >= len(report["sections"])
    assert counts["images-loaded"] == counts["images-total"]
    assert counts["tables-with-rows"] == counts["tables-total"]
