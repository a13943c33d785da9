"""Run gmsh on a user's file in a child process with limits, so that no file can hang,
prompt, print into ``--json``'s output or take the machine.

:func:`run_bounded` forks (POSIX): the child's stdin is /dev/null, its stdout and stderr go to
a scratch file (their last lines make the error message when it fails), its address space is
limited to what it holds now plus ``memory_bytes`` and its CPU time to ``cpu_seconds``
(setrlimit); the parent waits at most ``wall_seconds`` and kills it past that. The result or
the exception comes back pickled. Where the platform has no fork (Windows) the function runs
in-process, unbounded: the allow-list of geo_guard.py still holds.
"""
import os
import pickle
import select
import signal
import tempfile
import time

from ...fem.gmsh_session import fork_outside_sessions
from ...fem.budget import BudgetError


class ChildLimit(BudgetError):
    """gmsh exceeded the memory, CPU or wall-clock limit of its child process."""


def _address_space() -> int:
    """This process's virtual size now (bytes), 0 if unknown."""
    try:  # statm's first field: the virtual size in pages (VmSize)
        with open("/proc/self/statm") as f:
            return int(f.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        return 0


def _child(write_fd: int, log, function, args, memory_bytes: int, cpu_seconds: int) -> None:
    import resource

    devnull = os.open(os.devnull, os.O_RDONLY)
    os.dup2(devnull, 0)
    os.dup2(log.fileno(), 1)
    os.dup2(log.fileno(), 2)
    if memory_bytes:
        limit = _address_space() + memory_bytes
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    resource.setrlimit(resource.RLIMIT_CPU, (cpu_seconds, cpu_seconds + 5))
    try:
        outcome = ("ok", function(*args))
    except BaseException as error:  # noqa: BLE001 - every failure goes back to the parent
        outcome = ("error", error)
    try:
        data = pickle.dumps(outcome)
    except Exception:  # noqa: BLE001 - an exception that does not pickle: its message
        data = pickle.dumps(("error", ValueError(str(outcome[1]))))
    view = memoryview(data)
    while view:
        view = view[os.write(write_fd, view):]


#: A child that uses no CPU for this long (s) is waiting forever (a lock or a thread pool
#: copied by fork without its threads): it is stopped instead of waited for.
STALL_SECONDS = 30.0


def _cpu_seconds(pid: int):
    """The CPU time (s) process ``pid`` has used, None where /proc cannot tell."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            fields = f.read().rpartition(")")[2].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError):
        return None


def _tail(log, lines: int = 3) -> str:
    """The last ``lines`` non-empty lines the child printed, one line."""
    log.seek(0, os.SEEK_END)
    log.seek(max(0, log.tell() - 4096))
    text = log.read().decode("utf-8", errors="replace")
    shown = [line.strip() for line in text.splitlines() if line.strip()][-lines:]
    return " | ".join(shown)


def run_bounded(function, *args, memory_bytes: int, cpu_seconds: int, wall_seconds: float,
                what: str):
    """``function(*args)`` in a bounded child process (see the module's docstring); its
    result, or its exception raised here. ChildLimit (a BudgetError) naming ``what`` when the
    child dies of a limit."""
    if not hasattr(os, "fork"):
        return function(*args)
    read_fd, write_fd = os.pipe()
    log = tempfile.TemporaryFile()
    pid = fork_outside_sessions()
    if pid == 0:  # the child
        try:
            os.close(read_fd)
            _child(write_fd, log, function, args, memory_bytes, int(cpu_seconds))
        finally:
            os._exit(0)
    os.close(write_fd)
    chunks, deadline, timed_out = [], time.monotonic() + wall_seconds, False
    cpu, working = _cpu_seconds(pid), time.monotonic()
    try:
        while True:
            left = deadline - time.monotonic()
            now, used = time.monotonic(), _cpu_seconds(pid)
            if used is not None and cpu is not None and used > cpu:
                cpu, working = used, now
            stalled = now - working > STALL_SECONDS
            if left <= 0 or stalled:
                timed_out = "stalled" if stalled else "slow"
                os.kill(pid, signal.SIGKILL)
                break
            ready, _, _ = select.select([read_fd], [], [], min(left, 1.0))
            if ready:
                chunk = os.read(read_fd, 1 << 20)
                if not chunk:
                    break
                chunks.append(chunk)
    except BaseException:  # Ctrl-C or a failed read: the child goes too
        os.kill(pid, signal.SIGKILL)
        raise
    finally:
        os.close(read_fd)
        _, status = os.waitpid(pid, 0)
    with log:
        said = _tail(log) if not chunks or timed_out else ""
    if timed_out == "stalled":
        raise ChildLimit(f"{what}: gmsh stopped working ({STALL_SECONDS:.0f} s without CPU "
                         "time: waiting on something that never comes)"
                         + (f"; gmsh's last words: {said}" if said else ""))
    if timed_out:
        raise ChildLimit(f"{what}: gmsh did not finish within {wall_seconds:.0f} s (a loop or "
                         "a mesh far larger than the budget?)")
    if not chunks:
        signalled = os.WIFSIGNALED(status)
        cause = {signal.SIGXCPU: f"its CPU-time limit of {cpu_seconds:.0f} s",
                 signal.SIGKILL: "its memory or time limit",
                 signal.SIGSEGV: f"its memory limit of {memory_bytes / 2**30:.1f} GiB",
                 signal.SIGABRT: f"its memory limit of {memory_bytes / 2**30:.1f} GiB"}.get(
            os.WTERMSIG(status) if signalled else None, "an unknown cause")
        raise ChildLimit(f"{what}: gmsh stopped at {cause} (a mesh or loop beyond the "
                         "budget?); use a coarser mesh or raise the budget with --max-dofs"
                         + (f"; gmsh's last words: {said}" if said else ""))
    kind, value = pickle.loads(b"".join(chunks))
    if kind == "error":
        if isinstance(value, MemoryError):
            raise ChildLimit(f"{what}: gmsh ran out of its memory limit of "
                             f"{memory_bytes / 2**30:.1f} GiB (a mesh beyond the budget?); use "
                             "a coarser mesh or raise the budget with --max-dofs") from None
        raise value
    return value
