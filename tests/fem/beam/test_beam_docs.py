"""The docs/beam.md example runs and gives the parallel guide's beam-theory answers."""
import re
from pathlib import Path

import numpy as np

DOC = Path(__file__).resolve().parents[3] / "docs" / "beam.md"


def test_docs_example_runs(capsys):
    code = re.search(r"```python\n(.*?)```", DOC.read_text(), re.S).group(1)
    ns = {}
    exec(compile(code, str(DOC), "exec"), ns)
    E, I, L = 200e9, 0.01 * 0.5e-3**3 / 12, 0.05
    assert np.isclose(1 / ns["C"][1, 1], 24 * E * I / L**3, rtol=1e-3)
    end = ns["end"]
    assert np.isclose(-end.q[ns["stage"], 0], 0.6 * 0.005**2 / L, rtol=0.01)
    assert "k_y" in capsys.readouterr().out
