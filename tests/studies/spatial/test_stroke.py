"""The leaf guide's support stiffness along its stroke (studies/spatial/stroke.py): at a
stroke of a micrometre the probes give the linear compliance's stiffness (prescribed y
also holding the stage's turns about x and z, as the continuum's every-node constraint
does); along 10 % of the leaf length the support stiffness falls, the beam model within
5 % of the continuum's large-deflection solve at every step (slow)."""
from pathlib import Path

import numpy as np
import pytest

from flexfem.fem import Fixed, compliance_matrix
from flexfem.geometry.user_model import load_spec
from flexfem.studies.spatial.beam_model import beam_model
from flexfem.studies.spatial.stroke import support_along_stroke

EXAMPLES = Path(__file__).resolve().parents[3] / "examples" / "spatial"
PROBES = {"x": 1.0, "z": 10.0}


def _beam():
    spec = load_spec(EXAMPLES / "leaf_guide.toml")
    return spec, beam_model(spec.spatial, spec.material).model


def test_a_tiny_stroke_gives_the_linear_stiffness():
    _, model = _beam()
    out = support_along_stroke(model, [Fixed("base")], "stage", "y", 1e-6, PROBES, steps=1)
    free = [0, 2, 4]  # y held, and with it the turns about x and z: x, z and r_y move
    K = np.linalg.inv(compliance_matrix(model, [Fixed("base")], "stage").matrix)
    held = np.linalg.inv(K[np.ix_(free, free)])
    for axis, k in (("x", 0), ("z", 1)):
        assert out["stiffness"][axis][0] == pytest.approx(1 / held[k, k], rel=1e-3)


def test_the_support_stiffness_falls_along_the_stroke():
    spec, model = _beam()
    out = support_along_stroke(model, [Fixed("base")], "stage", "y", 0.1 * spec.constants["L"],
                               PROBES, steps=3)
    assert out["stroke_m"] == pytest.approx([0.001, 0.002, 0.003])
    for axis in PROBES:
        assert np.all(np.diff(out["stiffness"][axis]) < 0)
    with pytest.raises(ValueError, match="distinct axes"):
        support_along_stroke(model, [Fixed("base")], "stage", "y", 0.001, {"y": 1.0})


@pytest.mark.slow
def test_the_beam_follows_the_continuum_along_the_stroke_within_5_percent():
    """Two steps to 10 % of the leaf length; the continuum at size factor 2 (41 k DOFs,
    about two minutes: within 0.6 % of size factor 1.5 here; docs/spatial.md has the default
    mesh's three steps); the beam model with its leaves' root rules
    (studies/spatial/roots.py): the roots' axial compliance is in k_z from rest on, the
    restrained warping of the leaves' torsion in k_x's fall along the stroke."""
    from flexfem.studies.user_model.analysis import build_model

    spec, model = _beam()
    stroke = 0.1 * spec.constants["L"]
    beam = support_along_stroke(model, [Fixed("base")], "stage", "y", stroke, PROBES, steps=2)
    solid = support_along_stroke(build_model(spec, size_factor=2.0), [Fixed("base")], "stage",
                                 "y", stroke, PROBES, steps=2)
    for axis in PROBES:
        ratio = np.array(beam["stiffness"][axis]) / np.array(solid["stiffness"][axis])
        assert np.all(np.abs(ratio - 1) < 0.05), (axis, ratio)
