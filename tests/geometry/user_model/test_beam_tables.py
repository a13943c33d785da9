"""The beam declarations of a model file (geometry/user_model/beam_tables.py, beam_model.py):
expressions of the sketch's parameters, and the model they build from the examples."""
import math
from pathlib import Path

import numpy as np
import pytest

from flexfem.geometry.user_model import load_spec
from flexfem.reduced.model_file import beam_model
from flexfem.geometry.user_model.expressions import evaluate_expression
from flexfem.reduced.crossings import crossings

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
    stage, = (n for n in model.point_masses if model.nodes[n][1] > 0)  # the base's is held
    mass, inertia = model.point_masses[stage]
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
    from flexfem.reduced.model_file import _block_height
    block = ((-0.01, 0.0), (0.02, 0.005))
    up = np.array([0.0, 1.0])
    assert _block_height((0.0, 0.0), up, [block]) == pytest.approx(0.03)  # on its face
    assert _block_height((0.0, 0.002), up, [block]) == pytest.approx(0.03)  # inside
    assert _block_height((0.0, -0.001), up, [block]) is None  # short of it
    diagonal = np.array([1.0, 1.0]) / math.sqrt(2)  # across: along (-1, 1) from the point
    assert _block_height((0.0, 0.0), diagonal, [block]) == pytest.approx(0.005 * math.sqrt(2))


def test_axial_root_compliance_where_the_block_is_declared():
    """The guide's leaves enter base and stage (31 mm across) end-on: each root extension
    element carries the root's axial compliance (axial_root_compliance) / (E w), by its
    stiffness factor; its area, and so its mass, stay the root's own w t."""
    from flexfem.reduced.layout import axial_root_compliance
    spec = load_spec(EXAMPLES / "parallel_guide" / "guide.toml")
    p = spec.constants
    model, _ = beam_model(spec)
    H = p["d"] + p["t"] + 2 * p["m"]
    roots = [e for e, sec in enumerate(model.sections) if sec.depth_y is None]
    assert len(roots) == 4
    for e in roots:
        sec = model.sections[e]
        compliance = model.lengths[e] / (sec.A * sec.factors[2])  # x E w
        assert compliance * W_GUIDE == pytest.approx(axial_root_compliance(H, p["t"]))
        assert sec.A == pytest.approx(W_GUIDE * p["t"])


def test_root_offset_is_where_the_whole_section_has_left_the_face():
    """(t/2) cot(phi) along the beam from its centre line's meeting with the face: where its
    acute edge meets the face (constructed here from the edge line's intersection)."""
    from flexfem.reduced.roots import root_offset
    block, t, tol = [((-1.0, -1.0), (1.0, 0.0))], 1e-3, 1e-12  # the face y = 0
    for phi in np.radians([15, 30, 45, 60, 90, 120]):
        d = np.array([math.cos(phi), math.sin(phi)])
        edge = -np.sign(math.cos(phi)) * t / 2 * np.array([-d[1], d[0]])  # the acute edge
        s_edge = -edge[1] / d[1]  # where edge + s d meets y = 0
        assert root_offset((0.2, 0.0), d, t, block, tol, "f") == pytest.approx(
            max(s_edge, 0.0) if abs(math.cos(phi)) > 1e-12 else 0.0, abs=1e-15)
        assert root_offset((0.2, 0.0), d, t, block, tol, "f") == pytest.approx(
            t / 2 / abs(math.tan(phi)), abs=1e-15)
    assert root_offset((5.0, 0.0), (0.6, 0.8), t, block, tol, "f") == 0.0  # on no face
    assert root_offset((1.0, 0.0), (0.6, 0.8), t, block, tol, "f") == 0.0  # a corner
    with pytest.raises(ValueError, match=r"f: .* 8.02 degrees, less than 10"):
        root_offset((0.2, 0.0), (math.cos(0.14), math.sin(0.14)), t, block, tol, "f")


@pytest.mark.parametrize("degrees", [90, 45, 30, 15])
def test_oblique_leaf_begins_at_its_acute_edge(degrees):
    """The one-leaf example: its flexible length is L - 2 (t/2) cot(phi), plus the common root
    extension 0.38 t at both roots; the bare beams (root extension 0) keep the whole L."""
    over = {"phi": math.radians(degrees)}
    spec = load_spec(EXAMPLES / "oblique_leaf" / "leaf.toml", over)
    bare = load_spec(EXAMPLES / "oblique_leaf" / "leaf.toml",
                     {**over, "beam_model.root_extension": 0})
    L, t = spec.constants["L"], spec.constants["t"]
    cot = 1 / math.tan(math.radians(degrees))
    centre = load_spec(EXAMPLES / "oblique_leaf" / "leaf.toml",
                       {**over, "beam_model.roots": "centre_line"})
    assert beam_model(spec)[0].lengths.sum() == pytest.approx(L - t * cot + 2 * 0.38 * t)
    assert beam_model(bare)[0].lengths.sum() == pytest.approx(L)
    assert beam_model(centre)[0].lengths.sum() == pytest.approx(L + 2 * 0.38 * t)


def test_an_unknown_roots_rule_is_refused():
    with pytest.raises(ValueError, match=r"leaf.toml.*roots = 'edge' must be \"acute_edge\""):
        load_spec(EXAMPLES / "oblique_leaf" / "leaf.toml", {"beam_model.roots": "edge"})


def test_oblique_roots_that_leave_no_beam_or_are_too_shallow_are_refused():
    leaf = EXAMPLES / "oblique_leaf" / "leaf.toml"
    with pytest.raises(ValueError, match=r"leaf.toml.*oblique roots .* leave no length"):
        beam_model(load_spec(leaf, {"phi": math.radians(15), "L": 0.003}))  # 2 x 1.87 t > L
    with pytest.raises(ValueError, match=r"leaf.toml.*leaves its block .* less than 10"):
        beam_model(load_spec(leaf, {"phi": math.radians(8)}))
