"""Published parameters and reference values, each with the document it came from, and
tables flexfem computes once (each names the script that writes it and what it computes:
notch_factors.toml).

Every number a source document gives lives in a TOML file here, never in code. Lengths in the
files are in the units the source prints (the key says which, e.g. ``l_mm``); loaders convert
them to SI once.
"""
import functools
from pathlib import Path

import tomllib

# the package's folder: its files are plain files beside this module (importlib.resources
# would import its readers on the first call, ~5 ms of a beam model's first analysis)
FOLDER = Path(__file__).resolve().parent


def load_toml(name: str) -> dict:
    """Parse ``data/<name>`` (a TOML file shipped with the package) into a dict."""
    with (FOLDER / name).open("rb") as f:
        return tomllib.load(f)


@functools.lru_cache(maxsize=None)
def shared_toml(name: str) -> dict:
    """``load_toml(name)`` parsed once per process, for lookups on a hot path (a parse costs
    ~0.5 ms a design point); shared between callers, so read it, never change it."""
    return load_toml(name)
