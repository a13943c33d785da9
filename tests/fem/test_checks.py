"""The package's one set of input checks (fem/checks.py)."""
import math
import pickle

import numpy as np
import pytest
from flexfem.fem.checks import (InputError, count, finite_or_none, in_range, is_finite,
                                is_real, one_of, positive, real)


def test_what_a_number_is():
    assert is_real(1) and is_real(np.float64(2.5)) and is_real(math.inf)
    assert not is_real(True) and not is_real("1") and not is_real(None)
    assert is_finite(1e300) and not is_finite(math.nan) and not is_finite(-math.inf)


@pytest.mark.parametrize("value", [0, -1.0, math.inf, math.nan, True, "1", None])
def test_positive_refuses_naming_the_value(value):
    with pytest.raises(ValueError, match=r"^thickness = .* must be a finite number > 0$"):
        positive("thickness", value)


def test_positive_and_finite_or_none_keep_the_value():
    assert positive("t", 2) == 2.0 and isinstance(positive("t", 2), float)
    assert positive("t", None, allow_none=True) is None
    assert finite_or_none("x", None) is None and finite_or_none("x", -3) == -3.0
    with pytest.raises(ValueError, match=r"x = inf must be a finite number or None \(free\)"):
        finite_or_none("x", math.inf)


@pytest.mark.parametrize("check, args, message", [
    (real, ("x", math.nan), "x = nan must be a finite number"),
    (positive, ("E", 0.0), "E = 0.0 must be a finite number > 0 (Pa)"),
    (in_range, ("nu", 0.5, (-1.0, 0.5)), "nu = 0.5 must be a finite number in (-1, 0.5)"),
    (in_range, ("s", 11, (0.1, 10)), "s = 11 must be a finite number in [0.1, 10]"),
    (count, ("n", 2.0), "n = 2.0 must be a whole number >= 1"),
    (count, ("n", 2, 3), "n = 2 must be a whole number >= 3"),
    (count, ("n", 2000, 3, 1000), "n = 2000 must be a whole number from 3 to 1,000"),
])
def test_each_check_says_the_name_the_value_and_what_it_must_be(check, args, message):
    options = {"unit": "Pa"} if check is positive else {}
    options |= {"closed": False} if args[0] == "nu" else {}
    with pytest.raises(InputError) as info:
        check(*args, owner="Part", **options)
    assert str(info.value) == f"Part: {message}"
    assert (info.value.name, info.value.owner) == (args[0], "Part")


def test_checks_keep_good_values_in_their_type():
    assert real("x", np.float64(-2.5)) == -2.5 and isinstance(real("x", 3), float)
    assert in_range("nu", 0.3, (-1.0, 0.5), closed=False) == 0.3
    assert in_range("s", 10, (0.1, 10)) == 10.0       # closed: the ends are inside
    assert count("n", np.int64(4), 3) == 4 and isinstance(count("n", np.int64(4)), int)
    with pytest.raises(ValueError, match="must be a whole number"):
        count("n", True)


def test_a_refusal_crosses_a_process_boundary_whole():
    error = pickle.loads(pickle.dumps(InputError("b", 0.0, "a finite number > 0", "DBMAParams")))
    assert isinstance(error, InputError) and str(error) == \
        "DBMAParams: b = 0.0 must be a finite number > 0"


def test_one_of_names_the_choices():
    assert one_of("kind", "lhs", ("lhs", "sobol")) == "lhs"
    with pytest.raises(InputError, match=r"^sample: kind = 'grid' must be one of 'lhs', 'sobol'$"):
        one_of("kind", "grid", ("lhs", "sobol"), owner="sample")
