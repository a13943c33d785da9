"""Units of study quantities: the lookup, each mechanism's table against its own metrics and
parameters, and the sweep plot's axis labels."""
from dataclasses import fields

import pytest

from flexfem.geometry.dbma.params import DBMAParams
from flexfem.geometry.eightbar.flexure import EightBarFlexureParams
from flexfem.geometry.eightbar.rigid import EightBarParams
from flexfem.studies.engine import sweep
from flexfem.studies.engine.store import CaseResult
from flexfem.studies.engine.units import unit_of
from flexfem.studies.mechanisms import get_evaluator, model_mechanism, quantity_units


def test_table_first_then_patterns_then_suffixes():
    table = {"k_in": "N/m", "R_*": "-"}
    assert unit_of("k_in", table) == "N/m"
    assert unit_of("R_eq7", table) == "-"
    assert unit_of("f1_hz", table) == "Hz" and unit_of("travel_m") == "m"
    assert unit_of("fem_deviation_pct") == "%" and unit_of("max_rotation_rad") == "rad"
    assert unit_of("mystery") is None  # no guess


@pytest.mark.parametrize("name", ["dbma", "eightbar"])
def test_every_metric_of_a_mechanism_has_a_unit(name):
    units = quantity_units(name)
    metrics = get_evaluator(name)({}, model="beam")
    assert [m for m in metrics if unit_of(m, units) is None] == []


@pytest.mark.parametrize("name, classes", [("dbma", [DBMAParams]),
                                           ("eightbar", [EightBarParams, EightBarFlexureParams])])
def test_every_numeric_parameter_has_a_unit(name, classes):
    units = quantity_units(name)
    numeric = [f.name for c in classes for f in fields(c) if f.type in (float, "float")]
    assert numeric and [p for p in numeric if unit_of(p, units) is None] == []


def test_model_file_metrics_have_units():
    units = quantity_units(model_mechanism("examples/parallel_guide/guide.toml"))
    assert unit_of("stiffness_stage_x", units) == "N/m"
    assert unit_of("mean_displacement_stage_y", units) == "m"


def test_sweep_plot_axes_name_their_units(tmp_path, monkeypatch):
    shown = []
    plt = sweep.pyplot()
    close = plt.close
    monkeypatch.setattr(plt, "close", lambda fig=None: (shown.append(fig), close(fig)))
    cases = [CaseResult(key=str(b), mechanism="dbma", params={"b": b},
                        metrics={"k_in": 1e9 * b, "R_eq7": 12.0}) for b in (0.4e-3, 0.6e-3)]
    sweep.plot_metric(cases, "k_in", "b", tmp_path / "k.png", overlay=["R_eq7"],
                      units=quantity_units("dbma"))
    ax = shown[0].axes[0]
    assert ax.get_xlabel() == "b (m)" and ax.get_ylabel() == "k_in (N/m)"
