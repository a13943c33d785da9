"""Every name a user gives is checked before anything runs: a misspelled parameter or key of
a model file (``--set``, a study's grid, cases, sample, tolerances, a front's variables) or
of a built-in mechanism is refused, naming the file or mechanism, the bad name, the known
names and the nearest; a mesh size that cannot be honoured is refused, not raised."""
import os
from pathlib import Path
import re
import shutil
import subprocess
import sys

import pytest

from flexfem.geometry.mechanism.draw import element_sizes, estimate_mesh
from flexfem.geometry.user_model import load_spec
from flexfem.geometry.user_model.beam_tables import beam_options
from flexfem.geometry.user_model.names import OVERRIDE_KEYS
from flexfem.geometry.user_model.material_table import parse_material
from flexfem.geometry.user_model.tables import Locator, parse_analysis, parse_mesh, parse_section
from flexfem.studies.mechanisms import get_evaluator
from flexfem.studies.run import run_front, study_from_dict, sweep

ROOT = Path(__file__).resolve().parents[3]
BODIES = ROOT / "examples" / "bodies" / "guide.toml"
GEO = ROOT / "examples" / "parallel_guide"


def flexfem(*args) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k != "FLEXFEM_SCHEDULER"}
    return subprocess.run([sys.executable, "-m", "flexfem.studies.cli", *map(str, args)],
                          capture_output=True, text=True, timeout=120, env=env)


@pytest.fixture
def bodies(tmp_path) -> Path:
    shutil.copy(BODIES, tmp_path / "guide.toml")
    return tmp_path / "guide.toml"


@pytest.fixture
def geo(tmp_path) -> Path:
    for name in ("guide.toml", "guide.geo"):
        shutil.copy(GEO / name, tmp_path / name)
    return tmp_path / "guide.toml"


def test_analyze_refuses_a_misspelled_parameter_of_bodies_and_flexures():
    run = flexfem("analyze", BODIES, "--model", "beam", "--set", "thicknes=0.002")
    assert run.returncode == 2, run.stderr
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in run.stderr, run.stderr
    assert lines[0].startswith("flexfem analyze: error: ")
    for word in ("guide.toml", "'thicknes'", "known: L, d, t"):
        assert word in lines[0], (word, lines[0])


@pytest.mark.parametrize("name, words", [
    ("Lx", ["override 'Lx' is not a [parameters] name of guide.toml", "known: L, d, t",
            "did you mean 'L'?"]),
    ("material.EE", ["override 'material.EE'", "'EE' is not a key of [material]",
                     "did you mean 'E'?"]),
    ("mesh.sise", ["'sise' is not a key of [mesh]", "known: order, refine, size",
                   "did you mean 'size'?"]),
    ("analysis.mode", ["did you mean 'modes'?"]),
    ("beam_model.element", ["[beam_model]", "did you mean 'elements'?"]),
    ("materia.E", ["only [parameters] names and material.KEY", "did you mean 'material'?"]),
])
def test_overrides_of_a_bodies_file_are_checked_by_name(bodies, name, words):
    with pytest.raises(ValueError) as error:
        load_spec(bodies, {name: 1.0})
    message = str(error.value)
    assert message.startswith(str(bodies)) and "\n" not in message
    for word in words:
        assert word in message, (word, message)


def test_known_overrides_still_change_the_design(bodies):
    spec = load_spec(bodies, {"t": 0.0012, "material.E": 1.9e11, "mesh.size": 0.002})
    assert spec.parameters["t"] == 0.0012 and spec.material.E == 1.9e11
    assert spec.mesh.size == 0.002
    assert {f.thickness for f in spec.mechanism.flexures} == {0.0012}


def test_a_geo_constant_misspelled_gets_the_nearest(geo):
    with pytest.raises(ValueError, match=r"override 'Lx' is not a DefineConstant of guide.geo; "
                                         r"its constants: L, d, .*; did you mean 'L'\?"):
        load_spec(geo, {"Lx": 0.05})


def _allowed(parse, table) -> tuple:
    """The keys a table's parser allows, read from its refusal of a key it cannot know."""
    with pytest.raises(ValueError) as error:
        parse({"zz_not_a_key": 1})
    found = re.search(r"unknown key 'zz_not_a_key'; allowed: (.*)$", str(error.value))
    assert found, str(error.value)
    return tuple(k.strip() for k in found.group(1).split(","))


def test_the_override_keys_are_the_parsers_keys(tmp_path):
    loc = Locator(tmp_path / "m.toml", "")
    parsers = {"material": lambda raw: parse_material(raw, loc),
               "section": lambda raw: parse_section(raw, 2, loc),
               "mesh": lambda raw: parse_mesh(raw, loc),
               "analysis": lambda raw: parse_analysis(raw, loc),
               "beam_model": lambda raw: beam_options(raw, loc)}
    assert set(parsers) == set(OVERRIDE_KEYS)
    for table, parse in parsers.items():
        assert sorted(_allowed(parse, table)) == sorted(OVERRIDE_KEYS[table]), table


def test_a_mesh_size_finer_than_the_flexures_is_refused_with_the_possible_sizes(bodies):
    with pytest.raises(ValueError) as error:
        load_spec(bodies, {"mesh.size": 1e-9})
    message = str(error.value)
    assert message.startswith(str(bodies)) and "[mesh] size = 1e-09 m cannot be honoured" in message
    assert "give size >= 0.0005 m" in message and "half the 0.001 m thickness" in message
    spec = load_spec(bodies)  # no size: the default, at least the flexures' own, unchanged
    sizes, coarse = element_sizes(spec.mechanism)
    assert spec.mesh.size is None and coarse >= max(sizes) == 0.0005
    with pytest.raises(ValueError, match="cannot be honoured"):  # the Python route too
        estimate_mesh(spec.mechanism, coarse=1e-9)
    assert element_sizes(spec.mechanism, 0.002)[1] == 0.002


def _study(folder: Path, **tables) -> dict:
    return {"mechanism": {"model": "guide.toml"}, "name": "s",
            "options": {"model": "beam"}, **tables}


@pytest.mark.parametrize("tables, where", [
    ({"grid": {"thicknes": [0.001, 0.0012]}}, "grid.thicknes"),
    ({"base": {"Lenght": 0.04}}, "base.Lenght"),
    ({"cases": [{"t": 0.001}, {"dd": 0.02}]}, "cases[1].dd"),
    ({"sample": {"n": 4, "ranges": {"tt": [0.001, 0.0012]}}}, "sample.ranges.tt"),
    ({"tolerances": {"n": 8, "parameters": {"tt": {"nominal": 0.001, "tolerance": 1e-5}}}},
     "tolerances.parameters.tt"),
])
def test_a_study_of_a_model_file_refuses_unknown_names_before_any_case(bodies, tables, where):
    study = study_from_dict(_study(bodies.parent, **tables), base_dir=bodies.parent)
    with pytest.raises(ValueError) as error:
        sweep(study, bodies.parent / "out", workers=1, progress=False)
    message = str(error.value)
    assert message.startswith(where) and "guide.toml" in message and "L, d, t" in message
    assert not (bodies.parent / "out" / "results.sqlite").exists()  # nothing ran


def test_a_study_of_a_geo_model_refuses_unknown_names_before_any_case(geo):
    study = study_from_dict(_study(geo.parent, grid={"Lx": [0.04, 0.05]}), base_dir=geo.parent)
    with pytest.raises(ValueError, match=r"grid.Lx names no parameter of mechanism "
                                         r"'model:.*guide.toml@.*'; its parameters: L, d, .*"
                                         r"did you mean 'L'\?"):
        sweep(study, geo.parent / "out", workers=1, progress=False)
    assert not (geo.parent / "out" / "results.sqlite").exists()


@pytest.mark.parametrize("options, words", [
    ({"colour": "red"}, ["options.colour is not an option", "'model'", "'mesh.size'"]),
    ({"mesh.sise": 0.001}, ["options.mesh.sise", "did you mean 'mesh.size'?"]),
])
def test_unknown_options_of_a_model_file_study_are_refused_up_front(bodies, options, words):
    data = _study(bodies.parent, grid={"t": [0.001]})
    data["options"].update(options)
    with pytest.raises(ValueError) as error:
        sweep(study_from_dict(data, base_dir=bodies.parent), bodies.parent / "out", workers=1,
              progress=False)
    for word in words:
        assert word in str(error.value), (word, str(error.value))
    assert not (bodies.parent / "out" / "results.sqlite").exists()


def test_the_confirming_options_and_plot_parameters_are_checked_up_front(bodies):
    tolerances = {"n": 8, "parameters": {"t": {"nominal": 0.001, "tolerance": 1e-5}},
                  "confirm": {"modell": "continuum"}}
    study = study_from_dict(_study(bodies.parent, tolerances=tolerances), base_dir=bodies.parent)
    with pytest.raises(ValueError, match=r"tolerances.confirm.modell is not an option.*did you "
                                         r"mean 'model'\?"):
        sweep(study, bodies.parent / "out", workers=1, progress=False)
    plots = [{"metric": "stiffness_stage_x", "parameter": "tt"}]
    study = study_from_dict(_study(bodies.parent, grid={"t": [0.001]}, plots=plots),
                            base_dir=bodies.parent)
    with pytest.raises(ValueError, match=r"plots\[0\].parameter = 'tt' is no parameter the study "
                                         r"gives .*: t; did you mean 't'\?"):
        sweep(study, bodies.parent / "out", workers=1, progress=False)
    assert not (bodies.parent / "out" / "results.sqlite").exists()


def test_a_front_refuses_unknown_variables_before_any_evaluation(bodies):
    front = bodies.parent / "front.toml"
    front.write_text('mechanism = { model = "guide.toml" }\n[options]\nmodel = "beam"\n'
                     '[variables]\nL = [0.02, 0.06]\nthicknes = [0.0005, 0.0015]\n'
                     '[[objectives]]\nmetric = "stiffness_stage_x"\ngoal = "min"\n'
                     '[[objectives]]\nmetric = "f1_hz"\ngoal = "max"\n')
    with pytest.raises(ValueError, match=r"variables.thicknes names no parameter of mechanism "
                                         r"'model:.*guide.toml@.*'; its parameters: L, d, t"):
        run_front(front, bodies.parent / "out")
    assert not (bodies.parent / "out" / "evaluations.sqlite").exists()


@pytest.mark.parametrize("mechanism, typo, meant", [
    ("toy", "lenght_m", "length_m"),
    ("dbma", "hh", "h"),
    ("eightbar", "flexure_widht", "flexure_width"),
    ("eightbar_driving", "flexure_lenght", "flexure_length"),
])
def test_built_in_mechanisms_refuse_unknown_names_before_any_case(tmp_path, mechanism, typo,
                                                                  meant):
    study = study_from_dict({"mechanism": mechanism, "name": "s", "grid": {typo: [1e-3]}})
    with pytest.raises(ValueError) as error:
        sweep(study, tmp_path / "out", workers=1, progress=False)
    message = str(error.value)
    assert message.startswith(f"grid.{typo} names no parameter of mechanism {mechanism!r}")
    assert message.endswith(f"did you mean {meant!r}?") and f" {meant}," in message
    assert not (tmp_path / "out" / "results.sqlite").exists()


def test_built_in_mechanisms_declare_the_names_their_parsers_take():
    from flexfem.studies.engine.validate import known_parameters
    from flexfem.studies.dbma.analysis import params_from_dict as dbma_params
    from flexfem.studies.eightbar.analysis import params_from_dict as eightbar_params

    for name, parse in (("dbma", dbma_params), ("eightbar", eightbar_params)):
        known = known_parameters(get_evaluator(name))
        assert known, name
        with pytest.raises(ValueError, match=r"unknown .*parameter\(s\)"):  # refuses others
            parse({"zz_not_a_parameter": 1.0})
        for field in known:  # and takes every declared name (unknown is not its complaint)
            try:
                parse({field: 0.0})
            except (ValueError, TypeError) as error:
                assert "parameter(s)" not in str(error), (name, field, str(error))


def test_sweep_refuses_a_misspelled_grid_name_in_one_line(bodies):
    study = bodies.parent / "s.toml"
    study.write_text('mechanism = { model = "guide.toml" }\n[options]\nmodel = "beam"\n'
                     '[grid]\nthicknes = [0.001, 0.0012, 0.0014]\n')
    run = flexfem("sweep", study, "--out", bodies.parent / "out", "--workers", "1")
    assert run.returncode == 2, run.stderr
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("flexfem sweep: error: grid.thicknes "), lines
    assert "guide.toml" in lines[0] and "its parameters: L, d, t" in lines[0]
    assert not (bodies.parent / "out" / "results.sqlite").exists()
