"""The same study on a real local Dask cluster (a scheduler and two workers on loopback,
started here as subprocesses) gives the results of the local run."""
import os
import socket
import subprocess
import sys
from pathlib import Path

import pytest
from flexfem.studies.engine.sweep import Study
from flexfem.studies.run import run_study

distributed = pytest.importorskip("distributed", reason="Dask 'distributed' is not installed "
                                  "(pip install 'dask[distributed]'); the cluster test needs it")

STUDY = Study("toy", grid={"length_m": [0.05, 0.1, 0.15], "thickness_tip_m": [0.001, 0.002],
                           "fail_if": [0, 1]})


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture
def dask_cluster(tmp_path):
    """tcp://127.0.0.1:<port> of a scheduler with two single-thread workers; torn down after."""
    dask = str(Path(sys.executable).with_name("dask"))
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
    env.pop("FLEXFEM_SCHEDULER", None)
    log = (tmp_path / "dask.log").open("w")
    processes = [subprocess.Popen([dask, "scheduler", "--host", "127.0.0.1", "--port", str(port),
                                   "--no-dashboard"], stdout=log, stderr=log, env=env, cwd=tmp_path)]
    for i in range(2):
        processes.append(subprocess.Popen(
            [dask, "worker", address, "--nthreads", "1", "--nworkers", "1", "--no-nanny", "--host", "127.0.0.1",
             "--no-dashboard", "--name", f"w{i}", "--local-directory", str(tmp_path / f"w{i}")],
            stdout=log, stderr=log, env=env, cwd=tmp_path))
    try:
        with distributed.Client(address, timeout=60) as client:
            client.wait_for_workers(2, timeout=60)
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


def test_dask_cluster_matches_the_local_run(tmp_path, dask_cluster, monkeypatch):
    monkeypatch.delenv("FLEXFEM_SCHEDULER", raising=False)
    local = run_study(STUDY, tmp_path / "local.sqlite", workers=1, progress=False)
    remote = run_study(STUDY, tmp_path / "dask.sqlite", scheduler=dask_cluster, progress=False)
    assert remote.executor == f"Dask cluster {dask_cluster}"
    assert remote.computed == 12
    # the same cases (same keys), the same failures, bit-identical metrics
    assert {c.key: (c.status, c.metrics) for c in remote.cases} == \
           {c.key: (c.status, c.metrics) for c in local.cases}
    assert all(c.worker.split(":")[1] != str(os.getpid()) for c in remote.cases)
    # FLEXFEM_SCHEDULER selects the cluster with no argument; everything is already stored
    monkeypatch.setenv("FLEXFEM_SCHEDULER", dask_cluster)
    again = run_study(STUDY, tmp_path / "dask.sqlite", retry_failed=True, progress=False)
    assert again.executor.startswith("Dask cluster") and (again.computed, again.reused) == (6, 6)


def test_unreachable_scheduler_is_a_clear_error(tmp_path, monkeypatch):
    monkeypatch.delenv("FLEXFEM_SCHEDULER", raising=False)
    from flexfem.studies.engine.executors import DaskExecutor
    executor = DaskExecutor(f"tcp://127.0.0.1:{_free_port()}", timeout_s=0.5)
    with pytest.raises(ValueError, match="cannot reach the Dask scheduler"):
        with executor:
            pass
    with pytest.raises(ValueError, match="scheduler"):
        DaskExecutor("localhost")
