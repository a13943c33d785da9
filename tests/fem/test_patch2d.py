"""Plane-stress patches condensed onto beam nodes (flexfem.reduced.patch2d): a prismatic strip
condenses to the Timoshenko beam, a held face carries a pure moment and a pull as plane
sections do, and bad input names the problem."""
import numpy as np
import pytest
from flexfem.fem.beam import BeamModel, Section, beam_chain
from flexfem.fem.beam.supports import NodeFixed
from flexfem.fem.beam.compliance import compliance
from flexfem.fem.materials import Material
from flexfem.reduced.patch2d import TensorPatch, cell_edges, held_face, section

NU = 0.3


def _beam_compliance(a, L):
    """Tip compliance (x, y, theta) of a Timoshenko cantilever along y (E = 1, unit width,
    depth a, kappa 5/6), clamped at y = 0."""
    mesh = beam_chain([(a / 2, 0.0), (a / 2, L)], Section.rect(1.0, a), 4)
    model = BeamModel(mesh.nodes, mesh.elements, mesh.sections, Material("unit", 1.0, NU, 1.0),
                      shear=True)
    return compliance(model, [NodeFixed(0)], 4)


@pytest.mark.parametrize("cells", [4, 8])
def test_a_strip_between_two_sections_is_the_timoshenko_beam(cells):
    """With beam theory's tractions on its cuts the plane-stress strip is the Timoshenko
    beam (kappa = 5/6): its condensed compliance equals the beam's, axial and bending
    exactly, the shear deflection to the mesh error (4e-5 with 4 cells across)."""
    a, L = 1.0, 3.0
    patch = TensorPatch(cell_edges([0, a], a / cells), cell_edges([0, L], a / cells), NU)
    K, M = patch.condensed([section((0.0, 0.0), (a, 0.0)), section((0.0, L), (a, L))])
    assert np.linalg.eigvalsh(K)[:3] == pytest.approx(0.0, abs=1e-12)  # three rigid motions
    C, Cb = np.linalg.inv(K[3:, 3:]), _beam_compliance(a, L)
    assert C == pytest.approx(Cb, rel=1e-4, abs=1e-12 * np.abs(Cb).max())
    assert C[1, 1] == pytest.approx(Cb[1, 1], rel=1e-10)  # the pull
    assert C[2, 2] == pytest.approx(Cb[2, 2], rel=1e-10)  # the moment
    ones = np.tile([0.0, 1.0, 0.0], 2)  # the whole strip moved along y: its mass
    assert ones @ M @ ones == pytest.approx(a * L, rel=1e-12)


def test_a_held_face_carries_a_moment_and_a_pull_as_plane_sections():
    """A strip held on its end face along the normal (the tangential motion free) under a
    moment or a pull at its other end: plane sections stay plane and the lateral contraction
    is free, so the compliance is beam theory's, L / (E I) and L / (E A)."""
    a, L = 2.0, 5.0
    patch = TensorPatch(cell_edges([0, L], 0.5), cell_edges([0, a], 0.5), NU)
    K, _ = patch.condensed([held_face((0.0, 0.0), (0.0, a)), section((L, 0.0), (L, a))])
    C = np.linalg.inv(K[3:, 3:])  # the face's node held
    assert C[0, 0] == pytest.approx(L / a, rel=1e-10)
    assert C[2, 2] == pytest.approx(L / (a ** 3 / 12), rel=1e-10)


def test_a_segment_off_the_cell_boundaries_is_refused():
    patch = TensorPatch(cell_edges([0, 1], 0.5), cell_edges([0, 1], 0.5), NU)
    with pytest.raises(ValueError, match="not a boundary of whole cells"):
        patch.condensed([section((0.0, 0.1), (1.0, 0.1)), section((0.0, 1.0), (1.0, 1.0))])


def _saddle_condensed(patch, joints):
    """(K, M) on the joints from the whole saddle system [[K, Cu^T], [Cu, 0]] solved densely
    (M the consistent mass on its static modes): an independent check of the patch's banded
    flexibility route."""
    rows = [joint(patch) for joint in joints]
    Cu = np.vstack([C for C, _ in rows])
    Cg = np.zeros((len(Cu), 3 * len(rows)))
    r = 0
    for k, (C, G) in enumerate(rows):
        Cg[r:r + len(C), 3 * k:3 * k + 3] = G
        r += len(C)
    n, m = patch.n, len(Cu)
    S = np.block([[patch.K.toarray(), Cu.T], [Cu, np.zeros((m, m))]])
    solution = np.linalg.solve(S, np.vstack([np.zeros((n, Cg.shape[1])), -Cg]))
    return Cg.T @ solution[n:], patch.mass_of(solution[:n])


def test_a_stepped_patch_condenses_as_its_whole_saddle_system():
    """A member with a pad on part of one face (the DBMA's shape, off the origin), joined at
    two cuts and the pad's face: the stiffness from the patch held statically determinate
    and its mass equal the full saddle system's, and they keep the three rigid motions
    (no stiffness; the patch's mass and its polar moment about the origin)."""
    a, h, depth, cut = 1.0, 0.4, 0.3, 1.2
    xs = cell_edges([-depth, 0.0, a], a / 3, (0.0,), 1) + 2.0
    ys = cell_edges([-cut, -h, h, cut], a / 3, (-h, h), 1) - 1.0
    patch = TensorPatch(xs, ys, NU, keep=lambda x, y: (x > 2.0) | (np.abs(y + 1.0) < h))
    joints = [section((2.0, -1.0 - cut), (2.0 + a, -1.0 - cut)),
              section((2.0, cut - 1.0), (2.0 + a, cut - 1.0)),
              held_face((2.0 - depth, -1.0 - h), (2.0 - depth, h - 1.0))]
    K, M = patch.condensed(joints)
    K_ref, M_ref = _saddle_condensed(patch, joints)
    assert K == pytest.approx(K_ref, abs=1e-10 * np.abs(K_ref).max())
    assert M == pytest.approx(M_ref, abs=1e-10 * np.abs(M_ref).max())
    nodes = np.array([[2.0 + a / 2, -1.0 - cut], [2.0 + a / 2, cut - 1.0], [2.0 - depth, -1.0]])
    turn = np.column_stack([-nodes[:, 1], nodes[:, 0], np.ones(3)]).ravel()
    area = a * 2 * cut + depth * 2 * h
    second = lambda u0, u1, v0, v1: (u1 ** 3 - u0 ** 3) / 3 * (v1 - v0)  # int u^2 over a box
    polar = sum(second(x0, x1, y0, y1) + second(y0, y1, x0, x1) for x0, x1, y0, y1 in
                ((2.0, 2.0 + a, -1.0 - cut, cut - 1.0), (2.0 - depth, 2.0, -1.0 - h, h - 1.0)))
    for move, mass in ((np.tile([1.0, 0.0, 0.0], 3), area), (np.tile([0.0, 1.0, 0.0], 3), area),
                       (turn, polar)):
        assert np.abs(K @ move).max() < 1e-10 * np.abs(K).max()
        assert move @ M @ move == pytest.approx(mass, rel=1e-10)


def test_a_patch_in_two_pieces_is_refused():
    patch = TensorPatch(cell_edges([0, 1], 0.25), cell_edges([0, 1], 0.25), NU,
                        keep=lambda x, y: np.abs(x - 0.5) > 0.25)
    with pytest.raises(ValueError, match="not all connected"):
        patch.condensed([section((0.0, 0.0), (0.25, 0.0)), section((0.0, 1.0), (0.25, 1.0))])
