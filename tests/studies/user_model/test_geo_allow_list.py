"""The .geo allow-list and the bounded gmsh child: each probe of a security audit (a command
past a deny-list, a file read or written outside the folder, a prompt, an exit, a loop or a
mesh far beyond the budget) is refused with one line naming the file and line, or stopped by
the child's limits within seconds; nothing runs and no marker file appears."""
import json
import shutil
import time
from pathlib import Path

import pytest
from flexfem.fem.budget import BudgetError
from flexfem.geometry.user_model import geometry as user_geometry
from flexfem.geometry.user_model import load_spec
from flexfem.geometry.user_model.geo_guard import CodeInGeometry, check_geo, tokens
from flexfem.geometry.user_model.geometry import mesh_geometry
from flexfem.studies.cli import main

EXAMPLE = Path(__file__).parents[3] / "examples" / "parallel_guide"


def _model(tmp_path, payload: str) -> tuple[Path, Path]:
    """A copy of the parallel-guide example whose .geo ends with ``payload`` ({marker}: a
    file the payload would create); returns the model file and the marker."""
    folder = tmp_path / "model"
    shutil.copytree(EXAMPLE, folder)
    marker = tmp_path / "MARKER"
    geo = folder / "guide.geo"
    geo.write_text(geo.read_text() + "\n" + payload.replace("{marker}", str(marker)) + "\n")
    return folder / "guide.toml", marker


def _refused(capsys, argv, where: str) -> str:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err and where in err, err
    return err


# each is refused at the last line of guide.geo (the payload's)
PROBES = {
    "single-quoted strings": "Printf('\"'); SystemCall 'touch {marker}'; Printf('\"');",
    "ListFromFile": 'x() = ListFromFile("/etc/hostname");',
    "FileExists": 'If (FileExists("/etc/shadow")) y = 1; EndIf',
    "AbortOnError": 'General.AbortOnError += 2; Error("bye");',
    "GetValue": 'v = GetValue("answer?", 1);',
    "RefineMesh": "RefineMesh;",
    "MathEval field": 'Field[9] = MathEval; Field[9].F = "1e-9";',
    "Mesh command": "Mesh 2;",
    "a loop of 1e9 passes": "For i In {1:1e9}\n x = i;\nEndFor",
    "a variable used as a command": "Shelly = 1; Shelly \"touch {marker}\";",
    "an unknown command": 'Frobnicate "touch {marker}";',
    "an option outside Mesh and Geometry": 'Print.Format = "png";',
    "Printf to a file in single quotes": "Printf('owned') > '{marker}';",
    "a View": 'View "x" { SP(0, 0, 0){1}; };',
}


@pytest.mark.parametrize("name", sorted(PROBES))
def test_analyze_refuses_each_probe(tmp_path, capsys, name):
    model, marker = _model(tmp_path, PROBES[name])
    lines = (model.parent / "guide.geo").read_text().splitlines()
    first = len(lines) - PROBES[name].count("\n")
    err = _refused(capsys, ["analyze", str(model), "--json"], "guide.geo:")
    assert any(f"guide.geo:{n}:" in err for n in range(first, len(lines) + 1)), err
    assert not marker.exists()


def test_single_quoted_strings_are_strings_for_the_lexer():
    kinds = [(t.kind, t.text) for t in tokens("Printf('\"'); x = \"a'b\";", "x.geo")]
    assert ("string", "'\"'") in kinds and ("string", "\"a'b\"") in kinds


def test_includes_and_merges_are_judged_by_content(tmp_path, capsys):
    model, marker = _model(tmp_path, 'Include "helper.txt";')
    helper = model.parent / "helper.txt"
    helper.write_text(f'a = 1;\nSystemCall "touch {marker}";\n')
    _refused(capsys, ["analyze", str(model)], "helper.txt:2: 'SystemCall'")
    helper.write_text("a_helper = 2;\n")  # a safe script included: fine
    assert load_spec(model).groups
    model2, marker = _model(tmp_path / "b", 'Merge "extra.msh";')
    (model2.parent / "extra.msh").write_text(f'SystemCall "touch {marker}";\n')
    _refused(capsys, ["analyze", str(model2)], "extra.msh:1: 'SystemCall'")
    assert not marker.exists()


def test_compressed_merges_are_refused(tmp_path, capsys):
    import gzip

    model, _ = _model(tmp_path, 'Merge "x.geo.gz";')
    (model.parent / "x.geo.gz").write_bytes(gzip.compress(b"a = 1;\n"))
    _refused(capsys, ["analyze", str(model)], "compressed")
    assert sorted(p.name for p in model.parent.iterdir()) == sorted(
        p.name for p in EXAMPLE.iterdir()) + ["x.geo.gz"]  # nothing unpacked


def test_a_geometry_is_what_its_name_says(tmp_path, capsys):
    model, marker = _model(tmp_path, "")
    fake = model.parent / "x.msh"
    fake.write_text((model.parent / "guide.geo").read_text()
                    + f'\nSystemCall "touch {marker}";\n')
    model.write_text(model.read_text().replace('"guide.geo"', '"x.msh"'))
    err = _refused(capsys, ["analyze", str(model)], "x.msh")
    assert "script" in err
    assert not marker.exists()


def test_export_refuses_a_geo_model_before_gmsh_reads_it(tmp_path, capsys):
    model, marker = _model(tmp_path, 'SystemCall "touch {marker}";')
    _refused(capsys, ["export", str(model), str(tmp_path / "out.dxf"), "--allow-code"],
             "export needs a model of bodies and flexures")
    assert not marker.exists()  # not even --allow-code made gmsh run it


def test_gmsh_prints_nothing_into_json(tmp_path, capsys):
    model, _ = _model(tmp_path, 'Printf("hello from the geo");')
    assert main(["analyze", str(model), "--json"]) == 0
    out = capsys.readouterr().out
    assert "hello" not in out and isinstance(json.loads(out), dict)


def test_a_computed_endless_loop_is_stopped_by_the_child(tmp_path, monkeypatch):
    monkeypatch.setattr(user_geometry, "READ_CPU_SECONDS", 3)
    model, _ = _model(tmp_path, "n = 1e9;\nFor i In {1:n}\n x = i;\nEndFor")
    start = time.monotonic()
    with pytest.raises(BudgetError, match="reading guide.geo: gmsh stopped at its CPU-time"):
        load_spec(model)
    assert time.monotonic() - start < 30


def test_a_tiny_size_in_the_geo_is_refused_by_the_estimate(tmp_path, capsys):
    model, _ = _model(tmp_path, "Mesh.MeshSizeMax = 2e-6;")
    start = time.monotonic()
    _refused(capsys, ["analyze", str(model)], "above the budget")
    assert time.monotonic() - start < 60


def test_a_transfinite_curve_is_stopped_after_the_curves_are_meshed(tmp_path):
    model, _ = _model(tmp_path, "Transfinite Curve{1} = 400000;")
    with pytest.raises(BudgetError, match="nodes on the curves alone"):
        mesh_geometry(load_spec(model), max_dofs=200_000)


def test_a_tiny_refine_size_in_the_model_file_is_refused(tmp_path, capsys):
    model, _ = _model(tmp_path, "")
    text = model.read_text()
    assert text.count("[mesh]\n") == 1
    model.write_text(text.replace("[mesh]\n", '[mesh]\nrefine = [{group = "fixed", '
                                               'size = 1e-6, distance = 0.002}]\n'))
    start = time.monotonic()
    _refused(capsys, ["analyze", str(model)], "above the budget")
    assert time.monotonic() - start < 60


def test_every_example_passes_and_meshes_in_the_child():
    for geo in sorted(EXAMPLE.parent.glob("*/*.geo")):
        check_geo(geo)
    spec = load_spec(EXAMPLE / "guide.toml")
    mesh = mesh_geometry(spec)
    assert mesh.mesh.t.shape[1] > 100 and set(spec.groups) <= set(mesh.boundaries) | set(
        mesh.subdomains)


def test_allow_code_still_runs_what_the_user_trusts(tmp_path):
    model, marker = _model(tmp_path, 'SystemCall "touch {marker}";')
    with pytest.raises(CodeInGeometry):
        load_spec(model)
    load_spec(model, allow_code=True)
    assert marker.exists()


def test_a_msh_claiming_1e11_nodes_is_refused_by_analyze(tmp_path, capsys):
    model, _ = _model(tmp_path, "")
    spec = load_spec(model)
    mesh_file = model.parent / "guide.msh"
    from flexfem.fem import gmsh_session
    with gmsh_session("probe") as gmsh:  # the example's own mesh, written by gmsh
        gmsh.merge(str(spec.geometry))
        gmsh.model.mesh.generate(2)
        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        gmsh.write(str(mesh_file))
    data = mesh_file.read_bytes()
    at = data.find(b"\n$Nodes") + len(b"\n$Nodes\n")
    end = data.find(b"\n", at)
    fields = data[at:end].split()
    mesh_file.write_bytes(data[:at] + b" ".join([fields[0], b"100000000000", *fields[2:]])
                          + data[end:])
    text = model.read_text().replace('"guide.geo"', '"guide.msh"')
    model.write_text(text[:text.index("[parameters]")] + text[text.index("[material]"):])
    _refused(capsys, ["analyze", str(model)], "guide.msh: its $Nodes header claims "
                                                "100,000,000,000 nodes")


def test_the_commands_of_an_ordinary_geometry_pass(tmp_path):
    """A built-in kernel drawing with what geometry scripts commonly use: lists, loops,
    conditionals, extrusion with layers, duplication, transfinite curves and mesh options."""
    geo = tmp_path / "t.geo"
    geo.write_text('''SetFactory("Built-in");
lc = 0.1;
Point(1) = {0, 0, 0, lc}; Point(2) = {1, 0, 0, lc}; Point(3) = {1, 1, 0, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 1};
Line Loop(1) = {1, 2, 3}; Plane Surface(1) = {1};
Transfinite Line{1} = 10 Using Progression 1.2;
Recombine Surface{1};
Characteristic Length {1, 2} = 0.05;
Geometry.OCCTargetUnit = "M";
Mesh.Algorithm = 6;
n = 4;
For i In {1:n}
  p[i] = newp;
EndFor
If (n > 2)
  Printf("n = %g", n);
ElseIf (n == 1)
  Warning("one");
Else
  Error("none");
EndIf
out[] = Extrude {0, 0, 1} { Surface{1}; Layers{5}; Recombine; };
Physical Volume("body") = {out[1]};
Translate {1, 0, 0} { Duplicata { Surface{1}; } }
''')
    check_geo(geo)


def _sleep_long():
    time.sleep(120)


def _sum_up(n):
    return sum(range(n))


def test_a_child_that_stops_working_is_stopped(monkeypatch):
    from flexfem.geometry.user_model import bounded

    monkeypatch.setattr(bounded, "STALL_SECONDS", 1.5)
    start = time.monotonic()
    with pytest.raises(bounded.ChildLimit, match="probe: gmsh stopped working"):
        bounded.run_bounded(_sleep_long, memory_bytes=0, cpu_seconds=200, wall_seconds=200,
                            what="probe")
    assert time.monotonic() - start < 20
    assert bounded.run_bounded(_sum_up, 10**6, memory_bytes=0, cpu_seconds=60,
                               wall_seconds=60, what="probe") == sum(range(10**6))
