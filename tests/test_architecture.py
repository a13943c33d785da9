"""The package's shape: no import loops (function-level imports and the registry's targets
included), small modules and functions, relative imports inside the package, and no path
outside the repository in code or docs."""
import ast
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("fem", "geometry", "studies", "data", "topopt", "reduced")
MAX_MODULE_LINES = 400
MAX_FUNCTION_LINES = 80


def package_files() -> list[Path]:
    return sorted(p for top in PACKAGES for p in (ROOT / top).rglob("*.py"))


def module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _resolve(path: Path, node: ast.ImportFrom) -> str:
    """Absolute module (without 'flexfem.') that a relative ``from`` import names."""
    package = module_name(path).split(".")
    if path.name != "__init__.py":
        package = package[:-1]
    base = package[:len(package) - node.level + 1]
    return ".".join(base + ([node.module] if node.module else []))


def _registry_edges(modules: set) -> dict:
    """studies.mechanisms -> every module its registry targets name."""
    from flexfem.studies.mechanisms import BUILTIN
    targets = set()
    for m in BUILTIN:
        for target in (m.evaluate, m.commands, m.optimizer, *(s.target for s in m.sections)):
            if target:
                targets.add(f"studies.{m.package}.{target.partition(':')[0]}")
    missing = targets - modules
    assert not missing, f"registry targets name no module: {sorted(missing)}"
    return {"studies.mechanisms": targets}


def import_graph() -> dict:
    """module -> set of package modules it imports, at any depth of the file."""
    modules = {module_name(p) for p in package_files()}
    graph = {}
    for path in package_files():
        edges = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level:
                target = _resolve(path, node)
                for alias in node.names:
                    child = f"{target}.{alias.name}"
                    edges.add(child if child in modules else target)
        graph[module_name(path)] = {e for e in edges if e in modules}
    for module, targets in _registry_edges(modules).items():
        graph[module] |= targets
    return graph


def cycles(graph: dict) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def test_no_import_loops():
    assert cycles(import_graph()) == []


def test_the_cycle_finder_finds_a_loop():
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]


def test_fem_knows_no_mechanism_and_the_engine_no_mechanism_by_name():
    graph = import_graph()
    for module, targets in graph.items():
        if module.startswith("fem"):
            assert not {t for t in targets if not t.startswith(("fem", "data"))}, module
        if module.startswith(("studies.engine", "studies.report")):
            named = {t for t in targets if t.startswith("studies.")
                     and not t.startswith(("studies.engine", "studies.report", "studies.mechanisms"))}
            assert not named, f"{module} imports mechanisms {sorted(named)}"


# what geometry/ may use of fem: meshes, gmsh, materials and the mesh budget, never a solver
DRAWING_MODULES = {"fem.gmsh_session", "fem.mesh", "fem.materials", "fem.budget", "fem.checks",
                   "fem.curved"}
DRAWING_NAMES = {"FEMesh", "gmsh_session", "mesh_from_gmsh", "read_mesh", "facets_where",
                 "drop_unused_vertices", "Material", "material", "material_names"}


def solver_imports(sources) -> list[str]:
    """The imports of ``sources`` ((path, text) pairs) that reach a solver: a fem module
    beyond meshes, gmsh, materials, the budget and the input checks (or a solver's name from
    flexfem.fem), or the reduced models."""
    found = []
    for path, text in sources:
        for node in ast.walk(ast.parse(text)):
            if not (isinstance(node, ast.ImportFrom) and node.level):
                continue
            target = _resolve(path, node)
            names = {a.name for a in node.names}
            modules = {f"{target}.{n}" for n in names} if target == "fem" else {target}
            solving = (target.startswith("reduced") or target.startswith("studies")
                       or target.startswith("fem") and not (
                           target in DRAWING_MODULES
                           or target == "fem" and names <= DRAWING_NAMES | {
                               m.split(".")[1] for m in DRAWING_MODULES})
                       or target == "fem" and modules & {"fem.beam", "fem.beam.spatial"})
            if solving:
                found.append(f"{path.relative_to(ROOT)}:{node.lineno} {target} {sorted(names)}")
    return found


def test_geometry_draws_and_never_solves():
    paths = sorted((ROOT / "geometry").rglob("*.py"))
    assert solver_imports((p, p.read_text()) for p in paths) == []


def test_the_solver_import_finder_finds_one():
    probe = (ROOT / "geometry" / "probe.py",
             "from ..fem import solve_static\nfrom ..fem.mesh import FEMesh\n"
             "from ..reduced.layout import ROOT_EXTENSION\n")
    assert [f.split()[1] for f in solver_imports([probe])] == ["fem", "reduced.layout"]


def test_imports_inside_the_package_are_relative():
    offenders = [f"{p.relative_to(ROOT)}:{n.lineno}" for p in package_files()
                 for n in ast.walk(ast.parse(p.read_text()))
                 if isinstance(n, ast.Import) and any(a.name.startswith("flexfem") for a in n.names)
                 or isinstance(n, ast.ImportFrom) and (n.module or "").startswith("flexfem")]
    assert offenders == []


def test_modules_and_functions_stay_small():
    long_modules = [f"{p.relative_to(ROOT)} ({n})" for p in package_files()
                    if (n := len(p.read_text().splitlines())) > MAX_MODULE_LINES]
    long_functions = [f"{p.relative_to(ROOT)}:{f.name} ({f.end_lineno - f.lineno + 1})"
                      for p in package_files() for f in ast.walk(ast.parse(p.read_text()))
                      if isinstance(f, (ast.FunctionDef, ast.AsyncFunctionDef))
                      and f.end_lineno - f.lineno + 1 > MAX_FUNCTION_LINES]
    assert long_modules == [] and long_functions == []


TEXT_FILES = ("*.py", "*.md", "*.toml", "*.sh", "*.geo")
OUTSIDE = re.compile(r"\.\./shared|/work/|/home/\w+|/root/|/tmp/bash_jobs|[A-Z]:\\\\Users")


@pytest.mark.parametrize("pattern", TEXT_FILES)
def test_no_path_outside_the_repository(pattern):
    skip = {".git", ".venv", "report", "node_modules"}
    hits = []
    for path in ROOT.rglob(pattern):
        if skip & set(path.relative_to(ROOT).parts) or path == Path(__file__):
            continue
        for k, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
            if OUTSIDE.search(line):
                hits.append(f"{path.relative_to(ROOT)}:{k}: {line.strip()}")
    assert hits == []


def private_names_shared() -> list[str]:
    """'file:line name' for every ``_name`` that one module of the package imports from
    another (``from .x import _name``) or reads off one it imported (``x._name``): what two
    modules share is public and documented."""
    found = []
    for path in package_files():
        tree = ast.parse(path.read_text())
        imported = set()
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and (node.level or (node.module or "").startswith(
                    "flexfem")):
                for alias in node.names:
                    if alias.name.startswith("_") and not alias.name.startswith("__"):
                        found.append(f"{path.relative_to(ROOT)}:{node.lineno} {alias.name}")
                    imported.add(alias.asname or alias.name)
        for node in ast.walk(tree):
            if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
                    and node.value.id in imported and node.attr.startswith("_")
                    and not node.attr.startswith("__")):
                found.append(f"{path.relative_to(ROOT)}:{node.lineno} {node.value.id}.{node.attr}")
    return found


def test_no_private_name_crosses_modules():
    assert private_names_shared() == []


def test_the_private_name_finder_finds_one(tmp_path, monkeypatch):
    (tmp_path / "fem").mkdir()
    (tmp_path / "fem" / "a.py").write_text("from .b import _hidden\nfrom . import c\nc._x\n")
    monkeypatch.setitem(globals(), "ROOT", tmp_path)
    assert private_names_shared() == ["fem/a.py:1 _hidden", "fem/a.py:3 c._x"]


def classes_defined_twice(sources) -> dict:
    """{class name: ['file:line', ...]} for every class name that ``sources`` ((path, text)
    pairs) define more than once, at any depth of a file: two classes of one name read as one
    thing in a traceback, a docstring or an import, and one of them is misnamed."""
    places = {}
    for path, text in sources:
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.ClassDef):
                places.setdefault(node.name, []).append(f"{path.relative_to(ROOT)}:{node.lineno}")
    return {name: where for name, where in places.items() if len(where) > 1}


# names still defined twice, each for a reason; the list only shrinks (the beam solvers' node
# supports are fem/beam/supports.py's NodeFixed and NodePrescribed: a user meets fem/boundary's
# Fixed, Prescribed and Force on the beam models too)
STILL_TWICE = set()


def test_no_class_name_is_defined_twice():
    twice = classes_defined_twice((p, p.read_text()) for p in package_files())
    assert {n: w for n, w in twice.items() if n not in STILL_TWICE} == {}
    assert set(twice) >= STILL_TWICE, f"no longer twice: {sorted(STILL_TWICE - set(twice))}"


def test_the_class_name_finder_finds_one():
    a, b = ROOT / "fem" / "a.py", ROOT / "geometry" / "b.py"
    sources = [(a, "class Part:\n    class Inner:\n        pass\n"),
               (b, "def f():\n    class Inner:\n        pass\nclass Other:\n    pass\n")]
    assert classes_defined_twice(sources) == {"Inner": ["fem/a.py:2", "geometry/b.py:2"]}
