"""A test-only mechanism: the toy cantilever with hooks for testing the study engine.

It is named by its import path, ``"toy_hooks:evaluate"``, so studies need ``allow_code``
(``--allow-code``). pytest puts this folder on ``sys.path`` of the test process; worker
processes started with 'spawn' receive the parent's ``sys.path``, and subprocesses started
by the tests get it through PYTHONPATH (see ``HOOKS_PATH``).

Extra parameters: ``sleep_s`` (wait first, for kills and parallelism), ``fail_if`` (raise a
ValueError -- a failed design -- when non-zero), ``env_error_if`` (raise a RuntimeError -- an
environment error, computed again by the next run -- when non-zero), ``crash_if`` (the
process exits at once when non-zero, as after a segfault: only for worker processes).
"""
import os
import time
from pathlib import Path

from flexfem.studies.toy import model as toy

MECHANISM = "toy_hooks:evaluate"
PROBE = "toy_hooks:environment_probe"
HOOKS_PATH = str(Path(__file__).resolve().parent)
HOOKS = ("sleep_s", "fail_if", "env_error_if", "crash_if")


def evaluate(params: dict, size_factor: float = 1.0, n_elements: int | None = None) -> dict:
    """The toy's evaluate after the hooks of ``params`` (see the module)."""
    params = dict(params)
    hooks = {name: float(params.pop(name, 0.0)) for name in HOOKS}
    if hooks["sleep_s"] < 0:
        raise ValueError(f"sleep_s = {hooks['sleep_s']!r} must be >= 0")
    time.sleep(hooks["sleep_s"])
    if hooks["crash_if"]:  # as a segfault in a native library would: never use in-process
        os._exit(70)
    if hooks["fail_if"]:
        raise ValueError(f"toy cantilever asked to fail (fail_if = {hooks['fail_if']})")
    if hooks["env_error_if"]:
        raise RuntimeError(f"toy cantilever's environment failed (env_error_if = "
                           f"{hooks['env_error_if']})")
    return toy.evaluate(params, size_factor=size_factor, n_elements=n_elements)


def environment_probe(params: dict, **options) -> dict:
    """An evaluate for testing executors: the worker's process id and its OMP_NUM_THREADS /
    OPENBLAS_NUM_THREADS / MKL_NUM_THREADS (-1 when unset), after ``params["sleep_s"]`` s."""
    time.sleep(float(params.get("sleep_s", 0.0)))
    return {"pid": os.getpid(), **{name.lower(): float(os.environ.get(name, -1)) for name in
                                   ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")}}
