"""geometry/spatial/composites.py: the functions give examples/spatial's mechanisms number for
number, the folded leaf guide is two leaf guides in series (beam model against 12 E I / L^3,
the fold at half the stage's travel), and bad numbers are refused by name."""
from pathlib import Path

import numpy as np
import pytest

from flexfem.fem import Fixed, Force, compliance_matrix, material, solve_static
from flexfem.fem.checks import InputError
from flexfem.geometry.spatial import composites
from flexfem.geometry.user_model import load_spec
from flexfem.studies.spatial.beam_model import beam_model

EXAMPLES = Path(__file__).resolve().parents[3] / "examples" / "spatial"
STEEL = material("structural_steel")


@pytest.mark.parametrize("name, function", [
    ("wire_guide", "wire_guide"), ("leaf_guide", "leaf_guide"), ("cross_pivot", "cross_pivot"),
    ("folded_guide", "folded_leaf_guide")])
def test_each_function_is_its_example_file(name, function):
    built, read = getattr(composites, function)(), load_spec(EXAMPLES / f"{name}.toml").spatial
    assert [b.name for b in built.bodies] == [b.name for b in read.bodies]
    for b, r in zip(built.bodies, read.bodies):
        assert np.allclose(b.boxes, r.boxes, rtol=0, atol=1e-12)
    assert len(built.flexures) == len(read.flexures)
    for f, r in zip(built.flexures, read.flexures):
        assert (f.kind, f.name, f.between) == (r.kind, r.name, r.between)
        assert np.allclose([f.start, f.end], [r.start, r.end], rtol=0, atol=1e-12)
        sizes = ("diameter",) if f.kind == "wire" else ("thickness", "width", "width_along")
        assert all(np.allclose(getattr(f, k), getattr(r, k)) for k in sizes)


def test_the_folded_guide_is_two_leaf_guides_in_series():
    numbers = dict(L=30e-3, t=1e-3, w=10e-3)
    single, folded = (beam_model(m, STEEL) for m in
                      (composites.leaf_guide(**numbers), composites.folded_leaf_guide(**numbers)))
    k = [1 / compliance_matrix(b.model, [Fixed("base")], "stage").matrix[1, 1]
         for b in (single, folded)]
    assert k[1] == pytest.approx(composites.closed_form_stiffness(
        "folded_leaf_guide", STEEL.E, **numbers), rel=0.02)
    assert k[1] == pytest.approx(k[0] / 2, rel=0.005)
    state = solve_static(folded.model, [Fixed("base")], [Force("stage", (0.0, 1.0, 0.0))])
    fold, stage = (state.mean_displacement(g)[1] for g in ("fold", "stage"))
    assert fold == pytest.approx(stage / 2, rel=0.01)


def test_bad_numbers_are_refused_by_name():
    with pytest.raises(InputError, match="L"):
        composites.wire_guide(L=-0.03)
    with pytest.raises(ValueError, match="outer .* must exceed inner"):
        composites.folded_leaf_guide(outer=20e-3, inner=16e-3)
    with pytest.raises(ValueError, match="intersects"):
        composites.leaf_guide(d=0.5e-3)      # the two leaves' sections overlap
