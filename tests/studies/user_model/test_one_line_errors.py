"""Every failure of a model file is one line naming the file, the entity and the cause, with
exit status 2 and no traceback: Newton's own message (not a TypeError of its rebuilding), a
sliver of a body, a notch wider than the body face it starts on, a group both supported and
loaded, a .msh whose header claims more than the file holds; and Newton on a small load step
converges instead of stalling at the round-off of F^T F - I."""
from pathlib import Path
import struct

import pytest

from flexfem.fem import NonConvergenceError
from flexfem.geometry.user_model import load_spec
from flexfem.geometry.user_model.msh_header import check_msh_counts
from flexfem.studies.cli import main
from flexfem.studies.user_model import analysis
from flexfem.studies.user_model.analysis import analyze_model

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"


def _variant(tmp_path, example: str, old: str, new: str) -> Path:
    text = (EXAMPLES / example).read_text()
    assert old in text
    path = tmp_path / Path(example).name
    path.write_text(text.replace(old, new))
    return path


def _one_line_error(capsys, *argv) -> str:
    assert main(["analyze", *map(str, argv)]) == 2
    captured = capsys.readouterr()
    err = captured.err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err, err
    return err


def test_newtons_own_message_reaches_the_user(tmp_path, capsys, monkeypatch):
    """_in_context keeps the error (its type and attributes) and prefixes the file."""
    def stall(*args, **kwargs):
        raise NonConvergenceError("no convergence beyond load factor 0.5: the residual stalls "
                                  "at 2.4e-06", 0.5, 0.52, 25, [2.4e-6])
    monkeypatch.setattr(analysis, "solve_nonlinear", stall)
    path = _variant(tmp_path, "bodies/guide.toml", "modes = 3", "steps = 10")
    err = _one_line_error(capsys, path, "--model", "continuum")
    assert f"{path}: no convergence beyond load factor 0.5: the residual stalls" in err
    assert "__init__" not in err and "missing" not in err
    with pytest.raises(NonConvergenceError) as caught:
        analyze_model(load_spec(path))
    assert caught.value.load_factor == 0.5 and caught.value.residual_history == [2.4e-6]


def test_newton_converges_on_small_load_steps():
    """50 steps of 0.02 N: the residual's round-off floor no longer stalls Newton (it did at
    2.4e-6 of the step's load, computing E from F^T F - I); any number of steps gives the
    same large-deflection answer."""
    spec = load_spec(EXAMPLES / "bodies/guide.toml", {"analysis.steps": 50})
    fifty = analyze_model(spec)["nonlinear"]
    five = analyze_model(load_spec(EXAMPLES / "bodies/guide.toml",
                                   {"analysis.steps": 5}))["nonlinear"]
    assert fifty["steps"] == 50
    for a, b in zip(fifty["mean_displacement"]["stage"], five["mean_displacement"]["stage"]):
        assert a == pytest.approx(b, rel=1e-6, abs=1e-15)


def test_a_sliver_of_a_body_names_the_body(tmp_path, capsys):
    """A stage box L + 5.39e-12 tall (a rounding error in a corner) once reached
    OpenCASCADE ("BRep_API: command not done") as a traceback."""
    path = _variant(tmp_path, "bodies/guide.toml", '["d / 2 + 0.005", "L + 0.008"]',
                    '["d / 2 + 0.005", "L + 5.39e-12"]')
    err = _one_line_error(capsys, path)
    assert f"{path.name} line" in err and "body 'stage'" in err and "5.39e-12 m tall" in err


def test_gmsh_failing_to_draw_a_body_names_it(monkeypatch):
    """Whatever OpenCASCADE refuses while drawing a body comes back naming the body."""
    import gmsh

    def refuse(*args, **kwargs):
        raise Exception("OpenCASCADE exception BRep_API: command not done")
    spec = load_spec(EXAMPLES / "bodies/guide.toml")
    monkeypatch.setattr(gmsh.model.occ, "addRectangle", refuse)
    with pytest.raises(ValueError, match=r"body 'ground': gmsh cannot draw it \(OpenCASCADE "
                                         r"exception BRep_API: command not done\); look for"):
        analysis.build_model(spec)


def test_a_notch_wider_than_its_body_face_names_the_flexure(tmp_path, capsys):
    """The ground cut back to x = 1e-13, where the notch starts: its side misses the body (it
    was "min() arg is an empty sequence")."""
    path = _variant(tmp_path, "bodies/notch.toml", "box = [[-0.01, -0.01], [0.01, 0.0]]",
                    "box = [[-0.01, -0.01], [1e-13, 0.0]]")
    for argv in ([path], [path, "--model", "beam"]):
        err = _one_line_error(capsys, *argv)
        assert "flexure 1 (circular_notch between 'ground' and 'lever')" in err
        assert "misses body 'ground'" in err and "min()" not in err


@pytest.mark.parametrize("model", ["continuum", "beam"])
def test_a_group_both_supported_and_loaded_is_refused_up_front(tmp_path, capsys, model):
    path = _variant(tmp_path, "bodies/guide.toml", '[[loads]]\ngroup = "stage"',
                    '[[loads]]\ngroup = "ground"')
    err = _one_line_error(capsys, path, "--model", model)
    assert "group 'ground' is both supported and loaded (along x)" in err
    assert "inf" not in err and "double precision" not in err


def test_a_partly_held_group_may_be_loaded_along_its_free_axis(tmp_path):
    """A roller (y held) pushed along x is no contradiction."""
    path = _variant(tmp_path, "bodies/guide.toml", '[[supports]]\ngroup = "ground"',
                    '[[supports]]\ngroup = "ground"\n\n[[supports]]\ngroup = "stage"\ny = 0.0')
    out = analyze_model(load_spec(path), model="beam")
    assert out["mean_displacement"]["stage"][0] > 0


def _mesh(folder: Path, binary: bool) -> Path:
    import gmsh

    from flexfem.fem import gmsh_session
    path = folder / ("bin.msh" if binary else "ascii.msh")
    with gmsh_session("test") as g:
        g.model.occ.addRectangle(0, 0, 0, 0.01, 0.002)
        g.model.occ.synchronize()
        g.option.setNumber("Mesh.MeshSizeMax", 0.001)
        g.model.mesh.generate(2)
        g.option.setNumber("Mesh.MshFileVersion", 4.1)
        g.option.setNumber("Mesh.Binary", int(binary))
        g.write(str(path))
    assert gmsh is not None
    return path


@pytest.mark.parametrize("binary", [False, True])
def test_a_msh_header_claiming_more_than_the_file_holds(tmp_path, binary):
    path = _mesh(tmp_path, binary)
    check_msh_counts(path)  # a sound file passes
    data = path.read_bytes()
    at = data.find(b"\n$Nodes") + len(b"\n$Nodes\n")
    if binary:
        data = data[:at + 8] + struct.pack("<Q", 10 ** 11) + data[at + 16:]
    else:
        end = data.find(b"\n", at)
        fields = data[at:end].split()
        data = data[:at] + b" ".join([fields[0], b"100000000000", *fields[2:]]) + data[end:]
    path.write_bytes(data)
    with pytest.raises(ValueError, match=rf"{path.name}: its \$Nodes header claims "
                                         r"100,000,000,000 nodes, which need at least .* bytes, "
                                         r"but the file has .*: it is damaged or truncated"):
        check_msh_counts(path)
