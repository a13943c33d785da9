"""The planar/spatial consistency test (issue 35): the parallel leaf guide of
examples/bodies/guide.toml (planar, analysed with --dim 3) and its spatial twin
examples/spatial/guide.toml (3-D boxes and leaves, the same shape) give the same numbers.

- The continuum: the same solid meshed by the same rules (half a leaf's thickness in the
  leaves, the bodies at half the shortest box side, 2.5 mm here), by two drawings (the
  planar outline extruded, the spatial boxes and plates fused), so the meshes differ cell by
  cell: the two stiffnesses agree to within the mesh's own discretisation error. At size
  factor 2 (4 s) they are 0.19 % apart while the mesh itself is 1.0 % from the default
  one (63 294 and 63 412 N/m against 62 689 and 62 700 at size factor 1, 0.016 % apart):
  held to 0.5 %.
- The beam model: the spatial model is the planar one without the planar root extension
  ([beam_model] root_extension = 0): equal to 3e-4 (1.3e-4 apart: the planar model's body
  stands at the centroid of its outline where no flexure meets it, 44.11 mm up, the
  spatial one at the body's centroid, 44.0 mm, so the force's lever differs by that, 3e-5;
  and the spatial leaves' roots are axially compliant, studies/spatial/roots.py, which the
  stage's tilt feels, 1e-4), the first frequency to 1e-4. With its default root extension (0.38 t per root, calibrated on the 2-D
  plane-stress continuum, docs/beam.md) the planar beam model is 6 % softer than both 3-D
  continua (58 738 against 62 700 N/m): the wide leaf's 3-D roots do not soften as the
  plane-stress ones do (the blocks' clamping of its anticlastic curl stiffens them,
  docs/spatial.md); the spatial beam model, without it, is within 1 % of the continuum.
"""
import dataclasses
from pathlib import Path

import pytest

from flexfem.geometry.user_model import load_spec
from flexfem.studies.user_model.analysis import analyze_model

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
PLANAR, SPATIAL = EXAMPLES / "bodies" / "guide.toml", EXAMPLES / "spatial" / "guide.toml"


def _static(spec):
    return dataclasses.replace(spec, analysis=dataclasses.replace(spec.analysis, modes=None))


def test_the_spatial_twin_is_the_planar_guide_extruded():
    planar, spatial = load_spec(PLANAR, dim=3), load_spec(SPATIAL)
    assert spatial.spatial is not None and planar.mechanism is not None
    assert planar.material == spatial.material
    for name in ("ground", "stage"):
        lo, hi = spatial.spatial.body(name).extent()
        (x0, y0), (x1, y1) = planar.mechanism.body(name).boxes[0]
        assert list(lo) == pytest.approx([x0, y0, 0.0]) and list(hi) == pytest.approx(
            [x1, y1, planar.mechanism.depth])
    for i, leaf in enumerate(spatial.spatial.flexures):
        span, flat = spatial.spatial.span(i), planar.mechanism.span(i)
        assert span.length == pytest.approx(flat.length)
        assert leaf.thickness == planar.mechanism.flexures[i].thickness
        assert leaf.width == planar.mechanism.depth


def test_the_continua_agree_within_their_mesh_error():
    k = {name: analyze_model(_static(spec), size_factor=2.0)["stiffness"]["stage"]["x"]
         for name, spec in (("planar", load_spec(PLANAR, dim=3)),
                            ("spatial", load_spec(SPATIAL)))}
    assert k["spatial"] == pytest.approx(k["planar"], rel=0.005)


def test_the_beam_models_agree_without_the_planar_root_extension():
    spatial = analyze_model(load_spec(SPATIAL), model="beam")
    planar = analyze_model(load_spec(PLANAR, {"beam_model.root_extension": 0.0}, dim=3),
                           model="beam")
    assert spatial["stiffness"]["stage"]["x"] == pytest.approx(
        planar["stiffness"]["stage"]["x"], rel=3e-4)
    assert spatial["frequencies_hz"][0] == pytest.approx(planar["frequencies_hz"][0],
                                                         rel=1e-4)
    E, L, t, w = 200e9, 0.04, 0.001, 0.01  # two fixed-guided leaves: 24 E I / L^3
    assert spatial["stiffness"]["stage"]["x"] == pytest.approx(24 * E * w * t ** 3 / 12
                                                               / L ** 3, rel=0.01)
