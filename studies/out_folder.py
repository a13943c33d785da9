"""The output folder of a command (``--out DIR``): checked before anything is computed, so
that no result is lost to a folder that cannot be written, and created."""
import os
from pathlib import Path


def check_out(path) -> Path:
    """``path`` as a Path, after checking that it is a folder or can be made one: ValueError
    (one line) for an existing file, or where the nearest existing folder above it is not
    writable. Called before the analysis, so that no solve is lost to a bad ``--out``."""
    out = Path(path)
    if out.exists() and not out.is_dir():
        raise ValueError(f"--out {path}: is a file, not a folder; give a folder (created if "
                         "missing)")
    above = out
    while not above.exists() and above != above.parent:
        above = above.parent
    if not above.is_dir():
        raise ValueError(f"--out {path}: {above} is a file, not a folder")
    if not os.access(above, os.W_OK | os.X_OK):
        raise ValueError(f"--out {path}: cannot write in {above}")
    return out


def prepare_out(path) -> Path:
    """The folder ``path`` (:func:`check_out`), created if missing."""
    out = check_out(path)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise ValueError(f"--out {path}: cannot create the folder: "
                         f"{error.strerror or error}") from None
    return out
