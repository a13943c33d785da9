"""The bridge amplifier's Pareto front of R (an [outputs] metric) against its input stiffness,
run from its front file: every design on the front trades one for the other, and the
continuum confirms the beam model's R."""
import json
from pathlib import Path

from flexfem.studies.cli import main

EXAMPLE = Path(__file__).parents[3] / "examples" / "bodies"


def test_the_front_of_R_against_the_input_stiffness(tmp_path, capsys):
    for name in ("bridge.toml", "bridge_front.toml"):
        (tmp_path / name).write_text((EXAMPLE / name).read_text())
    front = tmp_path / "bridge_front.toml"
    text = front.read_text()
    front.write_text(text.replace("population = 16", "population = 10")
                     .replace("generations = 8", "generations = 3"))
    assert main(["front", str(front), "--out", str(tmp_path / "out")]) == 0
    designs = json.loads((tmp_path / "out" / "front.json").read_text())["designs"]
    assert len(designs) >= 2
    pairs = sorted((d["objectives"]["R"], d["objectives"]["stiffness_input_left_x"])
                   for d in designs)
    assert all(k1 > k2 for (_, k1), (_, k2) in zip(pairs, pairs[1:]))  # more R, softer input
    for d in designs:  # the beam model's R beside the continuum's (the leaves' roots differ)
        assert abs(d["confirmed"]["R"] / d["objectives"]["R"] - 1) < 0.08
