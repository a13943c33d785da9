"""A damaged or read-only result store is named for what it is, with advice that keeps good
results: a table whose columns were altered, a row whose params are null, a read-only folder."""
import os
import sqlite3

import pytest
from flexfem.studies.engine.store import ResultStore
from flexfem.studies.engine.sweep import Study
from flexfem.studies.run import run_study


def _store(tmp_path):
    path = tmp_path / "r.sqlite"
    run_study(Study("toy", grid={"length_m": [0.05, 0.1]}), path, workers=1, progress=False)
    return path


def test_a_dropped_column_is_named(tmp_path):
    path = _store(tmp_path)
    with sqlite3.connect(path) as db:
        db.execute("ALTER TABLE cases DROP COLUMN worker")
    with pytest.raises(ValueError, match=r"was altered \(missing columns: \['worker'\]"):
        ResultStore(path)


def test_a_row_with_null_params_is_named(tmp_path):
    path = _store(tmp_path)
    with sqlite3.connect(path) as db:
        key = db.execute("SELECT key FROM cases").fetchone()[0]
        db.execute("UPDATE cases SET params = 'null' WHERE key = ?", (key,))
    with ResultStore(path) as store, pytest.raises(ValueError) as error:
        store.results()
    assert f"case {key!r} is damaged" in str(error.value) and "params = None" in str(error.value)


def test_a_read_only_store_is_not_called_unreadable(tmp_path, monkeypatch):
    """As root a chmod does not stop SQLite, so the folder's write access and SQLite's refusal
    are simulated: the store is opened through its real constructor."""
    path = _store(tmp_path)
    real = os.access
    monkeypatch.setattr(os, "access", lambda p, mode, **kw: False if mode == os.W_OK
                        else real(p, mode, **kw))

    def refuse(*args, **kwargs):
        raise sqlite3.OperationalError("attempt to write a readonly database")

    monkeypatch.setattr(sqlite3, "connect", refuse)
    with pytest.raises(ValueError) as error:
        ResultStore(path)
    message = str(error.value)
    assert "read-only" in message and "results are kept" in message
    assert "delete" not in message
