"""Fuzzing the public inputs (hypothesis): parameter classes, materials, supports, loads and
study dictionaries either build a valid object or raise ValueError naming the problem --
never another exception, never an object holding a non-finite or mistyped value. Sized to
run in well under a minute (no meshing, no solving)."""
import math
import numbers

import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, example, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from flexfem.fem.boundary import Fixed, Force, Gravity, PointForce, Prescribed, Traction  # noqa: E402
from flexfem.fem.materials import Material  # noqa: E402
from flexfem.geometry.dbma.params import DBMAParams, paper_design  # noqa: E402
from flexfem.geometry.eightbar.flexure import EightBarFlexureParams  # noqa: E402
from flexfem.geometry.eightbar.rigid import EightBarParams  # noqa: E402
from flexfem.studies.engine.sweep import study_tasks  # noqa: E402
from flexfem.studies.run import study_from_dict  # noqa: E402

FAST = settings(max_examples=150, deadline=None, derandomize=True,
                suppress_health_check=[HealthCheck.too_slow])

NUMBERS = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-10**30, 10**30),
                    st.floats(min_value=1e-4, max_value=1e-1))
ANYTHING = st.one_of(NUMBERS, st.booleans(), st.none(), st.text(max_size=8),
                     st.sampled_from(["0.6e-3", "nan", "1", " 2 "]),
                     st.complex_numbers(allow_nan=False, max_magnitude=1e3),
                     st.lists(st.floats(), max_size=3), st.dictionaries(st.text(max_size=3), st.integers(), max_size=2))


def _finite_floats(obj, names) -> None:
    for name in names:
        value = getattr(obj, name)
        assert isinstance(value, float) and math.isfinite(value), (name, value)


def _builds_or_value_error(make, names):
    try:
        obj = make()
    except ValueError:
        return None
    _finite_floats(obj, names)
    return obj


DBMA_FIELDS = [f for f in DBMAParams.__dataclass_fields__]
EIGHTBAR_FIELDS = [f for f in EightBarParams.__dataclass_fields__]
FLEXURE_LENGTHS = ["link_width", "base_flexure_length", "base_flexure_width",
                   "flexure_length", "flexure_width", "thickness"]


@FAST
@given(st.dictionaries(st.sampled_from(DBMA_FIELDS), ANYTHING, max_size=4))
def test_dbma_params(changes):
    base = {f: getattr(paper_design(), f) for f in DBMA_FIELDS}
    p = _builds_or_value_error(lambda: DBMAParams(**{**base, **changes}), DBMA_FIELDS)
    if p is not None:
        assert 0 <= p.h <= p.c - p.b and p.b < min(p.a, p.c) and 1e-8 <= p.b <= 10


@FAST
@given(st.dictionaries(st.sampled_from(EIGHTBAR_FIELDS), ANYTHING, max_size=3))
def test_eightbar_params(changes):
    p = _builds_or_value_error(lambda: EightBarParams(**changes), EIGHTBAR_FIELDS)
    if p is not None:
        assert all(1e-8 <= getattr(p, f) <= 10 for f in EIGHTBAR_FIELDS)


@FAST
@given(st.dictionaries(st.sampled_from(FLEXURE_LENGTHS + ["material"]), ANYTHING, max_size=2))
def test_eightbar_flexure_params(changes):
    _builds_or_value_error(lambda: EightBarFlexureParams(**changes), FLEXURE_LENGTHS)


@FAST
@given(ANYTHING, ANYTHING, ANYTHING, ANYTHING)
def test_material(E, nu, rho, yield_strength):
    m = _builds_or_value_error(lambda: Material("m", E, nu, rho, yield_strength),
                               ["E", "nu", "rho"])
    if m is not None:
        assert m.E > 0 and -1 < m.nu < 0.5 and m.rho > 0 and m.yield_strength > 0


VECTORS = st.one_of(ANYTHING, st.lists(ANYTHING, max_size=4), st.tuples(NUMBERS, NUMBERS))


@FAST
@given(st.sampled_from([Force, Traction]), ANYTHING, VECTORS)
def test_loads(kind, group, vector):
    load = _builds_or_value_error(lambda: kind(group, vector), [])
    if load is not None:
        assert isinstance(load.group, str) and load.group
        assert all(isinstance(c, float) and math.isfinite(c) for c in load.vector)


@FAST
@given(VECTORS, VECTORS)
def test_point_force_and_gravity(point, vector):
    for make in (lambda: PointForce(point, vector), lambda: Gravity(vector)):
        load = _builds_or_value_error(make, [])
        if load is not None:
            for values in (getattr(load, "point", ()), getattr(load, "vector", load.__dict__.get("acceleration", ()))):
                assert all(isinstance(c, float) and math.isfinite(c) for c in values)


@FAST
@given(ANYTHING, ANYTHING, ANYTHING)
def test_supports(group, x, y):
    _builds_or_value_error(lambda: Fixed(group), [])
    support = _builds_or_value_error(lambda: Prescribed(group, x=x, y=y), [])
    if support is not None:
        assert isinstance(support.group, str)
        assert all(isinstance(v, numbers.Real) and math.isfinite(v) or callable(v)
                   for v in support.components().values())


KEYS = st.sampled_from(["mechanism", "name", "base", "options", "grid", "cases", "sample",
                        "plots", "colour"])
VALUES = st.recursive(ANYTHING, lambda inner: st.one_of(
    st.lists(inner, max_size=3), st.dictionaries(st.sampled_from(
        ["length_m", "n", "ranges", "method", "seed", "metric", "parameter", "model"]), inner,
        max_size=3)), max_leaves=8)


@FAST
@given(st.dictionaries(KEYS, VALUES, max_size=5), st.sampled_from(["toy", "dbma", None]))
@example({"base": {"length_m": [0j]}}, "toy")  # found by hypothesis: failed only when hashed
@example({"mechanism": {"model": 0.0}}, None)  # found by hypothesis: a TypeError
def test_study_dictionaries(data, mechanism):
    if mechanism is not None:
        data = {**data, "mechanism": mechanism}
    try:
        study = study_from_dict(data)
    except ValueError:
        return
    if study.case_count() <= 1000:
        for task in study_tasks(study, version="0"):
            assert len(task["key"]) == 64


@pytest.mark.parametrize("value", [None, "0.09", [0.09], 0.09 + 0j, True, float("nan"), 1e-300, 1e100])
def test_eightbar_params_are_type_checked_as_the_dbma_ones(value):
    with pytest.raises(ValueError, match="EightBarParams: crank_length"):
        EightBarParams(crank_length=value)


@pytest.mark.parametrize("name, value", [("flexure_width", 1e-300), ("thickness", 1e100),
                                         ("link_width", True), ("flexure_length", "0.02")])
def test_eightbar_flexure_sizes_are_bounded(name, value):
    with pytest.raises(ValueError, match=name):
        EightBarFlexureParams(**{name: value})
