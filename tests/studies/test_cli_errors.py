"""Every failure a user can cause is one ``error:`` line and exit status 2 from the real
command (a subprocess): no traceback, whatever the cause -- a missing, unreadable or
misplaced file, a damaged result store, a malformed study; a closed pipe exits quietly."""
import os
import sqlite3
import subprocess
import sys

import pytest

STUDY = 'mechanism = "toy"\n[grid]\nlength_m = [0.05, 0.1]\n'


def flexfem(*args, cwd=None) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k != "FLEXFEM_SCHEDULER"}
    return subprocess.run([sys.executable, "-m", "flexfem.studies.cli", *map(str, args)],
                          capture_output=True, text=True, timeout=120, env=env, cwd=cwd)


def assert_one_error_line(run, *words) -> None:
    assert run.returncode == 2, (run.returncode, run.stderr)
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("flexfem sweep: error: "), run.stderr
    assert "Traceback" not in run.stderr
    for word in words:
        assert word in lines[0], (word, lines[0])


@pytest.fixture
def study(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(STUDY)
    return path


def _store(tmp_path, study) -> "os.PathLike":
    run = flexfem("sweep", study, "--out", tmp_path / "out", "--workers", "1")
    assert run.returncode == 0, run.stderr
    return tmp_path / "out" / "results.sqlite"


def test_file_system_errors(tmp_path, study):
    assert_one_error_line(flexfem("sweep", tmp_path / "none.toml"), "none.toml")
    assert_one_error_line(flexfem("sweep", tmp_path), "IsADirectoryError")
    assert_one_error_line(flexfem("sweep", study, "--out", study / "sub"),
                          f"{study} is a file, not a folder")
    (tmp_path / "taken").write_text("x")
    assert_one_error_line(flexfem("sweep", study, "--out", tmp_path / "taken"),
                          "is a file, not a folder")
    if os.geteuid() != 0:  # root reads anything
        locked = tmp_path / "locked.toml"
        locked.write_text(STUDY)
        locked.chmod(0)
        assert_one_error_line(flexfem("sweep", locked), "PermissionError")


def test_damaged_stores_are_named_with_their_recovery(tmp_path, study):
    out = tmp_path / "empty"
    out.mkdir()
    (out / "results.sqlite").write_bytes(b"")
    assert_one_error_line(flexfem("sweep", study, "--out", out), "empty file", "results.sqlite")
    garbage = tmp_path / "garbage"
    garbage.mkdir()
    (garbage / "results.sqlite").write_bytes(b"not a database at all" * 100)
    assert_one_error_line(flexfem("sweep", study, "--out", garbage), "results.sqlite",
                          "not a readable flexfem result store", "move it aside")
    store = _store(tmp_path, study)
    with sqlite3.connect(store) as db:
        key = db.execute("SELECT key FROM cases LIMIT 1").fetchone()[0]
        db.execute("UPDATE cases SET metrics = '{broken' WHERE key = ?", (key,))
    assert_one_error_line(flexfem("sweep", study, "--out", tmp_path / "out"), key, "damaged",
                          "DELETE FROM cases")


def test_a_truncated_store_is_refused(tmp_path, study):
    store = _store(tmp_path, study)
    with sqlite3.connect(store) as db:  # fold the WAL into the file, then cut it
        db.execute("PRAGMA wal_checkpoint(TRUNCATE)")
        db.execute("PRAGMA journal_mode=DELETE")
    data = store.read_bytes()
    store.write_bytes(data[:len(data) // 2 + 100])
    assert_one_error_line(flexfem("sweep", study, "--out", tmp_path / "out"), "results.sqlite")


@pytest.mark.parametrize("text, word", [
    ('mechanism = "toy"\ncases = 3\n', "malformed study"),
    ('mechanism = "toy"\nplots = 3\n', "malformed study"),
    ('mechanism = 3\n', "mechanism"),
    ('mechanism = "toy"\nname = ".."\n', "name"),
    ('mechanism = "toy"\n[options]\nsize_factor = "0.5"\n', "options.size_factor"),
    ('mechanism = "toy"\n[sample]\nn = 4\nranges = 3\n', "malformed study"),
])
def test_malformed_studies(tmp_path, text, word):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    assert_one_error_line(flexfem("sweep", path, "--out", tmp_path / "o", "--workers", "1"), word)


def test_a_closed_pipe_exits_quietly(tmp_path, study):
    env = {k: v for k, v in os.environ.items() if k != "FLEXFEM_SCHEDULER"}
    process = subprocess.Popen([sys.executable, "-m", "flexfem.studies.cli", "sweep", str(study),
                                "--out", str(tmp_path / "o"), "--workers", "1", "--json"],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
    process.stdout.close()  # the reader is gone before anything is written (| head -0)
    err = process.stderr.read().decode()
    assert process.wait(timeout=120) == 0 and err == "", err


@pytest.mark.parametrize("error", [PermissionError(13, "Permission denied", "results.sqlite"),
                                   sqlite3.OperationalError("database is locked"),
                                   TypeError("unsupported operand")])
def test_every_error_kind_is_one_line_in_process(monkeypatch, capsys, study, error):
    # the subprocess tests above cannot provoke a PermissionError as root: raise it directly
    from flexfem.studies import run_cli
    from flexfem.studies.cli import main

    def fail(*args, **kwargs):
        raise error
    monkeypatch.setattr(run_cli, "sweep", fail)
    assert main(["sweep", str(study)]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and err.startswith("flexfem sweep: error: ")
    assert str(error).split()[0] in err
