"""Leaves with root fillets in a description of bodies and flexures: the beam model derived
from it against the 2-D continuum of the same description (independent truth: the
continuum meshes the fillets' arcs), for fillets shorter and longer than a beam element."""
import pytest

from flexfem.fem import material
from flexfem.geometry.mechanism.library import parallel_guide
from flexfem.geometry.user_model.spec import Analysis, mechanism_spec
from flexfem.studies.user_model.analysis import analyze_model

L, T, DEPTH = 0.04, 0.5e-3, 0.01


@pytest.mark.parametrize("fillet", [0.5e-3, 1e-3, 3e-3])
def test_a_filleted_guide_has_the_continuums_stiffness_and_first_mode(fillet):
    """A fillet of 0.5-3 mm on 2 mm beam elements: each fillet is meshed apart from the
    straight blade (an element spanning the fillet's end would be quadratic through a thick
    root and a thin middle and dip below the blade's thickness, 24 % soft at 1 mm), so the
    beam model stays within 3 % of the continuum in stiffness and first mode."""
    spec = mechanism_spec(parallel_guide(L, T, DEPTH, fillet=fillet),
                          material("structural_steel"), ["ground"], {"stage": (1.0, 0.0)},
                          Analysis(modes=1))
    continuum, beam = analyze_model(spec), analyze_model(spec, model="beam")
    k_c, k_b = (r["stiffness"]["stage"]["x"] for r in (continuum, beam))
    assert k_b == pytest.approx(k_c, rel=0.03)
    assert beam["frequencies_hz"][0] == pytest.approx(continuum["frequencies_hz"][0], rel=0.03)
