"""CSV tables of result rows, the one writer every study uses."""
import csv
from pathlib import Path


def write_rows(path, rows: list[dict], columns=None) -> Path:
    """Write ``rows`` (dicts) to the CSV file ``path``; returns the path. ``columns``: the
    columns in order (default: every key, in first-seen order); keys not in ``columns`` are
    left out, missing values are empty. Raises ValueError for no rows and no columns."""
    if columns is None:
        columns = list(dict.fromkeys(k for row in rows for k in row))
    if not columns:
        raise ValueError(f"no rows and no columns to write to {path}")
    path = Path(path)
    with path.open("w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(columns), restval="", extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)
    return path
