"""Model files: parsing, validation (errors name the file and line), geometry inspection and
meshing, and the select-rule grammar."""
from pathlib import Path
import shutil

import pytest

from flexfem.geometry.user_model import define_constant_names, load_spec, mesh_geometry
from flexfem.geometry.user_model.selection import compile_rule
from flexfem.geometry.user_model.toml_lines import find_line

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
GUIDE = EXAMPLES / "parallel_guide"

MODEL = """\
geometry = "guide.geo"
dim = 2

[parameters]
L = 0.04

[material]
name = "structural_steel"

[section]
kind = "plane_stress"
thickness = 0.01

[[supports]]
group = "fixed"

[[loads]]
group = "stage"
force = [1.0, 0.0]
"""


def write_model(tmp_path, text=MODEL, name="guide.toml") -> Path:
    shutil.copy(GUIDE / "guide.geo", tmp_path / "guide.geo")
    path = tmp_path / name
    path.write_text(text)
    return path


def test_example_guide_spec():
    spec = load_spec(GUIDE / "guide.toml")
    assert spec.dim == 2 and spec.geometry == (GUIDE / "guide.geo").resolve()
    assert spec.parameters == {"L": 0.04, "t": 0.001}
    assert spec.material.E == 200e9 and spec.section.kind == "plane_stress"
    assert spec.section.thickness == 0.01 and spec.mesh.order == 2
    assert spec.groups == {"fixed": 1, "stage": 1, "body": 2}
    assert spec.supports[0].group == "fixed" and spec.supports[0].components is None
    assert spec.loads[0].kind == "force" and spec.loads[0].vector == (1.0, 0.0)
    assert spec.analysis.modes == 3
    # the .geo's defaults, with lc_leaf = t / 2 evaluated by gmsh
    assert spec.constants["d"] == 0.02 and spec.constants["lc_leaf"] == pytest.approx(0.0005)


def test_define_constant_names():
    assert define_constant_names(GUIDE / "guide.geo") == ["L", "t", "d", "hb", "hs", "m",
                                                          "lc_leaf", "lc_block"]


def test_overrides_reach_gmsh_and_tables():
    spec = load_spec(GUIDE / "guide.toml", {"t": 0.002, "material.E": 1e11, "mesh.order": 1})
    assert spec.parameters["t"] == 0.002
    assert spec.constants["lc_leaf"] == pytest.approx(0.001)  # t / 2 with the new t
    assert spec.material.E == 1e11 and spec.material.nu == 0.3 and spec.mesh.order == 1


def test_mesh_has_groups_and_parameters_move_geometry():
    spec = load_spec(GUIDE / "guide.toml")
    mesh = mesh_geometry(spec)
    assert set(mesh.boundaries) == {"fixed", "stage"} and set(mesh.subdomains) == {"body"}
    top = mesh.mesh.p[1].max()
    assert top == pytest.approx(0.04 + 0.008)  # L + hs
    longer = mesh_geometry(load_spec(GUIDE / "guide.toml", {"L": 0.05}))
    assert longer.mesh.p[1].max() == pytest.approx(0.05 + 0.008)
    finer = mesh_geometry(spec, size_factor=0.5)
    assert finer.mesh.t.shape[1] > 3 * mesh.mesh.t.shape[1]


def test_mesh_size_and_refinement(tmp_path):
    coarse = load_spec(write_model(tmp_path, MODEL + "[mesh]\norder = 1\n"))
    capped = load_spec(write_model(tmp_path, MODEL + "[mesh]\nsize = 0.001\n"))
    refined = load_spec(write_model(tmp_path, MODEL + '[mesh]\nrefine = [{ group = "stage", '
                                    "size = 0.0005, distance = 0.001 }]\n"))
    n0, n1, n2 = (mesh_geometry(s).mesh.t.shape[1] for s in (coarse, capped, refined))
    assert n1 > 1.5 * n0 and n2 > n0 + 50


@pytest.mark.parametrize("edit, expected", [
    # (old text -> new text), fragments of the message
    (('group = "stage"', 'group = "stagee"'),
     ["line 18:",
      "[[loads]] group 'stagee' is not a group of guide.geo; groups: body, fixed, stage"]),
    (("L = 0.04", "Lx = 0.04"),
     ["line 5:", "'Lx' is not a DefineConstant of guide.geo", "L, d, hb, hs, lc_block"]),
    (("dim = 2", "dim = 2\ncolour = 1"), ["line 3:", "unknown key 'colour'"]),
    (('force = [1.0, 0.0]', 'force = [1.0, 0.0]\n[analysis]\ncompliance = "fixed"'),
     ["line 21:", "[analysis] compliance group 'fixed' is held by a [[supports]]"]),
    (('thickness = 0.01', 'thickness = 0.01\nwidth = 2'),
     ["line 13:", "[section]: unknown key 'width'"]),
    (('[[loads]]', '[extra]\na = 1\n[[loads]]'), ["line 17:", "unknown table 'extra'"]),
    (('name = "structural_steel"', 'name = "spring_steel"'),
     ["line 8:", "'spring_steel' is not in the library", "structural_steel",
      "missing: E, nu)"]),
    (('name = "structural_steel"', 'name = "structural_steel"\nnu = 0.7'), ["line 7:", "nu = 0.7"]),
    (('name = "structural_steel"', 'name = "structural_steel"\nE = 200e3'),
     ["line 9:", "yield_strength / E = 1.25e+03", "a unit mistake"]),
    (('force = [1.0, 0.0]', 'pressure = 1e5'), ["line 19:", "pressure is not available yet"]),
    (('force = [1.0, 0.0]', 'force = [1.0, 0.0, 0.0]'), ["line 19:", "list of 2 numbers"]),
    (('kind = "plane_stress"', 'kind = "solid"'), ["line 11:", "does not fit dim = 2"]),
    (('group = "fixed"', 'group = "body"\nx = 0.0'), []),  # a subdomain may be supported
    (('[[loads]]\ngroup = "stage"', '[[loads]]\ngroup = "body"'), ["line 18:", "subdomain"]),
    (('geometry = "guide.geo"', 'geometry = "nothere.geo"'), ["line 1:", "does not exist"]),
    (('geometry = "guide.geo"', 'geometry = "guide.iges"'), ["line 1:", "unknown file type"]),
    (("dim = 2", "dim = 2\n[[select]]\ngroup = 'a'\ndim = 1\nwhere = 'x < 0'"),
     ["line 3:", "[[select]] rules are for CAD files"]),
    (("L = 0.04", "L = 0.04 0.05"), ["not valid TOML", "line 5"]),
    (('[[supports]]', '[mesh]\norder = 3\n[[supports]]'), ["line 15:", "order = 3 must be 1 or 2"]),
    (('force = [1.0, 0.0]', 'force = [1.0, 0.0]\n[analysis]\nmodes = 0'),
     ["line 21:", "modes = 0 must be a whole number >= 1"]),
    (('[[supports]]\ngroup = "fixed"\n', ''), ["at least one [[supports]]"]),
    (('[material]\nname = "structural_steel"\n', ''), ["[material] is required"]),
])
def test_bad_model_files_name_file_and_line(tmp_path, edit, expected):
    old, new = edit
    assert old in MODEL
    path = write_model(tmp_path, MODEL.replace(old, new, 1))
    if not expected:
        load_spec(path)  # valid
        return
    with pytest.raises(ValueError) as info:
        load_spec(path)
    message = str(info.value)
    assert message.startswith(str(path)), message
    for fragment in expected:
        assert fragment in message, message


def test_unknown_override_lists_constants(tmp_path):
    with pytest.raises(ValueError, match=r"guide.toml: override 'Lx' is not a DefineConstant "
                                         r"of guide.geo; its constants: L, d, hb"):
        load_spec(write_model(tmp_path), {"Lx": 0.05})
    with pytest.raises(ValueError, match="only \\[parameters\\] names and material.KEY"):
        load_spec(write_model(tmp_path), {"supports.x": 0.0})


def test_geometry_kind_mismatches(tmp_path):
    step = EXAMPLES / "step_guide" / "guide_step.toml"
    with pytest.raises(ValueError, match=r"guide_step.toml: \[parameters\] are DefineConstant "
                                         r"overrides of a .geo file; guide.step has none"):
        load_spec(step, {"L": 0.03})
    shutil.copy(EXAMPLES / "cross_pivot" / "pivot3d.geo", tmp_path / "pivot3d.geo")
    path = write_model(tmp_path, MODEL.replace('"guide.geo"', '"pivot3d.geo"')
                       .replace("L = 0.04", "L = 0.03"))
    with pytest.raises(ValueError, match=r"guide.toml line 2: dim = 2 but pivot3d.geo is 3-D"):
        load_spec(path)


def test_unreadable_geometry_names_the_file(tmp_path):
    path = write_model(tmp_path)
    (tmp_path / "guide.geo").write_text("Point(1) = {0, 0, 0;\n")
    with pytest.raises(ValueError, match=r"guide.geo: gmsh cannot read this geometry file: "
                                         r".*line 1"):
        load_spec(path)
    (tmp_path / "part.step").write_text("not a step file\n")
    step = tmp_path / "part.toml"
    step.write_text(MODEL.replace('"guide.geo"', '"part.step"').replace("[parameters]\nL = 0.04\n",
                                                                          ""))
    with pytest.raises(ValueError, match=r"part.step: its content is text gmsh would run as a "
                                         r"\.geo script, not a STEP file"):
        load_spec(step)


def test_find_line():
    text = 'a = 1\n[t]\nk = 2\n[[arr]]\nk = 3\n[[arr]]\n"k" = 4\n'
    assert find_line(text, None, "a") == 1
    assert find_line(text, "t") == 2 and find_line(text, "t", "k") == 3
    assert find_line(text, "arr", "k", 0) == 5 and find_line(text, "arr", "k", 1) == 7
    assert find_line(text, "arr", "k", 2) is None and find_line(text, "t", "zz") is None
    assert find_line(text) is None


@pytest.mark.parametrize("rule, value", [
    ("x < 1e-9", True), ("abs(y - 0.02) < 1e-6", True), ("x > 0 or y >= 0.02", True),
    ("not (x < 1) and y == 0.02", False), ("-x <= -0.5 * 2 + 1", True),
    ("xmax - xmin < 1e-6 and zmax <= 0.003", False),
])
def test_select_rules(rule, value):
    values = dict(x=0.0, y=0.02, z=0.0, xmin=0.0, ymin=0.0, zmin=0.0, xmax=0.01, ymax=0.02,
                  zmax=0.003)
    assert compile_rule(rule)(values) is value


@pytest.mark.parametrize("rule", ["x", "x and y", "__import__('os').system('true')",
                                  "x < ", "foo < 1", "x < 1 < 2", "abs(x < 1)", "x.real < 1",
                                  "", "y < 1 1"])
def test_select_rules_refuse_anything_else(rule):
    with pytest.raises(ValueError):
        compile_rule(rule)
