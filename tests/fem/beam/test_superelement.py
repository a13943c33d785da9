"""Superelements in the planar beam model: a part given by its stiffness and mass matrices
assembles exactly as the elements it stands for, and bad input names the problem."""
import numpy as np
import pytest
from flexfem.fem.beam import (BeamModel, NodalLoad, RigidLink, Section, Superelement, beam_chain,
                              compliance, solve_beam_modes, solve_beam_nonlinear,
                              solve_beam_static)
from flexfem.fem.beam.supports import NodeFixed
from flexfem.fem.beam.assembly import BeamAssembler, mass_matrix
from flexfem.fem.beam.pattern import global_matrix
from flexfem.fem.materials import Material

STEEL = Material("steel", 200e9, 0.3, 7850.0)
MESH = beam_chain([(0.0, 0.0), (0.06, 0.01)], Section.rect(0.01, 1e-3), 6)


def _matrices(model: BeamModel) -> tuple:
    """(K, M) dense global matrices of a beam model (undeformed)."""
    ev = BeamAssembler(model, [], ()).evaluate(np.zeros(model.n_dofs), 0.0)
    return global_matrix(model, ev.ke).toarray(), mass_matrix(model).toarray()


def _models():
    """The chain as beams, and the same with its last three elements as a superelement on
    their four nodes; a rigid arm on the tip in both (the superelement's node a master)."""
    nodes = np.vstack([MESH.nodes, [0.07, 0.02]])
    links = [RigidLink(6, (7,))]
    whole = BeamModel(nodes, MESH.elements, MESH.sections, STEEL, shear=True,
                      rigid_links=links)
    part = BeamModel(MESH.nodes[3:], MESH.elements[3:] - 3, MESH.sections[3:], STEEL, shear=True)
    K, M = _matrices(part)
    split = BeamModel(nodes, MESH.elements[:3], MESH.sections[:3], STEEL, shear=True,
                      rigid_links=links, superelements=[Superelement((3, 4, 5, 6), K, M)])
    return whole, split


def test_a_superelement_assembles_as_the_elements_it_stands_for():
    whole, split = _models()
    load = [NodalLoad(7, fx=3.0, fy=-2.0, m=0.01)]
    a, b = (solve_beam_static(m, [NodeFixed(0)], load) for m in (whole, split))
    assert b.q == pytest.approx(a.q, rel=1e-10, abs=1e-14)
    assert compliance(split, [NodeFixed(0)], 6) == pytest.approx(compliance(whole, [NodeFixed(0)], 6),
                                                             rel=1e-10)
    fa, fb = (solve_beam_modes(m, [NodeFixed(0)], n=4) for m in (whole, split))
    assert fb.frequencies_hz == pytest.approx(fa.frequencies_hz, rel=1e-10)
    assert fb.effective_mass == pytest.approx(fa.effective_mass, rel=1e-8)


def test_the_nonlinear_solver_refuses_a_superelement():
    _, split = _models()
    with pytest.raises(ValueError, match="superelements, which are linear"):
        solve_beam_nonlinear(split, [NodeFixed(0)], [NodalLoad(6, fy=1.0)])


@pytest.mark.parametrize("nodes, K, match", [
    ((3,), np.eye(3), "two or more distinct nodes"),
    ((3, 3), np.eye(6), "two or more distinct nodes"),
    ((3, 4), np.eye(5), "finite 6 x 6 matrix"),
    ((3, 4), np.triu(np.ones((6, 6))), "stiffness must be symmetric"),
    ((3, 4), np.full((6, 6), np.nan), "finite 6 x 6 matrix"),
])
def test_bad_superelements_are_refused(nodes, K, match):
    with pytest.raises(ValueError, match=match):
        Superelement(nodes, K, np.eye(len(K)) if K.shape[0] == K.shape[1] else K)


def test_a_superelement_off_the_model_is_refused():
    with pytest.raises(ValueError, match="outside 0..6"):
        BeamModel(MESH.nodes, MESH.elements, MESH.sections, STEEL,
                  superelements=[Superelement((5, 9), np.eye(6), np.eye(6))])
