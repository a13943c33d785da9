"""The optimiser's state after each iteration, written atomically (a temporary file, then
``os.replace``) so that an interrupted run resumes from its last completed iteration."""
import os
from pathlib import Path

import numpy as np

STATE_FILE = "state.npz"


def save_state(folder, **arrays) -> Path:
    """Write ``arrays`` (numbers, strings, arrays) to ``folder/state.npz`` atomically."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    target = folder / STATE_FILE
    tmp = folder / f".{STATE_FILE}.{os.getpid()}.tmp"
    with open(tmp, "wb") as handle:
        np.savez(handle, **{k: np.asarray(v) for k, v in arrays.items()})
        handle.flush()
        os.fsync(handle.fileno())
    os.replace(tmp, target)
    return target


def load_state(folder, required=()) -> dict | None:
    """The arrays of ``folder/state.npz``, or None where there is none. A file numpy cannot
    read (cut short, overwritten, not an .npz, holding objects) or lacking one of the
    ``required`` keys: ValueError naming it, damaged, and what to do (numpy's own message
    would advise loading it with pickles, which runs code from the file)."""
    path = Path(folder) / STATE_FILE
    if not path.is_file():
        return None
    try:
        with np.load(path, allow_pickle=False) as data:
            state = {k: data[k] for k in data.files}
    except Exception as error:  # zipfile, OSError, EOFError, pickled objects: all damage
        cause = (f"{type(error).__name__}: {error}".split("\n")[0] if "pickle" not in str(error)
                 else "it is no archive of plain arrays; flexfem never unpickles a file, "
                 "which could run code")
        raise damaged(path, cause) from None
    missing = [k for k in required if k not in state]
    if missing:
        raise damaged(path, f"it lacks {', '.join(missing)}")
    return state


def damaged(path: Path, cause: str) -> ValueError:
    return ValueError(f"{path}: the saved optimiser state is damaged ({cause.rstrip('.')}); "
                      "delete it to start the optimisation again")
