"""The crash-safe result store of a study: one SQLite row per case, written as it completes.

The database runs in WAL mode and every case is committed on its own, so killing a study
(SIGINT or SIGKILL) loses at most the cases in flight, and the file stays readable. A case is
keyed by ``case_key``: the sha256 of the canonical JSON of mechanism, parameters, evaluate
options and the flexfem version, so a re-run finds what is already done, and a new flexfem
version recomputes everything.

A case's status is "ok", "failed" (the design itself failed: a deterministic error that a
re-run would repeat, kept and not re-run unless asked) or "error" (the environment failed it:
a lost worker, an out-of-memory, an OSError or RuntimeError around the evaluation; its cause
is stored and it is computed again by the next run). Stores written before "error" existed are
migrated when opened. Rows export to CSV (and Parquet where pyarrow is importable).
"""
import datetime
import hashlib
import json
import math
import os
import sqlite3
from dataclasses import dataclass, field
from pathlib import Path

from .tables import write_rows

SCHEMA = """
CREATE TABLE IF NOT EXISTS cases (
    key TEXT PRIMARY KEY,
    mechanism TEXT NOT NULL,
    params TEXT NOT NULL,
    options TEXT NOT NULL,
    status TEXT NOT NULL CHECK (status IN ('ok', 'failed', 'error')),
    metrics TEXT NOT NULL,
    error TEXT,
    wall_time_s REAL,
    dofs INTEGER,
    worker TEXT,
    flexfem_version TEXT,
    finished_at TEXT NOT NULL
)
"""


STATUSES = ("ok", "failed", "error")
COLUMNS = ("key", "mechanism", "params", "options", "status", "metrics", "error",
           "wall_time_s", "dofs", "worker", "flexfem_version", "finished_at")
KEY_SCHEMA = 2  # in every case key: 2 = options normalised to their declared types first


def flexfem_version() -> str:
    """The installed flexfem version (importlib.metadata), or "unknown"."""
    from importlib.metadata import PackageNotFoundError, version
    try:
        return version("flexfem")
    except PackageNotFoundError:
        return "unknown"


def _canonical(value):
    """Plain JSON values with one spelling per number: ints as floats, numpy scalars unboxed."""
    if isinstance(value, dict):
        return {str(k): _canonical(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_canonical(v) for v in value]
    if hasattr(value, "item") and not isinstance(value, (str, bytes)):
        value = value.item()
    if isinstance(value, bool) or value is None or isinstance(value, str):
        return value
    if isinstance(value, (int, float)):
        return float(value)
    raise ValueError(f"value {value!r} of type {type(value).__name__} is not a number, "
                     "string or bool: it cannot be a study parameter or option")


def canonical_json(value) -> str:
    """Sorted-key, compact JSON of ``value`` with numbers spelled as floats (1 and 1.0 agree)."""
    return json.dumps(_canonical(value), sort_keys=True, separators=(",", ":"), allow_nan=True)


def case_key(mechanism: str, params: dict, options: dict, version: str | None = None) -> str:
    """sha256 hex of the canonical JSON of mechanism, params, options, flexfem version and
    the key schema (KEY_SCHEMA: cases keyed before options were normalised, such as a
    ``dim = 2.0`` that failed in gmsh, are never reused for the normalised ``dim = 2``)."""
    payload = {"mechanism": mechanism, "params": params, "options": options,
               "flexfem": flexfem_version() if version is None else version,
               "schema": KEY_SCHEMA}
    return hashlib.sha256(canonical_json(payload).encode()).hexdigest()


@dataclass(frozen=True)
class CaseResult:
    """One evaluated case: parameters, metrics (SI), wall time (s), dofs, and on failure the
    error as "Type: message" (``status``: "ok", "failed" for the design, "error" for the
    environment; see the module)."""

    key: str
    mechanism: str
    params: dict
    options: dict = field(default_factory=dict)
    status: str = "ok"
    metrics: dict = field(default_factory=dict)
    error: str | None = None
    wall_time_s: float | None = None
    dofs: int | None = None
    worker: str | None = None
    flexfem_version: str | None = None
    finished_at: str | None = None

    def __post_init__(self):
        if self.status not in STATUSES:
            raise ValueError(f"status = {self.status!r} must be one of {STATUSES}")

    @property
    def ok(self) -> bool:
        return self.status == "ok"

    def to_row(self) -> dict:
        """Flat row: key, status, params, metrics (a metric named like a parameter gets the
        prefix "metric:"), wall_time_s, dofs, error."""
        row = {"key": self.key, "status": self.status, **self.params}
        for name, value in self.metrics.items():
            row[f"metric:{name}" if name in self.params or name in ("key", "status") else name] = value
        row.update(wall_time_s=self.wall_time_s, dofs=self.dofs, error=self.error)
        return row


def _json_metric(value):
    return None if isinstance(value, float) and not math.isfinite(value) else value


class ResultStore:
    """SQLite store of case results at ``path`` (created with its folder if missing).

    Use as a context manager, or call ``close()``. Only the process running the study writes;
    readers may open the file at any time (WAL mode).
    """

    def __init__(self, path):
        self.path = Path(path)
        if self.path.is_file() and self.path.stat().st_size == 0:
            raise ValueError(f"{self.path}: an empty file, not a flexfem result store; delete it "
                             "(or choose another --out) to start a new store")
        self.path.parent.mkdir(parents=True, exist_ok=True)
        try:
            self._db = sqlite3.connect(self.path, timeout=30.0)
        except sqlite3.DatabaseError as error:
            raise self._unreadable(error) from None
        try:
            self._db.execute("PRAGMA journal_mode=WAL")
            # NORMAL in WAL mode survives a process crash (not a power cut), keeps commits fast
            self._db.execute("PRAGMA synchronous=NORMAL")
            self._migrate()
            self._db.execute(SCHEMA)
            self._db.commit()
            self._check_columns()
        except sqlite3.DatabaseError as error:
            self._db.close()
            raise self._unreadable(error) from None
        except ValueError:
            self._db.close()
            raise

    def _read_only(self) -> bool:
        folder = self.path.parent
        return not (os.access(folder, os.W_OK) and (not self.path.exists()
                                                     or os.access(self.path, os.W_OK)))

    def _unreadable(self, error) -> ValueError:
        text = str(error)
        if self._read_only() or "readonly" in text or "read-only" in text:
            return ValueError(f"{self.path}: the store (or its folder) is read-only ({error}); "
                              "its results are kept: make the folder writable, or copy the "
                              "store to a writable folder and give that with --out")
        return ValueError(f"{self.path}: not a readable flexfem result store ({error}); move it "
                          "aside or delete it and run again: its cases will be computed anew")

    def _check_columns(self) -> None:
        """A table whose columns were altered (a column dropped, renamed or added) is refused by
        name, before any row is read."""
        found = tuple(r[1] for r in self._db.execute("PRAGMA table_info(cases)"))
        if found != COLUMNS:
            missing = [c for c in COLUMNS if c not in found]
            extra = [c for c in found if c not in COLUMNS]
            raise ValueError(f"{self.path}: its table 'cases' was altered (missing columns: "
                             f"{missing or 'none'}; unknown: {extra or 'none'}); a flexfem store "
                             f"has {', '.join(COLUMNS)}. Move it aside or delete it and run "
                             "again: its cases will be computed anew")

    def _migrate(self) -> None:
        """A store from before the "error" status: rebuild its table with the new CHECK."""
        row = self._db.execute("SELECT sql FROM sqlite_master WHERE name = 'cases'").fetchone()
        if row is None or "'error'" in row[0]:
            return
        self._db.execute("ALTER TABLE cases RENAME TO cases_before_error_status")
        self._db.execute(SCHEMA)
        self._db.execute("INSERT INTO cases SELECT * FROM cases_before_error_status")
        self._db.execute("DROP TABLE cases_before_error_status")
        self._db.commit()

    def _query(self, sql: str) -> list:
        try:
            return self._db.execute(sql).fetchall()
        except sqlite3.DatabaseError as error:
            raise self._unreadable(error) from None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        self._db.close()

    def record(self, case: CaseResult) -> None:
        """Insert (or replace) one case and commit at once."""
        finished = case.finished_at or datetime.datetime.now(datetime.timezone.utc).isoformat()
        self._db.execute(
            "INSERT OR REPLACE INTO cases VALUES (?,?,?,?,?,?,?,?,?,?,?,?)",
            (case.key, case.mechanism, canonical_json(case.params), canonical_json(case.options),
             case.status, json.dumps({k: _json_metric(v) for k, v in case.metrics.items()}),
             case.error, case.wall_time_s, case.dofs, case.worker, case.flexfem_version, finished))
        self._db.commit()

    def statuses(self) -> dict[str, str]:
        """key -> "ok" / "failed" / "error" for every stored case."""
        return dict(self._query("SELECT key, status FROM cases"))

    def results(self, keys=None) -> list[CaseResult]:
        """Stored cases (all, or those whose key is in ``keys``, in that order)."""
        rows = {r[0]: r for r in self._query("SELECT * FROM cases")}
        order = list(rows) if keys is None else [k for k in keys if k in rows]
        return [_case_from_row(rows[k], self.path) for k in order]


def _case_from_row(r, path) -> CaseResult:
    try:
        params, options = json.loads(r[2]), json.loads(r[3])
        for name, value in (("params", params), ("options", options)):
            if not isinstance(value, dict):
                raise TypeError(f"{name} = {value!r} is not a table")
        metrics = {k: (math.nan if v is None else v) for k, v in json.loads(r[5]).items()}
        return CaseResult(key=r[0], mechanism=r[1], params=params,
                          options=options, status=r[4], metrics=metrics, error=r[6],
                          wall_time_s=r[7], dofs=r[8], worker=r[9], flexfem_version=r[10],
                          finished_at=r[11])
    except (TypeError, ValueError, AttributeError) as error:  # JSONDecodeError is a ValueError
        raise ValueError(f"{path}: case {r[0]!r} is damaged ({type(error).__name__}: {error}); "
                         f"delete its row (DELETE FROM cases WHERE key = '{r[0]}') or the file, "
                         "and run again to recompute it") from None


def table_columns(cases: list[CaseResult], rows: list[dict]) -> list[str]:
    """Column names: key, status, every parameter, every metric (first-seen order), then
    wall_time_s, dofs and error."""
    head = ["key", "status", *dict.fromkeys(k for c in cases for k in c.params)]
    tail = ["wall_time_s", "dofs", "error"]
    middle = dict.fromkeys(k for row in rows for k in row if k not in head and k not in tail)
    return head + list(middle) + tail


def export_csv(cases: list[CaseResult], path) -> Path:
    """Write one CSV row per case (see CaseResult.to_row); missing values are empty."""
    rows = [{k: ("" if v is None else v) for k, v in c.to_row().items()} for c in cases]
    return write_rows(path, rows, table_columns(cases, rows))


def parquet_available() -> bool:
    """True when pyarrow is importable."""
    try:
        import pyarrow  # noqa: F401
    except ImportError:
        return False
    return True


def export_parquet(cases: list[CaseResult], path) -> Path:
    """Write the same table as export_csv to Parquet; ValueError if pyarrow is missing."""
    if not parquet_available():
        raise ValueError("Parquet export needs pyarrow (pip install pyarrow)")
    import pyarrow as pa
    import pyarrow.parquet as pq

    rows = [c.to_row() for c in cases]
    columns = table_columns(cases, rows)
    table = pa.table({name: [row.get(name) for row in rows] for name in columns})
    pq.write_table(table, Path(path))
    return Path(path)
