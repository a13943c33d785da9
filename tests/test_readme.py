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


def test_readme_analyses_match_beam_theory(capsys):
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(), re.S)
    namespace = {}
    for code in blocks[:2]:
        exec(compile(code, str(README), "exec"), namespace)
    model, C, buckling = namespace["model"], namespace["C"], namespace["buckling"]
    E, L, h, t = model.material.E, 0.1, 0.005, 0.01
    EI = E * t * h**3 / 12
    # Euler buckling of a cantilever, pi^2 EI / (4 L^2): L/h = 20, shear and P2 within 1 %
    assert np.isclose(buckling.load_factors[0], np.pi**2 * EI / (4 * L**2), rtol=0.01)
    # tip rotation compliance L / EI and the coupling L^2 / (2 EI); the centre of compliance
    # of a cantilever is at mid-length
    assert np.isclose(C.matrix[2, 2], L / EI, rtol=0.01)
    assert np.isclose(C.matrix[1, 2], L**2 / (2 * EI), rtol=0.01)
    assert np.isclose(C.centre_of_compliance[0], L / 2, rtol=0.01)
    assert all(namespace["large"].stable)
