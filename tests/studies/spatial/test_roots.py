"""The leaves' root rules of the spatial beam model (studies/spatial/roots.py): the bodies'
depth along a leaf, the roots' axial compliance in its k_z, the restrained warping's limits."""
import math
from pathlib import Path

import numpy as np
import pytest

from flexfem.fem import Fixed, compliance_matrix
from flexfem.geometry.user_model import load_spec
from flexfem.reduced.layout import axial_root_compliance
from flexfem.studies.spatial.beam_model import beam_model
from flexfem.studies.spatial.roots import axial_factor, block_depth, warping_factor

EXAMPLES = Path(__file__).resolve().parents[3] / "examples" / "spatial"


def test_the_leaf_guides_k_z_holds_its_roots_axial_compliance():
    spec = load_spec(EXAMPLES / "leaf_guide.toml")
    m = spec.spatial
    assert [block_depth(m, i, e) for i in range(2) for e in range(2)] == pytest.approx(
        [0.005] * 4, rel=1e-6)
    t, L, w, E = 0.001, 0.03, 0.01, spec.material.E
    f = axial_factor(t, L, (0.005, 0.005))
    assert f == pytest.approx(30 / (30 + 2 * axial_root_compliance(0.005, t)))
    assert 0.94 < f < 0.96
    k = {}
    for roots in (True, False):
        C = compliance_matrix(beam_model(m, spec.material, roots=roots).model,
                              [Fixed("base")], "stage").matrix
        k[roots] = 1 / C[2, 2]
    assert k[False] == pytest.approx(2 * E * w * t / L, rel=1e-3)
    assert k[True] == pytest.approx(f * k[False], rel=1e-3)


def test_an_oblique_leafs_body_depth_is_along_the_leaf():
    m = load_spec(EXAMPLES / "cross_pivot.toml").spatial  # at 45 deg, out through the side
    assert block_depth(m, 0, 0) == pytest.approx(0.003 * math.sqrt(2), rel=1e-6)
    assert block_depth(m, 0, 1) == pytest.approx(0.003 * math.sqrt(2), rel=1e-6)


def test_the_warping_factor_falls_to_one_for_a_long_leaf():
    J = lambda w, t: w * t ** 3 / 3 * (1 - 0.63 * t / w)  # noqa: E731
    factors = [warping_factor(0.01, 0.001, L, 0.3, J(0.01, 0.001))
               for L in np.geomspace(0.01, 10.0, 12)]
    assert np.all(np.diff(factors) < 0) and factors[-1] == pytest.approx(1.0, abs=1e-3)
    lam = math.sqrt(J(0.01, 0.001) / (2.6 * 0.01 ** 3 * 0.001 ** 3 / 144))
    assert lam * 0.01 == pytest.approx(4.2, rel=0.02)  # lambda about 4.2 / w


ONE_LEAF = """
[material]
name = "structural_steel"
[[body]]
name = "base"
box = [[-0.007, -0.003, -0.005], [0.007, 0.003, 0.0]]
[[body]]
name = "top"
box = [[-0.007, -0.003, 0.03], [0.007, 0.003, 0.035]]
[[flexure]]
kind = "leaf"
between = ["base", "top"]
from = [0.0, 0.0, 0.0]
to = [0.0, 0.0, 0.03]
thickness = 0.001
width = 0.01
width_along = [1, 0, 0]
[[supports]]
group = "base"
[[loads]]
group = "top"
force = [0.0, 1.0, 0.0]
[analysis]
compliance = "top"
"""


@pytest.mark.slow
def test_a_short_leafs_torsion_is_the_continuums(tmp_path):
    """One leaf, w / L = 1/3, t = 1 mm: the continuum (105 k DOFs, 15 s) twists at 9.50
    N m/rad, Saint-Venant's G J / L is 8.01 (0.84 of it), the beam with the restrained
    warping 9.54 (1.004)."""
    from flexfem.studies.user_model.analysis import analyze_model

    path = tmp_path / "leaf.toml"
    path.write_text(ONE_LEAF)
    spec = load_spec(path)
    k = {m: 1 / np.array(analyze_model(spec, model=m)["compliance"]["matrix"])[5, 5]
         for m in ("beam", "continuum")}
    assert k["beam"] == pytest.approx(k["continuum"], rel=0.02)
