"""Fuzzers of the project's own, derandomised so that CI is repeatable: a .geo token mutator
over the examples' .geo files (dangerous commands, strings in both quote kinds, redirections,
loops, options and brackets inserted, tokens dropped) and a mutator of the examples' model
files (keys dropped or misspelt, values of the wrong type, paths out of the folder). Each
mutant is refused with a ValueError of one line, or read by gmsh in its bounded child: never
another exception, a hang, or a marker file. Sized to run in well under a minute."""
from pathlib import Path
import tomllib

from hypothesis import HealthCheck, given, settings, strategies as st
import pytest
from flexfem.geometry.user_model import geometry as user_geometry
from flexfem.geometry.user_model import load_spec
from flexfem.geometry.user_model.geo_guard import CodeInGeometry, check_geo, tokens
from flexfem.geometry.user_model.geometry import inspect_geometry

EXAMPLES = Path(__file__).parents[3] / "examples"
GEOS = sorted(EXAMPLES.glob("*/*.geo"))
MODELS = sorted(p for p in EXAMPLES.glob("*/[!_]*.toml")
                if "body" in tomllib.loads(p.read_text())
                or str(tomllib.loads(p.read_text()).get("geometry", "")).endswith(".geo"))
POOL = ["SystemCall", "System", "Print", "Save", "Exit", "Include", "Merge", "GetValue",
        "ListFromFile", "FileExists", "General", "Solver", "Plugin", "Macro", "Call", "Mesh",
        "Geometry", "Field", "For", "In", "EndFor", "If", "EndIf", "Printf", "Sprintf", "Str",
        "DefineConstant", "SetNumber", "OnelabRun", "x", "lc", "Point", "Curve", "Physical",
        '"touch {marker}"', "'touch {marker}'", '"{marker}"', "'{marker}'", '"/etc/hostname"',
        '"../outside.geo"', ">", ">>", ";", "(", ")", "{", "}", "[", "]", "=", "+=", ".", ",",
        ":", "1e9", "-1", "0", "2e-6", "MeshSizeMax", "AbortOnError", "//", "/*", "*/", "'",
        '"', "#", "~", "::", "@", "$", "\\"]


def _mutant(geo: Path, edits, marker: Path) -> str:
    toks = [t.text for t in tokens(geo.read_text(), geo)]
    for kind, where, what in edits:
        i = where % (len(toks) + 1)
        if kind == "insert":
            toks.insert(i, POOL[what % len(POOL)].replace("{marker}", str(marker)))
        elif kind == "drop" and toks:
            del toks[min(i, len(toks) - 1)]
        elif toks:  # swap a string's quotes
            j = min(i, len(toks) - 1)
            if toks[j][:1] in "\"'":
                toks[j] = "'" + toks[j][1:-1] + "'"
    return "\n".join(" ".join(toks[k:k + 12]) for k in range(0, len(toks), 12)) + "\n"


EDITS = st.lists(st.tuples(st.sampled_from(["insert", "insert", "drop", "quote"]),
                           st.integers(0, 10_000), st.integers(0, 10_000)),
                 min_size=1, max_size=4)


@settings(max_examples=300, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(geo=st.sampled_from(GEOS), edits=EDITS)
def test_geo_mutants_are_refused_or_read_safely(tmp_path_factory, monkeypatch, geo, edits):
    monkeypatch.setattr(user_geometry, "READ_CPU_SECONDS", 5)
    folder = tmp_path_factory.mktemp("geo")
    marker = folder.parent / f"MARK_{folder.name}"
    path = folder / geo.name
    path.write_text(_mutant(geo, edits, marker))
    try:
        check_geo(path)
    except CodeInGeometry as error:
        assert "\n" not in str(error) and str(path) in str(error)
        return
    try:
        inspect_geometry(path)
    except ValueError as error:  # gmsh's own syntax errors, a limit of the child
        assert str(error)
    assert not marker.exists() and not any(folder.parent.glob("MARK*"))


def _mutate(raw: dict, edits) -> dict:
    """``raw`` (a model file's TOML) with keys dropped or misspelt and values replaced."""
    values = [-1, 0, 1e300, "x", "../outside.geo", "/etc/passwd", [], {}, True, "L * 1e9",
              "__import__('os')"]
    raw = {k: (dict(v) if isinstance(v, dict) else v) for k, v in raw.items()}
    for kind, where, what in edits:
        tables = [k for k, v in raw.items() if isinstance(v, dict) and v]
        if not tables:
            break
        table = tables[where % len(tables)]
        keys = sorted(raw[table])
        key = keys[what % len(keys)]
        if kind == "drop":
            del raw[table][key]
        elif kind == "insert":
            raw[table][key + "s"] = raw[table].pop(key)
        else:
            raw[table][key] = values[(where + what) % len(values)]
    return raw


def _toml(raw: dict) -> str:
    def value(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, str):
            return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
        if isinstance(v, dict):
            return "{" + ", ".join(f'"{k}" = {value(x)}' for k, x in v.items()) + "}"
        if isinstance(v, list):
            return "[" + ", ".join(value(x) for x in v) + "]"
        return repr(v)

    lines = [f'"{k}" = {value(v)}' for k, v in raw.items()
             if not isinstance(v, dict) and not (isinstance(v, list) and v and
                                                 all(isinstance(x, dict) for x in v))]
    for k, v in raw.items():
        if isinstance(v, dict):
            lines += [f'["{k}"]'] + [f'"{a}" = {value(b)}' for a, b in v.items()]
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for entry in v:
                lines += [f'[["{k}"]]'] + [f'"{a}" = {value(b)}' for a, b in entry.items()]
    return "\n".join(lines) + "\n"


@settings(max_examples=100, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(model=st.sampled_from(MODELS), edits=EDITS)
def test_model_file_mutants_are_refused_or_read(tmp_path_factory, model, edits):
    folder = tmp_path_factory.mktemp("model")
    for other in model.parent.iterdir():
        if other.is_file() and not other.name.startswith("_"):
            (folder / other.name).write_bytes(other.read_bytes())
    path = folder / model.name
    path.write_text(_toml(_mutate(tomllib.loads(model.read_text()), edits)))
    try:
        load_spec(path)
    except ValueError as error:
        assert str(error) and "\n" not in str(error).strip(), str(error)


def test_the_mutator_reaches_a_refusal(tmp_path):
    assert len(GEOS) >= 5 and len(MODELS) >= 5
    edits = [("insert", 0, POOL.index(";")), ("insert", 0, POOL.index("'touch {marker}'")),
             ("insert", 0, POOL.index("SystemCall"))]
    path = tmp_path / GEOS[0].name
    path.write_text(_mutant(GEOS[0], edits, tmp_path / "MARK"))
    assert path.read_text().startswith(f"SystemCall 'touch {tmp_path / 'MARK'}' ;")
    with pytest.raises(CodeInGeometry, match=":1: 'SystemCall' runs a shell command"):
        check_geo(path)
