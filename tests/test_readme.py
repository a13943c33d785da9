"""The README's Python example runs and gives the beam-theory answer."""
import re
from pathlib import Path

import numpy as np

README = Path(__file__).resolve().parents[1] / "README.md"


def test_readme_example_runs_and_matches_beam_theory(capsys):
    code = re.search(r"```python\n(.*?)```", README.read_text(), re.S).group(1)
    namespace = {}
    exec(compile(code, str(README), "exec"), namespace)
    result, model = namespace["result"], namespace["model"]
    E, L, h, t, P = model.material.E, 0.1, 0.005, 0.01, 10.0
    # Euler-Bernoulli tip deflection; L/h = 20 so shear adds ~ 3 (h/L)^2 = 0.75 %: allow 2 %
    expected = -P * L**3 / (3 * E * t * h**3 / 12)
    assert np.isclose(result.mean_displacement("tip")[1], expected, rtol=0.02)
    assert np.allclose(result.reactions["fixed"], [0.0, P], atol=1e-8 * P)
    assert "[" in capsys.readouterr().out
