"""The SQLite store: case keys, round trips, and a study killed for real (SIGKILL, SIGINT)."""
import math
import os
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

import pytest
from flexfem.studies.engine.store import CaseResult, ResultStore, case_key
from flexfem.studies.engine.sweep import load_study
from flexfem.studies.run import run_study
from toy_hooks import HOOKS_PATH
from toy_hooks import MECHANISM as HOOKED


@pytest.fixture(autouse=True)
def _no_cluster(monkeypatch):
    monkeypatch.delenv("FLEXFEM_SCHEDULER", raising=False)


def test_case_key_is_canonical():
    a = case_key("toy", {"length_m": 1, "width_m": 0.01}, {"size_factor": 0.5}, "0.1.0")
    assert a == case_key("toy", {"width_m": 0.01, "length_m": 1.0}, {"size_factor": 0.5}, "0.1.0")
    assert len(a) == 64
    assert a != case_key("toy", {"length_m": 1, "width_m": 0.01}, {"size_factor": 0.25}, "0.1.0")
    assert a != case_key("toy", {"length_m": 1, "width_m": 0.01}, {"size_factor": 0.5}, "0.2.0")
    assert a != case_key("dbma", {"length_m": 1, "width_m": 0.01}, {"size_factor": 0.5}, "0.1.0")
    with pytest.raises(ValueError, match="object"):
        case_key("toy", {"length_m": object()}, {})


def test_store_round_trip_in_wal_mode(tmp_path):
    path = tmp_path / "sub" / "r.sqlite"
    case = CaseResult(key="k1", mechanism="toy", params={"length_m": 0.1}, options={"n": 2.0},
                      metrics={"a": 1.5, "b": math.nan}, wall_time_s=0.25, dofs=9)
    failed = CaseResult(key="k2", mechanism="toy", params={"length_m": 0.2}, status="failed",
                        error="RuntimeError: boom")
    with ResultStore(path) as store:
        store.record(case)
        store.record(failed)
    with ResultStore(path) as store:
        assert store.statuses() == {"k1": "ok", "k2": "failed"}
        back, back_failed = store.results(["k1", "k2"])
    assert back.metrics["a"] == 1.5 and math.isnan(back.metrics["b"])
    assert (back.params, back.options, back.dofs, back.wall_time_s) == ({"length_m": 0.1}, {"n": 2.0}, 9, 0.25)
    assert back_failed.error == "RuntimeError: boom" and not back_failed.ok
    with sqlite3.connect(path) as db:
        assert db.execute("PRAGMA journal_mode").fetchone()[0] == "wal"
    with pytest.raises(ValueError, match="status"):
        CaseResult(key="k", mechanism="toy", params={}, status="done")


SLOW_STUDY = f"""mechanism = "{HOOKED}"
name = "slow"
[base]
sleep_s = 0.25
[grid]
length_m = [0.05, 0.06, 0.07, 0.08, 0.09, 0.10, 0.11, 0.12, 0.13, 0.14, 0.15, 0.16]
"""


# four quick cases, then eight that would take 30 s each: stopping must not wait for them
STUCK_STUDY = f'mechanism = "{HOOKED}"\nname = "stuck"\n' + "".join(
    f"[[cases]]\nlength_m = {0.05 + 0.01 * i:.2f}\nsleep_s = {0.2 if i < 4 else 30.0}\n" for i in range(12))


def _start_sweep(tmp_path: Path, text: str = SLOW_STUDY) -> tuple[subprocess.Popen, Path]:
    toml = tmp_path / "slow.toml"
    toml.write_text(text)
    out = tmp_path / "out"
    env = {k: v for k, v in os.environ.items() if k != "FLEXFEM_SCHEDULER"}
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [HOOKS_PATH, env.get("PYTHONPATH")]))
    process = subprocess.Popen(
        [sys.executable, "-m", "flexfem.studies.cli", "sweep", str(toml), "--out", str(out),
         "--workers", "2", "--allow-code"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env,
        start_new_session=True,  # its own process group: the kill reaches its workers too
        # a shell without job control starts background jobs with SIGINT ignored, and Python
        # keeps it ignored: give the study the default a user's terminal gives it
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    return process, out / "results.sqlite"


def _rows(db_path: Path) -> int:
    if not db_path.exists():
        return 0
    try:
        with sqlite3.connect(f"file:{db_path}?mode=ro", uri=True, timeout=5) as db:
            return db.execute("SELECT count(*) FROM cases").fetchone()[0]
    except sqlite3.OperationalError:  # table not created yet
        return 0


def _wait_for_rows(process, db_path: Path, n: int, timeout_s: float = 60.0) -> None:
    deadline = time.monotonic() + timeout_s
    while _rows(db_path) < n:
        if process.poll() is not None or time.monotonic() > deadline:
            process.kill()
            raise AssertionError(f"sweep ended or stalled: {process.communicate()}")
        time.sleep(0.05)


def test_sigkill_loses_only_cases_in_flight_and_rerun_completes(tmp_path):
    process, db_path = _start_sweep(tmp_path)
    try:
        _wait_for_rows(process, db_path, 3)
    finally:
        os.killpg(process.pid, signal.SIGKILL)
        process.wait(timeout=30)
    assert process.returncode == -signal.SIGKILL
    with sqlite3.connect(db_path) as db:
        assert db.execute("PRAGMA integrity_check").fetchone()[0] == "ok"
        stored = db.execute("SELECT count(*), sum(status = 'ok') FROM cases").fetchone()
    # at most the 2 cases in flight (and the one being committed) are lost: 12 were asked
    assert 3 <= stored[0] < 12 and stored[0] == stored[1]
    study = load_study(tmp_path / "slow.toml")
    again = run_study(study, db_path, workers=2, progress=False, allow_code=True)
    assert (again.computed, again.reused) == (12 - stored[0], stored[0])
    assert len(again.cases) == 12 and not again.failed


def _group_alive(pgid: int) -> bool:
    """True while a process of group ``pgid`` runs (zombies, waiting for init, do not count)."""
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue
        if int(fields[2]) == pgid and fields[0] != "Z":  # fields: state, ppid, pgrp, ...
            return True
    return False


def test_sigint_stops_the_study_at_once_and_keeps_its_rows(tmp_path):
    process, db_path = _start_sweep(tmp_path, STUCK_STUDY)
    try:
        _wait_for_rows(process, db_path, 4)  # both workers are now in 30-s cases
        os.kill(process.pid, signal.SIGINT)  # the main process only: it must stop its workers
        _, err = process.communicate(timeout=15)
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
    assert process.returncode == 130 and b"interrupted" in err and b"Traceback" not in err
    # no worker left running in its group (give the resource tracker a moment to exit)
    deadline = time.monotonic() + 3
    while _group_alive(process.pid) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert not _group_alive(process.pid)
    with ResultStore(db_path) as store:
        assert list(store.statuses().values()) == ["ok"] * 4


def test_workers_exit_by_themselves_when_the_parent_is_killed(tmp_path):
    process, db_path = _start_sweep(tmp_path, STUCK_STUDY)
    try:
        _wait_for_rows(process, db_path, 4)  # both workers are now in 30-s cases
        os.kill(process.pid, signal.SIGKILL)  # the parent only: nobody stops the workers
        process.wait(timeout=10)
        deadline = time.monotonic() + 10
        while _group_alive(process.pid) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert not _group_alive(process.pid), "orphaned workers still running"
    finally:
        if _group_alive(process.pid):
            os.killpg(process.pid, signal.SIGKILL)


def test_a_store_from_before_the_error_status_is_migrated(tmp_path):
    from flexfem.studies.engine.store import SCHEMA
    path = tmp_path / "old.sqlite"
    with sqlite3.connect(path) as db:
        db.execute(SCHEMA.replace("'ok', 'failed', 'error'", "'ok', 'failed'"))
        db.execute("INSERT INTO cases VALUES ('k1', 'toy', '{}', '{}', 'ok', '{\"a\": 1.0}', "
                   "NULL, 0.1, NULL, NULL, '0.1.0', '2026-01-01')")
    with ResultStore(path) as store:
        store.record(CaseResult(key="k2", mechanism="toy", params={}, status="error",
                                error="BrokenProcessPool: a worker process died"))
        assert store.statuses() == {"k1": "ok", "k2": "error"}
        assert store.results(["k1"])[0].metrics == {"a": 1.0}
