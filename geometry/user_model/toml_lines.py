"""Line numbers of keys and tables in a TOML text (tomllib gives none), for error messages.

A plain text search, enough for hand-written model files: a table ``[name]`` or the k-th
array-of-tables entry ``[[name]]`` is found by its header line, a key by ``key =`` at the start
of a line inside that table. Inline tables and dotted keys are not searched: None is returned.
"""
import re

_HEADER = re.compile(r"^\s*\[\[?\s*([^\]]+?)\s*\]\]?\s*(#.*)?$")


def _headers(lines: list[str]) -> list[tuple[int, str, bool]]:
    """(line index, table name, is array-of-tables) of every table header."""
    out = []
    for i, line in enumerate(lines):
        m = _HEADER.match(line)
        if m:
            out.append((i, m.group(1).strip().strip('"'), line.lstrip().startswith("[[")))
    return out


def find_line(text: str, table: str | None = None, key: str | None = None,
              index: int = 0) -> int | None:
    """1-based line of ``key`` in ``table`` (None: the top level; for an array of tables, its
    ``index``-th entry), or of the table header when ``key`` is None; None if not found."""
    if table is None and key is None:
        return None
    lines = text.splitlines()
    headers = _headers(lines)
    if table is None:
        start, end = 0, headers[0][0] if headers else len(lines)
    else:
        found = [h for h in headers if h[1] == table]
        if index >= len(found):
            return None
        start = found[index][0]
        later = [h[0] for h in headers if h[0] > start]
        end = later[0] if later else len(lines)
        if key is None:
            return start + 1
        start += 1
    pattern = re.compile(rf"^\s*\"?{re.escape(key)}\"?\s*=")
    for i in range(start, end):
        if pattern.match(lines[i]):
            return i + 1
    return None
