"""Study definition, designs, the runner (in-process and local processes), export and plots."""
import csv
import io
import json
import os

import pytest
from flexfem.studies.cli import main
from flexfem.studies.engine.progress import Progress, format_duration, format_progress
from flexfem.studies.engine.store import ResultStore, export_csv
from flexfem.studies.engine.sweep import Sample, Study, design_points, plot_metric
from flexfem.studies.mechanisms import MECHANISMS, get_evaluator
from flexfem.studies.run import load_study, run_study, study_from_dict
from flexfem.studies.toy import model as toy
from toy_hooks import MECHANISM as HOOKED, PROBE


@pytest.fixture(autouse=True)
def _no_cluster(monkeypatch):
    monkeypatch.delenv("FLEXFEM_SCHEDULER", raising=False)


def _exact_uniform(length_m=0.1, width_m=0.01, t=0.002, e=200e9, p=1.0):
    return p * length_m**3 / (3 * e * width_m * t**3 / 12)


# --- study definition -----------------------------------------------------------------------

def test_grid_is_the_cartesian_product_over_the_base():
    study = Study("toy", base={"width_m": 0.02, "length_m": 9.0},
                  grid={"length_m": [0.1, 0.2, 0.3], "load_n": [1.0, 2.0]})
    points = design_points(study)
    assert len(points) == 6
    assert all(p["width_m"] == 0.02 for p in points)          # base kept
    assert {p["length_m"] for p in points} == {0.1, 0.2, 0.3}  # grid overrides base
    assert len({(p["length_m"], p["load_n"]) for p in points}) == 6


def test_nothing_varied_is_the_base_design_alone():
    assert design_points(Study("toy", base={"length_m": 0.2})) == [{"length_m": 0.2}]


@pytest.mark.parametrize("method", ["lhs", "sobol"])
def test_sample_is_seeded_and_inside_its_ranges(method):
    sample = Sample({"length_m": (0.05, 0.2), "load_n": (1.0, 3.0)}, n=8, method=method, seed=3)
    points = sample.points()
    assert points == Sample(sample.ranges, n=8, method=method, seed=3).points()
    assert points != Sample(sample.ranges, n=8, method=method, seed=4).points()
    assert all(0.05 <= p["length_m"] <= 0.2 and 1.0 <= p["load_n"] <= 3.0 for p in points)


def test_latin_hypercube_puts_one_point_in_each_stratum():
    points = Sample({"length_m": (0.0, 1.0)}, n=10, method="lhs", seed=1).points()
    # Latin hypercube: exactly one of the n points in each of the n equal intervals
    assert sorted(int(p["length_m"] * 10) for p in points) == list(range(10))


@pytest.mark.parametrize("data, key", [
    ({"mechanism": "nope"}, "mechanism"),
    ({"mechanism": "toy", "colour": "red"}, "colour"),
    ({"mechanism": "toy", "grid": {"length_m": []}}, "grid.length_m"),
    ({"mechanism": "toy", "grid": {"length_m": 0.1}}, "grid.length_m"),
    ({"mechanism": "toy", "sample": {"n": 4, "ranges": {"length_m": [0.2, 0.1]}}}, "sample.ranges.length_m"),
    ({"mechanism": "toy", "sample": {"n": 4, "ranges": {"length_m": [0.1, 0.1]}}}, "sample.ranges.length_m"),
    ({"mechanism": "toy", "sample": {"n": 4, "ranges": {}}}, "sample.ranges"),
    ({"mechanism": "toy", "sample": {"n": 0, "ranges": {"length_m": [0.1, 0.2]}}}, "sample.n"),
    ({"mechanism": "toy", "sample": {"n": 4, "ranges": {"length_m": [0.1, 0.2]}, "size": 3}}, "sample.size"),
    ({"mechanism": "toy", "sample": {"n": 4, "method": "halton", "ranges": {"x": [0, 1]}}}, "sample.method"),
    ({"mechanism": "toy", "plots": [{"metric": "a", "parameter": "b", "colour": 1}]}, "colour"),
    ({"name": "x"}, "mechanism"),
])
def test_invalid_study_names_the_key(data, key):
    with pytest.raises(ValueError, match=key.replace(".", r"\.").replace("[", r"\[")):
        study_from_dict(data)


def test_study_toml_file_loads_with_its_stem_as_name(tmp_path):
    path = tmp_path / "beams.toml"
    path.write_text('mechanism = "toy"\n[grid]\nlength_m = [0.1, 0.2]\n'
                    '[sample]\nmethod = "sobol"\nn = 4\nseed = 2\n[sample.ranges]\nload_n = [1, 2]\n')
    study = load_study(path)
    assert study.name == "beams" and len(design_points(study)) == 6


def test_registry_resolves_lazily_and_names_the_known_mechanisms():
    assert get_evaluator("toy") is toy.evaluate
    assert set(MECHANISMS) >= {"toy", "dbma", "eightbar"}
    with pytest.raises(ValueError, match="toy"):
        get_evaluator("no-such-mechanism")
    with pytest.raises(ValueError, match="not importable"):
        get_evaluator("flexfem.studies.no_such_module:evaluate", allow_code=True)


# --- running --------------------------------------------------------------------------------

def test_failing_case_is_recorded_and_the_study_goes_on(tmp_path):
    study = Study(HOOKED, grid={"length_m": [0.05, 0.1], "fail_if": [0, 1]})
    result = run_study(study, tmp_path / "r.sqlite", workers=1, progress=False, allow_code=True)
    assert result.computed == 4 and len(result.cases) == 4
    failed = result.failed
    assert len(failed) == 2 and all(c.params["fail_if"] == 1 for c in failed)
    assert failed[0].error.startswith("ValueError: toy cantilever asked to fail")
    assert all(c.status == "failed" for c in failed)  # the design's failure, kept
    for case in result.cases:
        assert case.wall_time_s >= 0
        if case.ok:
            # uniform beam: closed form exact to round-off; the trapezoid rule (8 elements)
            # is exactly (1 + 1/(2 n^2)) times it, as the integrand is quadratic
            exact = _exact_uniform(case.params["length_m"])
            assert case.metrics["tip_deflection_analytical"] == pytest.approx(exact, rel=1e-12)
            assert case.metrics["tip_deflection"] == pytest.approx(exact * (1 + 1 / 128), rel=1e-12)
            assert case.dofs == 9


def test_rerun_computes_only_missing_and_retries_failed_on_request(tmp_path):
    store = tmp_path / "r.sqlite"
    run_study(Study(HOOKED, grid={"length_m": [0.05, 0.1], "fail_if": [0, 1]}), store, workers=1,
              progress=False, allow_code=True)
    bigger = Study(HOOKED, grid={"length_m": [0.05, 0.1, 0.2], "fail_if": [0, 1]})
    again = run_study(bigger, store, workers=1, progress=False, allow_code=True)
    assert (again.computed, again.reused, len(again.cases)) == (2, 4, 6)
    retry = run_study(bigger, store, workers=1, retry_failed=True, progress=False, allow_code=True)
    assert (retry.computed, retry.reused) == (3, 3)  # the three failed cases only


def test_local_processes_match_in_process_and_limit_threads(tmp_path):
    before = os.environ.get("OMP_NUM_THREADS")
    study = Study("toy", grid={"length_m": [0.05, 0.1, 0.15], "thickness_tip_m": [0.001, 0.002]})
    serial = run_study(study, tmp_path / "a.sqlite", workers=1, progress=False)
    parallel = run_study(study, tmp_path / "b.sqlite", workers=2, progress=False)
    assert parallel.executor == "2 local processes"
    # same arithmetic in every process: bit-identical metrics
    assert {c.key: c.metrics for c in serial.cases} == {c.key: c.metrics for c in parallel.cases}
    probe = Study(PROBE, grid={"sleep_s": [0.5, 0.51, 0.52, 0.53]})
    cases = run_study(probe, tmp_path / "c.sqlite", workers=2, progress=False, allow_code=True).cases
    pids = {c.metrics["pid"] for c in cases}
    assert os.getpid() not in pids and len(pids) == 2  # 4 sleeping cases spread on 2 workers
    assert all(c.metrics[k] == 1 for c in cases
               for k in ("omp_num_threads", "openblas_num_threads", "mkl_num_threads"))
    assert os.environ.get("OMP_NUM_THREADS") == before  # the parent's environment is restored


def test_csv_export_and_plot(tmp_path):
    study = Study(HOOKED, grid={"length_m": [0.05, 0.1], "width_m": [0.01, 0.02]}, cases=({"fail_if": 1},))
    cases = run_study(study, tmp_path / "r.sqlite", workers=1, progress=False, allow_code=True).cases
    rows = list(csv.DictReader(export_csv(cases, tmp_path / "r.csv").open()))
    assert len(rows) == 5
    assert {"length_m", "width_m", "tip_deflection", "tip_deflection_analytical", "wall_time_s",
            "dofs", "error"} <= set(rows[0])
    assert [r["status"] for r in rows].count("failed") == 1
    assert next(r for r in rows if r["status"] == "failed")["error"].startswith("ValueError")
    path = plot_metric(cases, "tip_deflection", "length_m", tmp_path / "p.png",
                       overlay=["tip_deflection_analytical"])
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and path.stat().st_size > 5000
    with pytest.raises(ValueError, match="no_such_metric"):
        plot_metric(cases, "no_such_metric", "length_m", tmp_path / "q.png")


def test_progress_line_only_when_asked_or_on_a_terminal():
    assert format_duration(3725) == "1h02m" and format_duration(65) == "1m05s"
    line = format_progress(done=3, failed=1, total=4, elapsed_s=30.0, width=4)
    assert line == "[###-] 3/4 cases, 1 failed, 10s left"
    quiet = io.StringIO()  # not a terminal
    bar = Progress(2, stream=quiet)
    bar.update(True), bar.update(False), bar.close()
    assert quiet.getvalue() == ""
    loud = io.StringIO()
    bar = Progress(2, stream=loud, enabled=True)
    bar.update(True), bar.update(False), bar.close()
    assert "2/2 cases, 1 failed" in loud.getvalue() and loud.getvalue().endswith("\n")


# --- command line ---------------------------------------------------------------------------

def test_sweep_command_json_and_resume(tmp_path, capsys):
    path = tmp_path / "s.toml"
    path.write_text(f'mechanism = "{HOOKED}"\n[grid]\nlength_m = [0.05, 0.1]\n[[cases]]\nfail_if = 1\n'
                    '[[plots]]\nmetric = "tip_deflection"\nparameter = "length_m"\n')
    out = tmp_path / "out"
    assert main(["sweep", str(path), "--out", str(out), "--workers", "1"]) == 2
    assert "--allow-code" in capsys.readouterr().err  # Python code: only when asked for
    assert main(["sweep", str(path), "--out", str(out), "--workers", "1", "--json",
                 "--allow-code"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert (result["cases"], result["computed"], result["failed"]) == (3, 3, 1)
    assert (out / "results.csv").exists() and (out / "tip_deflection_vs_length_m.png").exists()
    assert main(["sweep", str(path), "--out", str(out), "--workers", "1", "--allow-code"]) == 0
    assert "0 computed, 3 reused, 1 failed" in capsys.readouterr().out
    with ResultStore(out / "results.sqlite") as store:
        assert len(store.statuses()) == 3


def test_sweep_command_rejects_a_bad_study(tmp_path, capsys):
    path = tmp_path / "bad.toml"
    path.write_text('mechanism = "toy"\n[sample]\nn = 4\n[sample.ranges]\nlength_m = [0.3, 0.1]\n')
    assert main(["sweep", str(path), "--out", str(tmp_path / "o")]) == 2
    assert "sample.ranges.length_m" in capsys.readouterr().err


def test_a_dying_worker_fails_its_cases_not_the_study(tmp_path):
    study = Study(HOOKED, grid={"length_m": [0.05, 0.1, 0.15]}, cases=({"crash_if": 1},))
    result = run_study(study, tmp_path / "r.sqlite", workers=2, progress=False, allow_code=True)
    assert len(result.cases) == 4
    crashed = next(c for c in result.cases if c.params.get("crash_if") == 1)
    # the worker, not the design: an "error", computed again by the next run
    assert crashed.status == "error" and crashed.error.startswith("BrokenProcessPool")
    # the others either completed before the crash or are errors with it; the next run (no
    # retry_failed needed) completes all of them in a fresh pool
    retry = run_study(Study(HOOKED, grid=study.grid), tmp_path / "r.sqlite", workers=2,
                      progress=False, allow_code=True)
    assert len(retry.cases) == 3 and not retry.failed
