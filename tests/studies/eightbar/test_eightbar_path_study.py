"""The eight-bar path study: thesis data, CLI, and reproduce()."""
import json

import numpy as np
import pytest
from flexfem.studies.cli import main
from flexfem.studies.eightbar.path import appendix_a_points, reproduce, thesis_targets


def test_appendix_a_data_matches_the_text_summary():
    pts = appendix_a_points()
    targets = thesis_targets()
    assert pts.shape == (251, 2)
    # Ch. 5: Y between -70.069 and -70.042 mm, a 0.027 mm deviation (values in m here)
    assert pts[:, 1].max() == pytest.approx(targets["y_max_m"], abs=1e-12)
    assert pts[:, 1].min() == pytest.approx(targets["y_min_m"], abs=1e-12)
    assert np.ptp(pts[:, 1]) == pytest.approx(targets["max_deviation_m"], abs=1e-12)
    # the return sweep retraces the forward sweep
    assert np.allclose(pts[:126], pts[125:][::-1])


def test_cli_linkage_trace_json(capsys):
    assert main(["linkage", "trace", "peaucellier", "--points", "31", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["deviation_pct"] < 1e-9
    assert {"travel_m", "max_deviation_m"} <= set(out)


def test_cli_eightbar_trace(capsys):
    assert main(["eightbar", "trace", "--points", "41", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["travel_m"] >= 33e-3 and out["deviation_pct"] < 0.1
    assert main(["eightbar", "trace", "--points", "41"]) == 0
    assert "travel" in capsys.readouterr().out


def test_cli_bad_point_count_is_exit_code_2(capsys):
    with pytest.raises(SystemExit) as refused:
        main(["linkage", "trace", "watt", "--points", "2"])
    assert refused.value.code == 2
    assert "--points: '2' must be a whole number from 3" in capsys.readouterr().err


def _band_about_best_fit_line(path_csv) -> tuple[float, float]:
    """(band, travel) in m of the traced points, from the CSV alone: the principal axis of the
    centred points is the best-fit line (an independent check of the study's own fit)."""
    import csv
    with open(path_csv) as f:
        pts = np.array([[float(r["x_m"]), float(r["y_m"])] for r in csv.DictReader(f)])
    centred = pts - pts.mean(axis=0)
    _, _, vt = np.linalg.svd(centred, full_matrices=False)
    along, across = centred @ vt[0], centred @ vt[1]
    return float(np.ptp(across)), float(np.ptp(along))


def test_reproduce_quick_writes_tables_and_figures(tmp_path, section_contract):
    summary = reproduce(tmp_path, quick=True)
    section_contract(tmp_path, summary)
    rows = {r["quantity"]: r for r in summary["comparisons"]}
    # the travel is the run's input: shown as such, never as agreement or in a headline
    travel = rows["eight-bar travel"]
    assert travel["kind"] == "input" and travel["verdict"] == "input" and not travel["headline"]
    band, span = _band_about_best_fit_line(tmp_path / "eightbar_path.csv")
    assert rows["eight-bar path deviation band"]["flexfem"] == pytest.approx(band, rel=1e-6)
    deviation = rows["eight-bar path deviation (band, % of travel)"]
    assert deviation["flexfem"] == pytest.approx(100 * band / span, rel=1e-6)
    assert deviation["verdict"] == "within limit" and deviation["flexfem"] < 0.1
    json.dumps(summary, default=float)
    assert {r["linkage"] for r in summary["straight_line_linkages"]} >= {"watt", "roberts", "chebyshev",
                                                                          "peaucellier"}


def test_docs_example_runs():
    # the Python example of docs/eightbar.md runs and gives the numbers the page quotes
    import re
    from pathlib import Path
    page = (Path(__file__).parents[3] / "docs" / "eightbar.md").read_text()
    block = next(b for b in re.findall(r"```python\n(.*?)```", page, re.S) if "trace_eightbar" in b)
    scope = {}
    exec(block, scope)
    # regression values: the numbers the page quotes, so that the page cannot drift from the code
    assert scope["tr"].deviation.band_m == pytest.approx(1.53e-6, rel=0.01)
    assert scope["tr"].deviation.deviation_pct == pytest.approx(0.0026, rel=0.01)


def test_a_sampling_too_coarse_to_resolve_the_path_is_refused(capsys):
    """Three points of Watt's linkage all but miss its deviation (0.26 um against 9.4 um):
    refused, naming both bands, where the default sampling is accepted."""
    assert main(["linkage", "trace", "watt", "--points", "3"]) == 2
    assert "do not resolve the path" in capsys.readouterr().err
    assert main(["linkage", "trace", "watt", "--json"]) == 0
