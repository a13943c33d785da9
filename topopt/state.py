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


def load_state(folder) -> dict | None:
    """The arrays of ``folder/state.npz``, or None where there is none."""
    path = Path(folder) / STATE_FILE
    if not path.is_file():
        return None
    with np.load(path, allow_pickle=False) as data:
        return {k: data[k] for k in data.files}
