"""The install ships every subpackage: each folder with an __init__.py is listed in pyproject."""
from pathlib import Path
import tomllib

ROOT = Path(__file__).resolve().parents[1]


def test_every_subpackage_is_listed_in_pyproject():
    listed = set(tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["packages"])
    found = {"flexfem." + init.parent.relative_to(ROOT).as_posix().replace("/", ".")
             for top in ("fem", "geometry", "studies", "data", "topopt", "reduced")
             for init in (ROOT / top).rglob("__init__.py")}
    assert found - listed == set() and listed - found == set()
