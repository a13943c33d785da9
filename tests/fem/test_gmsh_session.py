"""gmsh sessions: one at a time, and a process that used gmsh still survives a broken pipe."""
import subprocess
import sys

import pytest
from flexfem.fem import gmsh_session

BROKEN_PIPE_AFTER_GMSH = """
import os
from flexfem.fem import gmsh_session
with gmsh_session() as gmsh:
    read, write = os.pipe()
    os.close(read)
    try:
        os.write(write, b"x")      # SIGPIPE at its default action would kill us here
    except BrokenPipeError:
        print("inside: BrokenPipeError")
read, write = os.pipe()
os.close(read)
try:
    os.write(write, b"x")
except BrokenPipeError:
    print("after: BrokenPipeError")
"""


def test_a_broken_pipe_raises_instead_of_killing_the_process():
    # gmsh.initialize() resets SIGPIPE to "terminate"; a process pool whose worker died would
    # then kill the parent process on its next write to that worker (seen in CI)
    run = subprocess.run([sys.executable, "-c", BROKEN_PIPE_AFTER_GMSH], capture_output=True,
                         text=True, timeout=60)
    assert run.returncode == 0, (run.returncode, run.stderr)
    assert run.stdout.split("\n")[:2] == ["inside: BrokenPipeError", "after: BrokenPipeError"]


def test_sessions_do_not_nest():
    with gmsh_session():
        with pytest.raises(RuntimeError, match="already open"):
            with gmsh_session():
                pass


BROKEN_PIPE_AFTER_GMSH_IN_A_THREAD = """
import os, threading
from flexfem.fem import gmsh_session
def mesh():
    with gmsh_session() as gmsh:
        gmsh.model.occ.addRectangle(0, 0, 0, 1, 1)
        gmsh.model.occ.synchronize()
        gmsh.model.mesh.generate(2)
        print("nodes", len(gmsh.model.mesh.getNodes()[0]) > 4)
thread = threading.Thread(target=mesh)
thread.start()
thread.join()
read, write = os.pipe()
os.close(read)
try:
    os.write(write, b"x")
except BrokenPipeError:
    print("after: BrokenPipeError")
"""


def test_a_session_runs_in_a_thread_and_keeps_sigpipe_ignored():
    # Dask runs tasks in worker threads: a session there meshes, finalises, and leaves SIGPIPE
    # as Python set it (restored through the C library: signal.signal refuses other threads)
    run = subprocess.run([sys.executable, "-c", BROKEN_PIPE_AFTER_GMSH_IN_A_THREAD],
                         capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, (run.returncode, run.stderr)
    assert run.stdout.split("\n")[:2] == ["nodes True", "after: BrokenPipeError"]


def test_a_session_writes_nothing_in_home(tmp_path, monkeypatch):
    """gmsh's FLTK preferences (~/.fltk) go to a temporary folder, removed: nothing outside
    the output folder is written; HOME is as it was."""
    import os

    monkeypatch.setenv("HOME", str(tmp_path))
    with gmsh_session() as gmsh:
        gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
        gmsh.model.occ.synchronize()
        gmsh.model.mesh.generate(3)
        assert os.environ["HOME"] == str(tmp_path)
    assert list(tmp_path.iterdir()) == []
