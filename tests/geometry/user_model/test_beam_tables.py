"""The beam declarations of a model file (geometry/user_model/beam_tables.py, beam_model.py):
expressions of the sketch's parameters, and the model they build from the examples."""
import math
from pathlib import Path

import numpy as np
import pytest

from flexfem.geometry.user_model import load_spec
from flexfem.geometry.user_model.beam_model import beam_model
from flexfem.geometry.user_model.beam_tables import evaluate_expression
from flexfem.geometry.user_model.crossings import crossings

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
W_GUIDE = 0.01  # the guide's out-of-plane width ([section] thickness), m


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
    assert len(model.rigid_links) == 3  # base, stage and the leaves' crossing joint


def test_root_extension_lengthens_the_joined_ends_only():
    spec = load_spec(EXAMPLES / "parallel_guide" / "guide.toml")
    bare = load_spec(EXAMPLES / "parallel_guide" / "guide.toml", {"beam_model.root_extension": 0})
    t = spec.constants["t"]
    extra = beam_model(spec)[0].lengths.sum() - beam_model(bare)[0].lengths.sum()
    assert extra == pytest.approx(2 * 2 * 0.38 * t)  # two leaves, both ends joined


def _stubs(spec):
    """{beam index: [distance (m) of its rigid stubs' ends from the crossing point]}."""
    found, = crossings(spec.beams.beams, 1e-12, spec.beams.root_extension)
    out = {}
    for i, seg, s in found.cuts:
        a, b = (np.asarray(p) for p in spec.beams.beams[i].points[seg:seg + 2])
        end = a + s * (b - a) / np.linalg.norm(b - a)
        out.setdefault(i, []).append(float(np.linalg.norm(end - np.asarray(found.point))))
    return out


@pytest.mark.parametrize("beta, t", [(math.pi / 4, 0.5e-3), (math.pi / 6, 0.5e-3),
                                     (math.pi / 6, 1e-3)])
def test_crossing_joint_is_the_leaves_overlap_less_the_root(beta, t):
    """Leaves at +-beta from the horizontal cross at alpha = 2 beta (or pi - 2 beta): each is
    rigid over t / (2 sin alpha) + t / 2 cot alpha - 0.38 t either side (90 degrees: 0.12 t)."""
    spec = load_spec(EXAMPLES / "cross_pivot" / "pivot.toml", {"beta": beta, "t": t})
    alpha = 2 * beta
    a = t / (2 * math.sin(alpha)) + t / 2 * abs(math.cos(alpha)) / math.sin(alpha) - 0.38 * t
    stubs = _stubs(spec)
    assert sorted(stubs) == [0, 1]
    assert np.concatenate(list(stubs.values())) == pytest.approx(a, rel=1e-9)
    model, _ = beam_model(spec)
    joint = model.rigid_links[-1]
    assert np.linalg.norm(model.nodes[joint.master]) < 1e-12 and len(joint.slaves) == 4
    assert np.linalg.norm(model.nodes[list(joint.slaves)], axis=1) == pytest.approx(a)


def test_weld_option_and_shallow_crossing_refused():
    weld = load_spec(EXAMPLES / "cross_pivot" / "pivot.toml", {"beam_model.crossings": "weld"})
    assert len(beam_model(weld)[0].rigid_links) == 2
    with pytest.raises(ValueError, match="crossings = 'glue' must be"):
        load_spec(EXAMPLES / "cross_pivot" / "pivot.toml", {"beam_model.crossings": "glue"})
    shallow = load_spec(EXAMPLES / "cross_pivot" / "pivot.toml", {"beta": math.radians(4)})
    with pytest.raises(ValueError, match="less than 10 degrees"):
        beam_model(shallow)
    thick = load_spec(EXAMPLES / "cross_pivot" / "pivot.toml",
                      {"beta": math.radians(6), "t": 4e-3})  # joint 4.4 t = 17.5 mm
    with pytest.raises(ValueError, match="reaches past its next point"):
        beam_model(thick)


def test_block_height_is_the_blocks_chord_across_the_beam():
    from flexfem.geometry.user_model.beam_model import _block_height
    block = ((-0.01, 0.0), (0.02, 0.005))
    up = np.array([0.0, 1.0])
    assert _block_height((0.0, 0.0), up, [block]) == pytest.approx(0.03)  # on its face
    assert _block_height((0.0, 0.002), up, [block]) == pytest.approx(0.03)  # inside
    assert _block_height((0.0, -0.001), up, [block]) is None  # short of it
    diagonal = np.array([1.0, 1.0]) / math.sqrt(2)  # across: along (-1, 1) from the point
    assert _block_height((0.0, 0.0), diagonal, [block]) == pytest.approx(0.005 * math.sqrt(2))


def test_axial_root_compliance_where_the_block_is_declared():
    """The guide's leaves enter base and stage (31 mm across) end-on: each root extension
    element carries the root's axial compliance (0.61 ln(H / t) - 0.24) / (E w)."""
    from flexfem.geometry.beam_layout import axial_root_compliance
    spec = load_spec(EXAMPLES / "parallel_guide" / "guide.toml")
    p = spec.constants
    model, _ = beam_model(spec)
    H = p["d"] + p["t"] + 2 * p["m"]
    roots = [e for e, sec in enumerate(model.sections) if not sec.is_rect]
    assert len(roots) == 4
    for e in roots:
        compliance = model.lengths[e] / model.sections[e].A  # x E w
        assert compliance * W_GUIDE == pytest.approx(axial_root_compliance(H, p["t"]))
