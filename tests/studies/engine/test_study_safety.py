"""What a study may run (registered mechanisms, never code unless asked), how its values are
normalised before they are hashed, and the limits checked before anything is expanded."""
import sys

import pytest
from flexfem.studies import mechanisms
from flexfem.studies.cli import main
from flexfem.studies.engine.store import case_key
from flexfem.studies.engine.sweep import Study
from flexfem.studies.engine.validate import normalise_options
from flexfem.studies.run import load_study, run_study, study_from_dict
from flexfem.studies.toy import model as toy
from toy_hooks import MECHANISM as HOOKED


@pytest.fixture(autouse=True)
def _no_cluster(monkeypatch):
    monkeypatch.delenv("FLEXFEM_SCHEDULER", raising=False)


SHELL_STUDY = '''mechanism = "subprocess:run"
[base]
args = "touch {marker}"
[options]
shell = true
'''


def test_a_study_file_cannot_run_a_shell_command(tmp_path, capsys):
    marker = tmp_path / "pwned"
    path = tmp_path / "evil.toml"
    path.write_text(SHELL_STUDY.format(marker=marker))
    assert main(["sweep", str(path), "--out", str(tmp_path / "out"), "--workers", "1"]) == 2
    err = capsys.readouterr().err
    assert "is Python code" in err and "--allow-code" in err and "Traceback" not in err
    assert not marker.exists() and not (tmp_path / "out").exists()
    with pytest.raises(ValueError, match="allow_code=True"):
        load_study(path)
    with pytest.raises(ValueError, match="allow_code"):
        run_study(Study("subprocess:run"), tmp_path / "r.sqlite", workers=1)


def test_code_runs_only_when_the_caller_allows_it(tmp_path):
    study = Study(HOOKED, grid={"length_m": [0.05, 0.1]})
    with pytest.raises(ValueError, match="is Python code"):
        run_study(study, tmp_path / "r.sqlite", workers=1, progress=False)
    result = run_study(study, tmp_path / "r.sqlite", workers=1, progress=False, allow_code=True)
    assert len(result.cases) == 2 and not result.failed


def test_a_package_registers_a_mechanism_through_an_entry_point(tmp_path, monkeypatch):
    dist = tmp_path / "flexfem_plugin-1.0.dist-info"
    dist.mkdir()
    (dist / "METADATA").write_text("Metadata-Version: 2.1\nName: flexfem-plugin\nVersion: 1.0\n")
    (dist / "entry_points.txt").write_text("[flexfem.mechanisms]\nhooked = toy_hooks:evaluate\n"
                                           "toy = toy_hooks:environment_probe\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    mechanisms.plugin_mechanisms.cache_clear()
    try:
        assert "hooked" in mechanisms._known()
        study = study_from_dict({"mechanism": "hooked", "grid": {"fail_if": [0, 1]}})
        result = run_study(study, tmp_path / "r.sqlite", workers=1, progress=False)
        assert sorted(c.status for c in result.cases) == ["failed", "ok"]
        assert mechanisms.get_evaluator("toy") is toy.evaluate  # a built-in name is not taken
    finally:
        monkeypatch.undo()
        mechanisms.plugin_mechanisms.cache_clear()
    with pytest.raises(ValueError, match="not a known mechanism"):
        mechanisms.get_evaluator("hooked")


# --- case identity --------------------------------------------------------------------------

def _dbma_like(params: dict, dim: int = 2, size_factor: float = 1.0, modes: bool = False) -> dict:
    return {"dim": dim}


def test_options_take_their_declared_types_before_hashing():
    assert normalise_options(_dbma_like, {"dim": 2.0, "size_factor": 4}, "m") == \
        {"dim": 2, "size_factor": 4.0}
    assert type(normalise_options(_dbma_like, {"dim": 2.0}, "m")["dim"]) is int
    for options, message in (({"dim": 2.5}, "options.dim = 2.5 must be an integer"),
                             ({"dim": "2"}, "options.dim"), ({"dim": True}, "options.dim"),
                             ({"modes": 1}, "options.modes"), ({"size_factor": "0.5"}, "quotes"),
                             ({"size_factor": float("nan")}, "finite"),
                             ({"colour": 1}, "options.colour is not an option")):
        with pytest.raises(ValueError, match=message):
            normalise_options(_dbma_like, options, "m")


def test_a_model_the_mechanism_does_not_have_is_refused_by_name():
    """evaluate declares its models as a Literal: options.model is checked with the other
    options, before any case runs or is stored."""
    evaluate = mechanisms.get_evaluator("dbma")
    assert normalise_options(evaluate, {"model": "beam"}, "dbma") == {"model": "beam"}
    with pytest.raises(ValueError, match=r"options.model = 'shell' must be one of "
                                         r"\['continuum', 'beam'\]"):
        normalise_options(evaluate, {"model": "shell"}, "dbma")


def test_dim_2_0_is_the_case_dim_2_and_never_a_stored_failure(tmp_path):
    evaluate = mechanisms.get_evaluator("dbma")
    assert normalise_options(evaluate, {"dim": 2.0}, "dbma") == {"dim": 2}
    # a store from before normalisation holds dim = 2.0's gmsh failure under the old key
    # (the options' numbers hashed as floats, no key schema): the new key is another one
    old = case_key("toy", {}, {"n_elements": 8.0}, "0.1.0")
    from flexfem.studies.engine import store
    payload = {"mechanism": "toy", "params": {}, "options": {"n_elements": 8.0}, "flexfem": "0.1.0"}
    import hashlib
    assert old != hashlib.sha256(store.canonical_json(payload).encode()).hexdigest()
    # one case for 8 and 8.0 (an int option): computed once
    study = Study("toy", cases=({"length_m": 0.1},), options={"n_elements": 8.0})
    first = run_study(study, tmp_path / "r.sqlite", workers=1, progress=False)
    again = run_study(Study("toy", cases=({"length_m": 0.1},), options={"n_elements": 8}),
                      tmp_path / "r.sqlite", workers=1, progress=False)
    assert first.cases[0].options == {"n_elements": 8} and (again.computed, again.reused) == (0, 1)
    with pytest.raises(ValueError, match="options.n_elements = 8.5 must be an integer"):
        run_study(Study("toy", options={"n_elements": 8.5}), tmp_path / "r.sqlite", workers=1)


@pytest.mark.parametrize("data, where", [
    ({"mechanism": "toy", "base": {"length_m": "0.6e-3"}}, "base.length_m"),
    ({"mechanism": "toy", "grid": {"length_m": [0.1, "0.2"]}}, "grid.length_m"),
    ({"mechanism": "toy", "cases": [{"width_m": "1e-2"}]}, r"cases\[0\].width_m"),
    ({"mechanism": "toy", "options": {"size_factor": " 2 "}}, "options.size_factor"),
])
def test_a_number_written_as_a_string_is_refused_by_name(data, where):
    with pytest.raises(ValueError, match=where + ".*number written as a string"):
        study_from_dict(data)


# --- limits ---------------------------------------------------------------------------------

def test_a_huge_study_is_refused_before_expansion(tmp_path):
    grid = {f"p{i}": [0.1 * (j + 1) for j in range(10)] for i in range(9)}  # 10^9 designs
    with pytest.raises(ValueError, match="1,000,000,000 cases"):
        run_study(Study("toy", grid=grid), tmp_path / "r.sqlite", workers=1)
    with pytest.raises(ValueError, match="sample.n"):
        study_from_dict({"mechanism": "toy", "sample": {"n": 1e11, "ranges": {"length_m": [0.1, 0.2]}}})
    big = study_from_dict({"mechanism": "toy", "sample": {"n": 10**11, "ranges": {"length_m": [0.1, 0.2]}}})
    with pytest.raises(ValueError, match="100,000,000,000 cases.*--max-cases"):
        run_study(big, tmp_path / "r.sqlite", workers=1)
    small = Study("toy", grid={"length_m": [0.1, 0.2, 0.3]})
    with pytest.raises(ValueError, match="3 cases, above the limit of 2"):
        run_study(small, tmp_path / "r.sqlite", workers=1, max_cases=2)
    assert not (tmp_path / "r.sqlite").exists()


@pytest.mark.parametrize("name", ["..", ".", "a/b", "../up", "a\\b"])
def test_a_study_name_never_leaves_the_output_folder(name):
    with pytest.raises(ValueError, match="name ="):
        study_from_dict({"mechanism": "toy", "name": name})


def test_unused_module_is_not_imported_by_a_refusal():
    sys.modules.pop("antigravity", None)
    with pytest.raises(ValueError, match="is Python code"):
        mechanisms.check_mechanism("antigravity:fly")
    assert "antigravity" not in sys.modules


def test_a_dbma_study_with_dim_2_0_runs_and_is_the_case_of_dim_2(tmp_path):
    # dim = 2.0 used to reach gmsh as a float and fail there, under the key of dim = 2
    store = tmp_path / "r.sqlite"
    first = run_study(Study("dbma", options={"dim": 2.0, "size_factor": 4}), store, workers=1,
                      progress=False)
    assert first.cases[0].ok, first.cases[0].error
    assert first.cases[0].options == {"dim": 2, "size_factor": 4.0}
    again = run_study(Study("dbma", options={"dim": 2, "size_factor": 4.0}), store, workers=1,
                      progress=False)
    assert (again.computed, again.reused) == (0, 1)


def test_a_study_with_a_million_base_keys_is_refused_by_its_size():
    from flexfem.studies.engine.sweep import study_from_dict

    with pytest.raises(ValueError, match=r"\[base\] has 1,000,000 entries"):
        study_from_dict({"mechanism": "toy", "base": {f"p{i}": 1.0 for i in range(10**6)}})
