"""The same study on a real local Dask cluster (a scheduler and two workers on loopback,
started here as subprocesses with the dask command-line tools) gives the results of the local
run: the toy with its test hooks, and the real mechanisms, which mesh with gmsh in Dask's
worker threads."""
import contextlib
import os
import shutil
import socket
import subprocess
import sys
from pathlib import Path

import pytest
from flexfem.studies.engine.sweep import Study
from flexfem.studies.run import run_study
from toy_hooks import HOOKS_PATH
from toy_hooks import MECHANISM as HOOKED

distributed = pytest.importorskip("distributed", reason="Dask 'distributed' is not installed "
                                  "(pip install 'dask[distributed]'); the cluster test needs it")

STUDY = Study(HOOKED, grid={"length_m": [0.05, 0.1, 0.15], "thickness_tip_m": [0.001, 0.002],
                            "fail_if": [0, 1]})
# a coarse 2-D DBMA (two designs) and the eight-bar suspension: gmsh in a worker thread
DBMA = Study("dbma", name="dbma", grid={"b": [0.6e-3, 0.7e-3]},
             options={"dim": 2, "size_factor": 4.0})
EIGHTBAR = Study("eightbar", name="eightbar", options={"size_factor": 2.0})


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@contextlib.contextmanager
def local_cluster(folder: Path, workers: int = 2, nanny: bool = False, scheduler_env=None):
    """tcp://127.0.0.1:<port> of a scheduler with ``workers`` single-thread workers started
    with the dask command-line tools (with ``nanny``: restarted when they die); torn down
    after."""
    dask = str(Path(sys.executable).with_name("dask"))
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
    env.pop("FLEXFEM_SCHEDULER", None)
    # the workers import the test-only mechanism (toy_hooks) from the tests' folder
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [HOOKS_PATH, env.get("PYTHONPATH")]))
    log = (folder / "dask.log").open("w")
    processes = [subprocess.Popen([dask, "scheduler", "--host", "127.0.0.1", "--port", str(port),
                                   "--no-dashboard"], stdout=log, stderr=log,
                                  env={**env, **(scheduler_env or {})}, cwd=folder)]
    for i in range(workers):
        processes.append(subprocess.Popen(
            [dask, "worker", address, "--nthreads", "1", "--nworkers", "1",
             "--nanny" if nanny else "--no-nanny", "--host", "127.0.0.1",
             "--no-dashboard", "--name", f"w{i}", "--local-directory", str(folder / f"w{i}")],
            stdout=log, stderr=log, env=env, cwd=folder))
    try:
        with distributed.Client(address, timeout=60) as client:
            client.wait_for_workers(workers, timeout=60)
        yield address
    finally:
        try:  # ask the scheduler to stop itself and its workers; then make sure
            with distributed.Client(address, timeout=5) as client:
                client.shutdown()
        except Exception:  # noqa: BLE001 - the cluster may not have started at all
            pass
        for process in processes:
            try:
                process.wait(timeout=5)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
        log.close()


@pytest.fixture
def dask_cluster(tmp_path):
    """A scheduler and two single-thread workers without nannies."""
    with local_cluster(tmp_path) as address:
        yield address


def test_dask_cluster_matches_the_local_run(tmp_path, dask_cluster, monkeypatch):
    monkeypatch.delenv("FLEXFEM_SCHEDULER", raising=False)
    local = run_study(STUDY, tmp_path / "local.sqlite", workers=1, progress=False, allow_code=True)
    remote = run_study(STUDY, tmp_path / "dask.sqlite", scheduler=dask_cluster, progress=False,
                       allow_code=True)
    assert remote.executor == f"Dask cluster {dask_cluster}"
    assert remote.computed == 12
    # the same cases (same keys), the same failures, bit-identical metrics
    assert {c.key: (c.status, c.metrics) for c in remote.cases} == \
           {c.key: (c.status, c.metrics) for c in local.cases}
    assert all(c.worker.split(":")[1] != str(os.getpid()) for c in remote.cases)
    # FLEXFEM_SCHEDULER selects the cluster with no argument; everything is already stored
    monkeypatch.setenv("FLEXFEM_SCHEDULER", dask_cluster)
    again = run_study(STUDY, tmp_path / "dask.sqlite", retry_failed=True, progress=False,
                      allow_code=True)
    assert again.executor.startswith("Dask cluster") and (again.computed, again.reused) == (6, 6)


def test_real_mechanisms_on_the_dask_cluster_match_the_local_run(tmp_path, dask_cluster):
    r = {}
    for study in (DBMA, EIGHTBAR):
        local = run_study(study, tmp_path / f"{study.name}-local.sqlite", workers=1, progress=False)
        remote = run_study(study, tmp_path / f"{study.name}-dask.sqlite", scheduler=dask_cluster,
                           progress=False)
        assert [c.error for c in remote.cases] == [None] * len(local.cases), study.name
        assert remote.computed == len(local.cases) >= 1
        for a, b in zip(local.cases, remote.cases):
            assert a.key == b.key and a.metrics.keys() == b.metrics.keys()
            for name, value in a.metrics.items():
                assert b.metrics[name] == pytest.approx(value, rel=1e-6, abs=1e-12), name  # solver round-off
        r.update({c.params["b"]: c.metrics["R_fem"] for c in remote.cases if "b" in c.params})
    assert len(r) == 2 and all(5 < v < 20 for v in r.values())  # a thinner hinge amplifies more


def test_a_case_the_environment_failed_is_recorded_and_recomputed(tmp_path, dask_cluster):
    study = Study(HOOKED, grid={"length_m": [0.05, 0.1], "env_error_if": [0, 1], "fail_if": [0, 1]})
    first = run_study(study, tmp_path / "r.sqlite", scheduler=dask_cluster, progress=False,
                      allow_code=True)
    statuses = sorted(c.status for c in first.cases)
    assert statuses == ["error"] * 2 + ["failed"] * 4 + ["ok"] * 2, statuses
    errors = [c for c in first.cases if c.status == "error"]
    assert all(c.error.startswith("RuntimeError: toy cantilever's environment") for c in errors)
    # the next run computes the environment's failures again (not the design's: no retry asked)
    again = run_study(study, tmp_path / "r.sqlite", scheduler=dask_cluster, progress=False,
                      allow_code=True)
    assert (again.computed, again.reused) == (2, 6)


def test_unreachable_scheduler_is_a_clear_error(tmp_path, monkeypatch):
    monkeypatch.delenv("FLEXFEM_SCHEDULER", raising=False)
    from flexfem.studies.engine.executors import DaskExecutor
    executor = DaskExecutor(f"tcp://127.0.0.1:{_free_port()}", timeout_s=0.5)
    with pytest.raises(ValueError, match="cannot reach the Dask scheduler"):
        with executor:
            pass
    with pytest.raises(ValueError, match="scheduler"):
        DaskExecutor("localhost")


def test_a_lost_worker_is_an_error_not_a_failed_design(tmp_path):
    # the scheduler gives up on a task at the first worker it kills (allowed-failures 0);
    # the nanny restarts the worker, which computes the other cases. One task on the worker
    # at a time (saturation 1), so that no other case is on it when it dies
    with local_cluster(tmp_path, workers=1, nanny=True, scheduler_env={
            "DASK_DISTRIBUTED__SCHEDULER__ALLOWED_FAILURES": "0",
            "DASK_DISTRIBUTED__SCHEDULER__WORKER_SATURATION": "1.0"}) as address:
        study = Study(HOOKED, grid={"length_m": [0.05, 0.1]}, cases=({"crash_if": 1},))
        first = run_study(study, tmp_path / "r.sqlite", scheduler=address, progress=False,
                          allow_code=True)
        crashed = next(c for c in first.cases if c.params.get("crash_if") == 1)
        assert crashed.status == "error" and crashed.error.startswith("KilledWorker"), crashed
        assert sorted(c.status for c in first.cases) == ["error", "ok", "ok"]
        again = run_study(study, tmp_path / "r.sqlite", scheduler=address, progress=False,
                          allow_code=True)
        assert (again.computed, again.reused) == (1, 2)  # the lost case only, no retry asked


def test_a_model_file_geo_runs_no_code_on_dask_workers(tmp_path, dask_cluster):
    """A study naming a model file whose .geo calls System: refused before any case reaches
    the cluster (the study's names are checked against the model first), and the command never
    runs (tests/studies/user_model/test_geo_is_data.py covers analyze and the local
    executors)."""
    from flexfem.geometry.user_model.geo_guard import CodeInGeometry
    from flexfem.studies.run import sweep

    folder = tmp_path / "model"
    shutil.copytree(Path(__file__).parents[3] / "examples" / "parallel_guide", folder)
    marker = tmp_path / "MARKER"
    geo = folder / "guide.geo"
    geo.write_text(geo.read_text() + f'\nSystem "touch {marker}";\n')
    study = folder / "study.toml"
    study.write_text('mechanism = { model = "guide.toml" }\n[grid]\nL = [0.04, 0.05]\n')
    with pytest.raises(CodeInGeometry, match="'System' runs a shell command"):
        sweep(study, tmp_path / "out", scheduler=dask_cluster, progress=False)
    assert not marker.exists()


def test_a_tolerance_study_on_dask_gives_the_local_indices(tmp_path, dask_cluster):
    """The Monte Carlo's designs are ordinary cases: on the cluster they give the indices of
    the local run (the toy cantilever, its root and tip thickness toleranced)."""
    from flexfem.studies.engine.tolerance import Tolerance, Tolerances
    from flexfem.studies.run import sweep

    tolerances = Tolerances({"thickness_root_m": Tolerance(0.002, 1e-4),
                             "thickness_tip_m": Tolerance(0.001, 1e-4, "uniform")}, n=16)
    study = Study("toy", name="tolerances", tolerances=tolerances)
    local = sweep(study, tmp_path / "local", workers=1, progress=False)
    remote = sweep(study, tmp_path / "dask", scheduler=dask_cluster, progress=False)
    assert remote["executor"].startswith("Dask cluster") and remote["failed"] == 0
    for metric, m in local["tolerances"]["metrics"].items():
        for name, value in m["total_order"].items():
            assert remote["tolerances"]["metrics"][metric]["total_order"][name] == \
                pytest.approx(value, rel=1e-9, abs=1e-12)
