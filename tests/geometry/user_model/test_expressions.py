"""The one expression language of model files (geometry/user_model/expressions.py): numbers
for coordinates, conditions for [[select]] rules, and everything else refused by name."""
import math

import pytest

from flexfem.geometry.user_model.expressions import (compile_expression, evaluate_expression,
                                                      names_in)
from flexfem.geometry.user_model.selection import compile_rule

NAMES = {"L": 0.03, "t": 1e-3}


@pytest.mark.parametrize("text, value", [
    ("L / (2 * sqrt(2))", 0.03 / (2 * math.sqrt(2))), ("-t**2 + pi", math.pi - 1e-6),
    ("atan2(t, L)", math.atan2(1e-3, 0.03)), ("abs(t - L)", 0.029), (" L ", 0.03),
])
def test_numbers(text, value):
    assert evaluate_expression(text, NAMES, "w") == pytest.approx(value, rel=1e-12)


def test_one_language_for_numbers_and_conditions():
    rule = compile_rule("abs(x - sqrt(2) * 0.01) < 1e-9 and y ** 2 == 0")
    values = dict.fromkeys(("y", "z", "xmin", "ymin", "zmin", "xmax", "ymax", "zmax"), 0.0)
    assert rule({**values, "x": math.sqrt(2) * 0.01}) is True
    assert rule({**values, "x": 0.0}) is False
    assert compile_expression("L < t or not t > 0", frozenset(NAMES), True)(NAMES) is False


@pytest.mark.parametrize("text, problem", [
    ("q + 1", "'q' in 'q \\+ 1' is not a parameter of the geometry; known: L, t"),
    ("__import__('os')", "only numbers"), ("L.real", "only numbers"), ("L[0]", "only numbers"),
    ("(lambda: 1)()", "only numbers"), ("'a'", "only numbers"), ("1e999", "only numbers"),
    ("L +", "is not an arithmetic expression"), ("L < t", "is a condition, not a number"),
    ("sqrt(L, t)", "sqrt takes 1 argument"), ("1 / (L - L)", "cannot be evaluated"),
    ("10.0 ** 400", "cannot be evaluated"), ("sqrt(-L)", "cannot be evaluated"),
    ("-" * 150 + "1", "nested over 100 deep"), ("1+" * 1500 + "1", "over 2000 characters"),
])
def test_numbers_refuse(text, problem):
    with pytest.raises(ValueError, match=f"^w: .*{problem}"):
        evaluate_expression(text, NAMES, "w")


@pytest.mark.parametrize("text, problem", [
    ("x", "is not a condition"), ("x and y", "a condition was expected"),
    ("abs(x < 1)", "a number was expected"), ("x < 1 < 2", "one comparison at a time"),
    ("foo < 1", "'foo' in 'foo < 1' is not a value of the entity"),
    ("x.real < 1", "only numbers"), ("y < 1 1", "is not a condition"),
])
def test_conditions_refuse(text, problem):
    with pytest.raises(ValueError, match=problem):
        compile_rule(text)


def test_names_in():
    assert names_in("t * (1 + s / L)") == {"t", "s", "L"}
    assert names_in("t +") == set() and names_in(0.001) == set()
