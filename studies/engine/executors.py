"""Where the cases of a study run: in this process, in local worker processes, or on Dask.

Every executor is a context manager with one method, ``run(function, tasks)``, which yields
``(task, result, lost)`` as each task completes, in completion order: ``result`` is what
``function(task)`` returned, or None with ``lost`` a message when the executor lost the task
(a worker process died, the cluster gave up on it). ``function`` must be importable by name
(it is pickled), and should catch its own errors.

Local workers are started with the 'spawn' method, so no gmsh session (process-global state)
is inherited half-used, and with OMP_NUM_THREADS, OPENBLAS_NUM_THREADS and MKL_NUM_THREADS set
to 1 both in the environment they inherit and by their initializer, so that N workers use N
cores, not N times the BLAS threads. This module imports no numpy, so the variables are set
before any worker imports it. Each local worker also watches its parent: when the parent dies
(SIGKILL, a crash) the worker exits within a second, even in the middle of a case, instead of
computing on as an orphan.
"""
import concurrent.futures
import multiprocessing
import os
import threading
import time

THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")
SCHEDULER_VARIABLE = "FLEXFEM_SCHEDULER"


def limit_threads() -> None:
    """One BLAS/OpenMP thread per process."""
    for name in THREAD_VARIABLES:
        os.environ[name] = "1"


def _exit_with_parent(parent: int, period_s: float) -> None:
    while os.getppid() == parent:
        time.sleep(period_s)
    os._exit(1)  # the parent died: nobody will read this worker's results


def init_worker(parent: int, period_s: float = 0.5) -> None:
    """Worker initializer: one BLAS thread, and exit when process ``parent`` is gone."""
    limit_threads()
    threading.Thread(target=_exit_with_parent, args=(parent, period_s), daemon=True,
                     name="flexfem-parent-watch").start()


class InProcessExecutor:
    """Runs the tasks one after the other in this process (``workers=1``)."""

    description = "in-process"

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False

    def run(self, function, tasks):
        for task in tasks:
            yield task, function(task), None


class LocalProcessExecutor:
    """A pool of ``workers`` spawned local processes (concurrent.futures)."""

    def __init__(self, workers: int):
        if int(workers) < 1:
            raise ValueError(f"workers = {workers!r} must be >= 1")
        self.workers = int(workers)
        self.description = f"{self.workers} local processes"
        self._pool = None
        self._saved_environment = {}

    def __enter__(self):
        self._saved_environment = {name: os.environ.get(name) for name in THREAD_VARIABLES}
        limit_threads()  # inherited by the spawned workers, before they import anything
        self._pool = concurrent.futures.ProcessPoolExecutor(
            max_workers=self.workers, mp_context=multiprocessing.get_context("spawn"),
            initializer=init_worker, initargs=(os.getpid(),))
        return self

    def __exit__(self, exc_type, exc, tb):
        interrupted = exc_type is not None
        if interrupted:  # Ctrl-C or an error: stop the cases in flight, start no more
            for process in list((getattr(self._pool, "_processes", None) or {}).values()):
                process.terminate()  # private attribute, stable since Python 3.2
        self._pool.shutdown(wait=True, cancel_futures=True)
        for name, value in self._saved_environment.items():
            if value is None:
                os.environ.pop(name, None)
            else:
                os.environ[name] = value
        return False

    def run(self, function, tasks):
        futures = {self._pool.submit(function, task): task for task in tasks}
        for future in concurrent.futures.as_completed(futures):
            task = futures.pop(future)
            try:
                yield task, future.result(), None
            except concurrent.futures.process.BrokenProcessPool as error:
                yield task, None, f"BrokenProcessPool: a worker process died ({error})"


class DaskExecutor:
    """The tasks of a study on an existing Dask distributed cluster at ``address``
    ("tcp://HOST:PORT"); needs the ``distributed`` package here and flexfem on the workers.

    Dask runs tasks in worker threads: start workers with ``--nthreads 1`` (one gmsh session
    per process) and with the thread variables above set to 1 in their environment.
    """

    def __init__(self, address: str, timeout_s: float = 30.0):
        if not isinstance(address, str) or "://" not in address:
            raise ValueError(f"scheduler = {address!r} must be an address like tcp://HOST:PORT")
        self.address = address
        self.timeout_s = timeout_s
        self.description = f"Dask cluster {address}"
        self._client = None

    def __enter__(self):
        try:
            from distributed import Client
        except ImportError as error:
            raise ValueError("scheduler given but the 'distributed' package is not installed "
                             "(pip install 'dask[distributed]')") from error
        try:
            self._client = Client(self.address, timeout=self.timeout_s)
        except (OSError, TimeoutError) as error:
            raise ValueError(f"cannot reach the Dask scheduler {self.address}: {error}") from error
        return self

    def __exit__(self, *exc):
        self._client.close()
        return False

    def run(self, function, tasks):
        from distributed import as_completed

        futures = {}
        for task in tasks:
            futures[self._client.submit(function, task, pure=False)] = task
        try:
            for future in as_completed(list(futures)):
                task = futures.pop(future)
                if future.status == "error":
                    error = future.exception()
                    yield task, None, f"{type(error).__name__}: {error}"
                else:
                    yield task, future.result(), None
        finally:
            if futures:  # interrupted: the cluster drops what is left
                self._client.cancel(list(futures))


MAX_WORKERS = 1024  # local processes; each imports numpy, scipy and gmsh


def make_executor(workers: int | None = None, scheduler: str | None = None):
    """The executor for a study: Dask when ``scheduler`` (or the FLEXFEM_SCHEDULER variable)
    gives an address, else local processes, in-process when ``workers`` is 1.
    ``workers=None`` means one per CPU."""
    scheduler = scheduler or os.environ.get(SCHEDULER_VARIABLE) or None
    if scheduler:
        return DaskExecutor(scheduler)
    workers = (os.cpu_count() or 1) if workers is None else workers
    if not 1 <= int(workers) <= MAX_WORKERS:
        raise ValueError(f"workers = {workers!r} must be from 1 to {MAX_WORKERS} local processes "
                         "(more: a Dask scheduler)")
    return InProcessExecutor() if int(workers) == 1 else LocalProcessExecutor(workers)
