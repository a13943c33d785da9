"""The one place that imports gmsh.

gmsh keeps process-global state; every use goes through :func:`gmsh_session`, which initialises
it, hands the ``gmsh`` module to the caller and finalises it on exit, so two models built in one
process never see each other. gmsh must run in the main thread of a process: parallel studies
use worker processes, never threads.

gmsh's initialisation also resets SIGPIPE to the default action (terminate), where Python
ignores it: a write to a closed pipe -- to a worker of a process pool that died, say -- would
then kill the process instead of raising BrokenPipeError. The session restores Python's
disposition.
"""
import signal
import threading
from contextlib import contextmanager


@contextmanager
def gmsh_session(name: str = "flexfem", verbose: bool = False):
    """Yield an initialised ``gmsh`` module holding one empty model called ``name``."""
    import gmsh

    if threading.current_thread() is not threading.main_thread():
        raise RuntimeError("gmsh must run in the main thread; use worker processes, not threads")
    if gmsh.isInitialized():
        raise RuntimeError("a gmsh session is already open in this process; close it first")
    sigpipe = signal.getsignal(signal.SIGPIPE)  # Python's own (SIG_IGN), not the kernel's
    gmsh.initialize(readConfigFiles=False, interruptible=False)
    signal.signal(signal.SIGPIPE, sigpipe)
    try:
        gmsh.option.setNumber("General.Terminal", 1 if verbose else 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.model.add(name)
        yield gmsh
    finally:
        gmsh.finalize()
        signal.signal(signal.SIGPIPE, sigpipe)
