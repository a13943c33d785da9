"""A damaged state.npz in a topopt --out folder: one error line naming the file, saying it is
damaged and to delete it, exit 2; never numpy's advice to load it with pickles."""
import numpy as np
import pytest

from flexfem.studies.cli import main
from flexfem.topopt.state import load_state, save_state
from pathlib import Path

MBB = Path(__file__).resolve().parents[2] / "examples" / "topopt" / "mbb.toml"


def _damage(folder: Path, how: str) -> Path:
    path = folder / "state.npz"
    if how == "truncated":
        save_state(folder, z=np.ones(10), digest="x")
        path.write_bytes(path.read_bytes()[:100])
    elif how == "objects":  # a pickled object array, which allow_pickle=False refuses
        np.savez(path, z=np.array([{"a": 1}], dtype=object))
    elif how == "text":
        path.write_text("not an npz file\n")
    elif how == "incomplete":
        save_state(folder, z=np.ones(10))
    return path


@pytest.mark.parametrize("how", ["truncated", "objects", "text", "incomplete"])
def test_a_damaged_state_is_one_line_naming_the_file(tmp_path, capsys, how):
    path = _damage(tmp_path, how)
    assert main(["topopt", str(MBB), "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert str(path) in err and "damaged" in err and "delete it" in err
    assert "allow_pickle" not in err.lower()  # numpy's advice to load it unsafely


def test_load_state_names_what_is_missing(tmp_path):
    save_state(tmp_path, z=np.ones(3))
    assert load_state(tmp_path, ("z",))["z"].tolist() == [1.0, 1.0, 1.0]
    with pytest.raises(ValueError, match=r"state.npz: the saved optimiser state is damaged "
                                         r"\(it lacks digest\); delete it"):
        load_state(tmp_path, ("z", "digest"))
