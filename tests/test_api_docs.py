"""The API reference builds (scripts/api_docs.sh: pdoc over the public face) without a warning,
the warning capture sees one where there is one, and each entry point of the public face has a
numpydoc Parameters section naming every parameter of its signature."""
import importlib.util
import inspect
from pathlib import Path
import re

import pytest

pytest.importorskip("pdoc", reason="pdoc is not installed (pip install -e '.[docs]')")

ROOT = Path(__file__).resolve().parents[1]


def _api_docs():
    spec = importlib.util.spec_from_file_location("api_docs", ROOT / "scripts" / "api_docs.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_public_modules_build_without_warnings(tmp_path):
    api_docs = _api_docs()
    assert api_docs.build(tmp_path, api_docs.PUBLIC_MODULES) == []
    pages = {p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*.html")}
    assert "index.html" in pages and "flexfem/studies/user_model/model_report.html" in pages
    report = (tmp_path / "flexfem/studies/user_model/model_report.html").read_text()
    assert "stroke_limits" in report and "<h6" in (tmp_path / "flexfem/studies/user_model/api.html"
                                                   ).read_text()  # numpydoc sections


def test_a_warning_of_pdoc_is_caught(tmp_path, monkeypatch):
    (tmp_path / "badly_annotated.py").write_text(
        '"""A module."""\n\ndef f(x: "NoSuchName") -> None:\n    """A function."""\n')
    monkeypatch.syspath_prepend(str(tmp_path))
    found = _api_docs().build(tmp_path / "out", ("badly_annotated",))
    assert found and "NoSuchName" in found[0]


def _entry_points():
    from flexfem import fem
    from flexfem.studies.engine import convergence, sweep
    from flexfem.studies.user_model import Report, analyze, load_model
    return [load_model, analyze, Report.summary, Report.write, fem.solve_static, fem.solve_modes,
            fem.solve_nonlinear, fem.solve_buckling, fem.compliance_matrix, fem.solve_harmonic,
            fem.Material, fem.Model, sweep.load_study, sweep.run_study, convergence.converge]


@pytest.mark.parametrize("entry", _entry_points(), ids=lambda f: f.__qualname__)
def test_every_parameter_of_an_entry_point_is_documented(entry):
    doc = inspect.getdoc(entry) or ""
    assert re.search(r"^Parameters\n-{10}$", doc, re.M), f"{entry.__qualname__}: no Parameters"
    section = doc.split("Parameters\n----------", 1)[1]
    documented = {name for line in re.findall(r"^(\*{0,2}\w+(?:, \w+)*)(?: : |$)", section,
                                              re.M) for name in line.split(", ")}
    target = entry.__init__ if inspect.isclass(entry) else entry
    names = [("**" if p.kind is p.VAR_KEYWORD else "") + p.name
             for p in inspect.signature(target).parameters.values() if p.name != "self"]
    missing = [n for n in names if n not in documented and n.lstrip("*") not in documented]
    assert missing == [], f"{entry.__qualname__}: undocumented {missing}"
