"""The package's one set of input checks (fem/checks.py)."""
import math

import numpy as np
import pytest
from flexfem.fem.checks import finite_or_none, is_finite, is_real, positive


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
