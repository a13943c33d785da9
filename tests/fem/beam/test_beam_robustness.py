"""Snap-through: load control stops with NonConvergenceError past the limit point,
displacement control passes it; bad arguments raise ValueError naming them."""
import pytest

from beam_models import cantilever
from flexfem.fem.beam import (BeamModel, NodalLoad, NonConvergenceError, RigidLink, Section,
                              SingularBeamError, beam_chain, beam_from_profile, compliance,
                              solve_beam_modes, solve_beam_nonlinear, solve_beam_static)
from flexfem.fem.beam.supports import NodeFixed, NodePrescribed


def shallow_arch(material, n=20):
    """Two bars (0, 0) - (0.05, 0.005) - (0.1, 0), rigidly joined at the apex, pinned ends."""
    mesh = beam_chain([(0, 0), (0.05, 0.005), (0.1, 0)], Section.rect(0.01, 1e-3), n)
    model = BeamModel(mesh.nodes, mesh.elements, mesh.sections, material)
    ends = (mesh.point_nodes[0], mesh.point_nodes[2])
    return model, [NodeFixed(ends, ("x", "y"))], mesh.point_nodes[1]


def test_snap_through(steel):
    model, supports, apex = shallow_arch(steel)
    res = solve_beam_nonlinear(model, supports, [NodalLoad(apex, fy=-1.0)], steps=40,
                               control=(apex, "y", -0.01))
    lam = res.load_factors
    peak = lam.max()
    assert peak > 0 and lam.min() < 0                # up the branch, past the limit, snapped
    assert res.final.q[apex, 1] == pytest.approx(-0.01)
    # the tangent loses definiteness where the path crosses the asymmetric bifurcation
    # (~30 N, before the symmetric limit point), the limit point and back: recorded
    assert len(res.info["definiteness_changes"]) >= 2
    # load control stops there rather than jump to the far branch or follow an unstable one
    with pytest.raises(NonConvergenceError, match="buckles or snaps") as info:
        solve_beam_nonlinear(model, supports, [NodalLoad(apex, fy=-1.2 * peak)], steps=10)
    assert 0 < info.value.load_factor < 1 / 1.2


def test_mechanism_raises(steel):
    model, tip = cantilever(steel, n=4)
    with pytest.raises(SingularBeamError):
        solve_beam_static(model, [NodeFixed(0, ("y", "theta"))], [NodalLoad(tip, fy=1.0)])
    with pytest.raises(NonConvergenceError):
        solve_beam_nonlinear(model, [NodeFixed(0, ("y", "theta"))], [NodalLoad(tip, fy=1.0)])


@pytest.mark.parametrize("make, name", [
    (lambda m: Section.rect(0.01, -1e-3), "thickness"),
    (lambda m: Section(A=1e-6, Iz=0.0), "Iz"),
    (lambda m: Section(A=1e-6, Iz=1e-12, factors=(1.0, 1.0)), "factors"),
    (lambda m: beam_chain([(0, 0)], Section.rect(0.01, 1e-3), 4), "points"),
    (lambda m: beam_chain([(0, 0), (1, 0)], Section.rect(0.01, 1e-3), 0), "n_per_segment"),
    (lambda m: beam_from_profile((0, 0), (1, 0), lambda s: -1.0, 0.01, 4), "thickness_fn"),
    (lambda m: BeamModel([(0, 0), (0, 0)], [(0, 1)], Section.rect(0.01, 1e-3), m),
     "zero length"),
    (lambda m: BeamModel([(0, 0), (1, 0)], [(0, 2)], Section.rect(0.01, 1e-3), m), "elements"),
    (lambda m: BeamModel([(0, 0), (1, 0)], [(0, 1)], Section.rect(0.01, 1e-3), "steel"),
     "material"),
    (lambda m: BeamModel([(0, 0), (1, 0)], [(0, 1)], Section.rect(0.01, 1e-3), m,
                         rigid_links=[RigidLink(0, (0,))]), "rigid_links"),
    (lambda m: NodeFixed(0, ("z",)).prescribed().__next__(), "dof"),
])
def test_bad_input_names_argument(steel, make, name):
    with pytest.raises(ValueError, match=name):
        make(steel)


def test_bad_solver_arguments(steel):
    model, tip = cantilever(steel, n=4)
    with pytest.raises(ValueError, match="steps"):
        solve_beam_nonlinear(model, [NodeFixed(0)], [NodalLoad(tip, fy=1.0)], steps=0)
    with pytest.raises(ValueError, match="control"):
        solve_beam_nonlinear(model, [NodeFixed(0)], [NodalLoad(tip, fy=1.0)], control=(0, "y", 1))
    with pytest.raises(ValueError, match="node"):
        compliance(model, [NodeFixed(0)], node=99)
    with pytest.raises(ValueError, match="held"):
        compliance(model, [NodeFixed(0)], node=0)
    with pytest.raises(ValueError, match="n = "):
        solve_beam_modes(model, [NodeFixed(0)], n=0)
    with pytest.raises(ValueError, match="supports"):
        solve_beam_static(model, [NodeFixed(9)], [])
    with pytest.raises(ValueError, match="loads"):
        solve_beam_static(model, [NodeFixed(0)], [NodalLoad(9, fy=1.0)])
    slave = BeamModel(model.nodes, model.elements, model.sections, steel,
                      rigid_links=[RigidLink(3, (4,))])
    with pytest.raises(ValueError, match="slave"):
        solve_beam_static(slave, [NodeFixed(0), NodePrescribed(4, "y", 1e-3)])
