"""One analysis face: the analyses dispatch on the model's type, and the results of the
planar and spatial beam models give the continuum's members under the same names
(result_face.SHARED), or raise NotOnModel naming the member and what they give instead."""
import dataclasses

import numpy as np
import pytest

from flexfem.fem import (Fixed, Force, Model, compliance_matrix, material, solve_harmonic,
                         solve_modes, solve_nonlinear, solve_static)
from flexfem.fem.analyses import DISPATCH
from flexfem.fem.beam import BeamGroup, BeamModel, Section, beam_chain
from flexfem.fem.beam.spatial import Beam3DModel
from flexfem.fem.beam.spatial import Section as Section3D
from flexfem.fem.compliance import Compliance
from flexfem.fem.harmonic import HarmonicResult
from flexfem.fem.modal import Modes
from flexfem.fem.nonlinear_result import NonlinearResult
from flexfem.fem.result_face import BEAM_STRAIN_LIMIT, SHARED, NotOnModel
from flexfem.fem.static_result import StaticResult

L, W, T, N = 0.05, 0.01, 0.5e-3, 20
STEEL = material("structural_steel")
CONTINUUM = {"static": StaticResult, "modes": Modes, "nonlinear": NonlinearResult,
             "compliance": Compliance, "harmonic": HarmonicResult}


def planar() -> BeamModel:
    mesh = beam_chain([(0, 0), (L, 0)], Section.rect(W, T), N)
    return BeamModel(mesh.nodes, mesh.elements, mesh.sections, STEEL,
                     groups={"root": [0], "tip": BeamGroup([N], (0.0, 0.0))})


def spatial() -> Beam3DModel:
    x = np.linspace(0.0, L, N + 1)
    nodes = np.column_stack([x, np.zeros_like(x), np.zeros_like(x)])
    elements = np.column_stack([np.arange(N), np.arange(1, N + 1)])
    return Beam3DModel(nodes, elements, Section3D.rect(W, T), STEEL,
                       groups={"root": [0], "tip": BeamGroup([N], (0.0, 0.0, 0.0))})


def results(model) -> dict:
    """One result of every kind on ``model`` (a tip force 0.01 N down; force = (0, -0.01))."""
    fixed, force = [Fixed("root")], [Force("tip", (0.0, -0.01))]
    return {"static": solve_static(model, fixed, force),
            "modes": solve_modes(model, 3, fixed),
            "nonlinear": solve_nonlinear(model, fixed, force, steps=2),
            "compliance": compliance_matrix(model, fixed, "tip"),
            "harmonic": solve_harmonic(model, fixed, force, [0.0, 10.0], n_modes=3)}


def members(cls) -> set:
    fields = {f.name for f in dataclasses.fields(cls)} if dataclasses.is_dataclass(cls) else set()
    return {n for n in set(dir(cls)) | fields if not n.startswith("_")}


@pytest.fixture(scope="module", params=["planar", "spatial"])
def beam_results(request):
    return results(planar() if request.param == "planar" else spatial())


def test_every_shared_member_is_the_continuums():
    for kind, names in SHARED.items():
        assert set(names) <= members(CONTINUUM[kind]), kind


@pytest.mark.parametrize("kind", sorted(SHARED))
def test_both_beam_models_give_every_shared_member(beam_results, kind):
    result = beam_results[kind]
    for name in SHARED[kind]:
        assert getattr(result, name) is not None or name in ("point", "frame"), name


def test_the_shared_methods_answer_on_both_beam_models(beam_results):
    static, path = beam_results["static"], beam_results["nonlinear"]
    assert static.mean_displacement("tip")[1] < 0
    assert static.strain_energy == pytest.approx(
        0.5 * 0.01 * -static.mean_displacement("tip")[1], rel=1e-9)
    assert static.applied_force.shape == static.u.shape
    assert static.von_mises_element_max.max() == pytest.approx(static.max_von_mises)
    displacement, force = path.force_displacement("tip")
    assert force[-1][:2] == pytest.approx([0.0, -0.01])
    assert displacement[-1] == pytest.approx(path.mean_displacement("tip"))
    assert path.force_displacement("root")[1][-1][1] == pytest.approx(0.01, rel=1e-6)
    assert path.stable.all() and path.strain_valid.all()
    assert path.strain_limit == BEAM_STRAIN_LIMIT
    assert path.max_strain[-1] == pytest.approx(path.max_von_mises / STEEL.E, rel=1e-6)
    assert not path.preloading.any() and path.preload_end == 0
    assert len(path.u) == len(path.load_factors) == len(path.stable)
    modes = beam_results["modes"]
    assert modes.dominant_direction(0) == 1 and modes.vertex_shape(0).shape[0] == N + 1
    harmonic = beam_results["harmonic"]
    assert harmonic.method == "modal"
    assert harmonic.frf("tip", "y").response[0] == pytest.approx(
        static.mean_displacement("tip")[1], rel=1e-6)


@pytest.mark.parametrize("kind", ["static", "nonlinear", "modes", "harmonic"])
def test_a_continuum_member_is_shared_or_refused_by_name(beam_results, kind):
    """Every public member of the continuum's result is shared, or the beam result refuses
    it with NotOnModel (an AttributeError) naming the member and what it gives instead."""
    result = beam_results[kind]
    refused = members(CONTINUUM[kind]) - set(SHARED[kind])
    assert refused == set(getattr(type(result), "unsupported", {})), kind
    for name in refused:
        with pytest.raises(NotOnModel, match=f"{type(result).__name__} has no .*\\({name}\\)"):
            getattr(result, name)
        assert not hasattr(result, name)


def test_the_refusal_names_the_member_the_model_and_what_it_gives():
    static = results(planar())["static"]
    with pytest.raises(AttributeError) as error:
        static.nodal_stress
    assert str(error.value) == ("BeamResult has no nodal stress field (nodal_stress): the beam "
                                "model gives beam stresses per element (beam_stress)")
    with pytest.raises(AttributeError, match="object has no attribute 'no_such'"):
        static.no_such


def test_the_analyses_dispatch_on_the_model_type():
    for name, function in DISPATCH.items():
        for cls in (Model, BeamModel, Beam3DModel):
            assert function.dispatch(cls) is not function.dispatch(object), (name, cls)
    model = planar()
    by_keyword = solve_static(model=model, supports=[Fixed("root")],
                              loads=[Force("tip", (0.0, -1.0))])
    by_position = solve_static(model, [Fixed("root")], [Force("tip", (0.0, -1.0))])
    assert by_keyword.mean_displacement("tip") == pytest.approx(
        by_position.mean_displacement("tip"), rel=1e-12)
    assert solve_modes(model=model, n=2, supports=[Fixed("root")]).frequencies_hz.shape == (2,)
    with pytest.raises(TypeError, match="solve_static: model is a str"):
        solve_static("model", [Fixed("root")])


def test_stable_counts_the_tangents_negative_eigenvalues_through_a_snap_through():
    """A shallow clamped arch pushed down at its apex (displacement control): two eigenvalues
    cross zero within one step near the load peak (the determinant's sign would not see it),
    the Sturm count does; the arch is stable again once inverted."""
    from flexfem.fem.beam import NodalLoad, solve_beam_nonlinear
    from flexfem.fem.beam.supports import NodeFixed
    from flexfem.fem.beam_result import BeamPath
    x = np.linspace(0.0, L, 41)
    mesh = beam_chain(list(zip(x, 0.002 * np.sin(np.pi * x / L))), Section.rect(W, 0.3e-3), 1)
    model = BeamModel(mesh.nodes, mesh.elements, mesh.sections, STEEL)
    result = solve_beam_nonlinear(model, [NodeFixed([0, 40])], [NodalLoad(20, 0.0, -1.0)],
                                  steps=40, control=(20, "y", -0.0044))
    path = BeamPath(model, result)
    stable, lam = path.stable, path.load_factors
    assert stable[:6].all() and not stable[6:25].any() and stable[25:].all()
    assert lam[5] < lam[6] and lam[24] < lam[23] and set(path.negative_eigenvalues) == {0, 2}
    assert not path.strain_valid.all() and path.strain_valid[:10].all()
