"""The beam declarations of a model file (geometry/user_model/beam_tables.py, beam_model.py):
expressions of the sketch's parameters, and the model they build from the examples."""
import math
from pathlib import Path

import numpy as np
import pytest

from flexfem.geometry.user_model import load_spec
from flexfem.geometry.user_model.beam_model import beam_model
from flexfem.geometry.user_model.beam_tables import evaluate_expression

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"


def test_expressions():
    names = {"L": 0.03, "t": 1e-3}
    assert evaluate_expression("L / (2 * sqrt(2))", names, "w") == pytest.approx(
        0.03 / (2 * math.sqrt(2)))
    assert evaluate_expression("-t**2 + pi", names, "w") == pytest.approx(math.pi - 1e-6)
    with pytest.raises(ValueError, match="'q' in 'q \\+ 1' is not a parameter"):
        evaluate_expression("q + 1", names, "w")
    with pytest.raises(ValueError, match="only numbers"):
        evaluate_expression("__import__('os')", names, "w")


def test_pivot_leaves_are_joined_where_they_cross():
    spec = load_spec(EXAMPLES / "cross_pivot" / "pivot.toml", {"beam_model.elements": 4})
    model, info = beam_model(spec)
    crossing = np.flatnonzero(np.linalg.norm(model.nodes, axis=1) < 1e-12)
    assert len(crossing) == 1  # one node: the leaves are welded there
    assert np.sum(model.elements == crossing[0]) == 4  # four half-leaves meet at it
    assert set(info["groups"]) == {"fixed", "left", "right"}
    # the base's master is its supported group; the stage carries its block's mass
    assert info["masters"][0] == info["groups"]["fixed"]
    hs, arm = spec.constants["hs"], spec.constants["arm"]
    (mass, inertia), = model.point_masses.values()
    assert mass == pytest.approx(7850 * 0.01 * 2 * arm * hs)
    assert inertia == pytest.approx(mass * ((2 * arm) ** 2 + hs ** 2) / 12)
    assert len(model.rigid_links) == 2


def test_root_extension_lengthens_the_joined_ends_only():
    spec = load_spec(EXAMPLES / "parallel_guide" / "guide.toml")
    bare = load_spec(EXAMPLES / "parallel_guide" / "guide.toml", {"beam_model.root_extension": 0})
    t = spec.constants["t"]
    extra = beam_model(spec)[0].lengths.sum() - beam_model(bare)[0].lengths.sum()
    assert extra == pytest.approx(2 * 2 * 0.38 * t)  # two leaves, both ends joined
