"""The one place that imports gmsh.

gmsh keeps process-global state; every use goes through :func:`gmsh_session`, which initialises
it, hands the ``gmsh`` module to the caller and finalises it on exit, so two models built in one
process never see each other. Sessions are serialised by a process-wide lock: threads of one
process (a Dask worker's, say) take turns, each with a fresh gmsh.

gmsh is initialised with ``interruptible=False``: it then installs no SIGINT handler, which
only the main thread may do, and meshes and finalises from any thread (gmsh >= 4.11). Its
initialisation still resets SIGPIPE to the default action (terminate), where Python ignores
it: a write to a closed pipe -- to a worker of a process pool that died, or a Dask peer --
would then kill the process instead of raising BrokenPipeError. The session restores Python's
disposition: with ``signal.signal`` in the main thread, through the C library elsewhere
(``signal.signal`` refuses other threads, but the disposition is the process's).

gmsh's FLTK writes its preferences (``~/.fltk/fltk.org/fltk.prefs``) when it is initialised;
nothing a model runs may write outside its output folder, so HOME points at a temporary
folder, removed at once, for that call.
"""
import ctypes
import os
import signal
import tempfile
import threading
from contextlib import contextmanager

_LOCK = threading.RLock()  # re-entered by the same thread: refused below, not a deadlock


def _restore_sigpipe(disposition) -> None:
    """Set SIGPIPE back to Python's ``disposition`` (SIG_IGN, normally), from any thread."""
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGPIPE, disposition)
    elif disposition in (signal.SIG_IGN, signal.SIG_DFL):
        libc = ctypes.CDLL(None, use_errno=True)
        libc.signal.restype = ctypes.c_void_p
        libc.signal.argtypes = (ctypes.c_int, ctypes.c_void_p)
        libc.signal(int(signal.SIGPIPE), int(disposition))


@contextmanager
def _home_elsewhere():
    """HOME set to a new temporary folder (removed afterwards) while the block runs."""
    home = os.environ.get("HOME")
    with tempfile.TemporaryDirectory(prefix="flexfem-gmsh-home-") as folder:
        os.environ["HOME"] = folder
        try:
            yield
        finally:
            if home is None:
                os.environ.pop("HOME", None)
            else:
                os.environ["HOME"] = home


@contextmanager
def gmsh_session(name: str = "flexfem", verbose: bool = False):
    """Yield an initialised ``gmsh`` module holding one empty model called ``name``."""
    import gmsh

    if not _LOCK.acquire(timeout=3600):
        raise RuntimeError("gmsh: waited an hour for another thread's session to close")
    try:
        if gmsh.isInitialized():
            raise RuntimeError("a gmsh session is already open in this process; close it first")
        sigpipe = signal.getsignal(signal.SIGPIPE)  # Python's own (SIG_IGN), not the kernel's
        with _home_elsewhere():
            gmsh.initialize(readConfigFiles=False, interruptible=False)
        _restore_sigpipe(sigpipe)
        try:
            gmsh.option.setNumber("General.Terminal", 1 if verbose else 0)
            gmsh.option.setNumber("General.NumThreads", 1)
            gmsh.model.add(name)
            yield gmsh
        finally:
            gmsh.finalize()
            _restore_sigpipe(sigpipe)
    finally:
        _LOCK.release()


def fork_outside_sessions() -> int:
    """``os.fork()`` while no thread of this process is inside a gmsh session (the child
    starts with no session open and may open its own); returns fork's value."""
    import os

    global _LOCK
    with _LOCK:
        pid = os.fork()
        if pid == 0:  # one thread now: a fresh lock instead of the copied, held one
            _LOCK = threading.RLock()
        return pid
