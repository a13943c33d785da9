"""The fast assembly paths of the beam model agree with their direct definitions: the rigid-link
Jacobian with finite differences of the constraint map, the condensed tangent by fixed pattern
with the sparse triple product T^T K T, the permutation parity with an inversion count, and the
chained flexure meshes with BeamMesh.join."""
import itertools

import numpy as np
import pytest
import scipy.sparse as sp

from beam_models import parallel_guide
from flexfem.fem.beam import BeamMesh, Section, beam_chain, solve_beam_nonlinear
from flexfem.fem.beam.supports import NodeFixed, NodePrescribed
from flexfem.fem.beam.assembly import BeamAssembler, _parity, global_matrix
from flexfem.fem.beam.pattern import Pattern
from flexfem.reduced.layout import _line_mesh, filleted_thickness, profile_beam


def deformed_guide(steel):
    """The parallel guide (two rigid-link slaves) with its stage moved 4 mm and turned: a
    state where the links' weights are not the undeformed ones. (assembler, z, lam)."""
    model, supports, stage = parallel_guide(steel, n=8)
    supports = supports + [NodePrescribed(stage, "y", 4e-3)]
    res = solve_beam_nonlinear(model, supports, steps=4)
    asm = BeamAssembler(model, supports, [])
    z = res.final.q.ravel()[asm.space.free] + 1e-3  # off equilibrium: r != 0 at the slaves
    return asm, z, 1.0


def test_link_jacobian_is_the_derivative_of_the_constraint_map(steel):
    asm, z, lam = deformed_guide(steel)
    space = asm.space
    T = space.jacobian(space.weights(space.q(z, lam))).toarray()
    h = 1e-7
    fd = np.column_stack([(space.q(z + h * e, lam) - space.q(z - h * e, lam)).ravel() / (2 * h)
                          for e in np.eye(space.n)])
    assert np.abs(T - fd).max() < 1e-7 * np.abs(fd).max()
    assert len(space.slaves) == 2 and np.abs(T).sum() > space.n  # the links' terms are there


def test_condensed_tangent_by_pattern_equals_the_triple_product(steel):
    asm, z, lam = deformed_guide(steel)
    first = asm.evaluate(z, lam).K  # sparse products
    second = asm.evaluate(z, lam)  # the fixed pattern (second tangent of the Space)
    space = asm.space
    T = space.jacobian(second.w)
    K_full = global_matrix(asm.model, second.ke, space.constraint_diagonal(second.q, second.r))
    direct = (T.T @ K_full @ T).toarray()
    scale = np.abs(direct).max()
    assert np.abs(second.K.toarray() - direct).max() < 1e-12 * scale
    assert np.abs(first.toarray() - direct).max() < 1e-12 * scale
    assert np.abs(space.constraint_diagonal(second.q, second.r)).max() > 0


def test_pattern_sums_duplicates_like_coo():
    rng = np.random.default_rng(1)
    rows, cols = rng.integers(0, 7, 60), rng.integers(0, 5, 60)
    values = rng.normal(size=60)
    expected = sp.coo_matrix((values, (rows, cols)), shape=(7, 5)).toarray()
    for fmt in ("csr", "csc"):
        assert np.allclose(Pattern(rows, cols, (7, 5), fmt).matrix(values).toarray(), expected,
                           rtol=0, atol=1e-14)


def test_parity_matches_inversion_count():
    rng = np.random.default_rng(2)
    perms = [rng.permutation(n) for n in (1, 2, 3, 7, 50, 333) for _ in range(4)]
    for perm in perms + [np.arange(9), np.roll(np.arange(10), 1)]:
        inversions = sum(a > b for a, b in itertools.combinations(perm.tolist(), 2))
        assert _parity(perm) == inversions % 2


def joined(a, b, fn, width, breaks, n_total, root, tol):
    """The flexure mesh by successive BeamMesh.join calls (what profile_beam chains)."""
    from flexfem.fem.beam import beam_from_profile
    a, b = np.asarray(a, float), np.asarray(b, float)
    length = float(np.linalg.norm(b - a))
    d = (b - a) / length
    cuts = [0.0, *breaks, length]
    mesh = None
    for s0, s1 in zip(cuts[:-1], cuts[1:]):
        part = beam_from_profile(a + s0 * d, a + s1 * d, lambda s, s0=s0: fn(s0 + s), width,
                                 max(4, int(round(n_total * (s1 - s0) / length))))
        mesh = part if mesh is None else mesh.join(part, tol=tol)
    t0, t1 = fn(0.0), fn(length)
    start, end = a - root * t0 * d, b + root * t1 * d
    mesh = beam_chain([start, a], Section.rect(width, t0), 1).join(mesh, tol=tol)
    return mesh.join(beam_chain([b, end], Section.rect(width, t1), 1), tol=tol)


def test_chained_flexure_mesh_equals_joined(steel):
    a, b, L, r = (0.01, 0.02), (0.03, 0.035), 0.025, 2e-3
    fn = filleted_thickness(L, 0.4e-3, r)
    chained = profile_beam(a, b, fn, 5e-3, (r, L - r), 24, root_extension=0.38)
    ref = joined(a, b, fn, 5e-3, (r, L - r), 24, 0.38, 1e-9 * L)
    assert np.array_equal(chained.nodes, ref.nodes)
    assert np.array_equal(chained.elements, ref.elements)
    assert [s.taper for s in chained.sections[1:-1]] == \
        [s.taper for s in ref.sections[1:-1]]
    assert chained.point_nodes == [0, len(ref.nodes) - 1]


def test_line_mesh_declines_coincident_nodes():
    """A piece shorter than the tolerance is left to BeamMesh.join's general merge."""
    sec = Section.rect(1e-3, 1e-3)
    tiny = BeamMesh(np.array([(1.0, 0.0), (1 + 1e-12, 0.0)]), np.array([[0, 1]]), [sec], [0, 1])
    parts = [beam_chain([(0, 0), (1, 0)], sec, 2), tiny]
    assert _line_mesh(parts, 1e-9) is None
    gap = [beam_chain([(0, 0), (1, 0)], sec, 2), beam_chain([(1.1, 0), (2, 0)], sec, 1)]
    assert _line_mesh(gap, 1e-9) is None
    ok = _line_mesh([beam_chain([(0, 0), (1, 0)], sec, 2), beam_chain([(1, 0), (2, 0)], sec, 3)],
                    1e-9)
    assert len(ok.nodes) == 6 and ok.elements.tolist() == [[k, k + 1] for k in range(5)]


def test_model_cache_is_read_only(steel):
    model, supports, stage = parallel_guide(steel, n=4)
    Kb = BeamAssembler(model, supports, []).Kb
    with pytest.raises(ValueError):
        Kb[0, 0, 0] = 0.0
    assert BeamAssembler(model, [NodeFixed(0)], []).Kb is Kb  # computed once per model


def test_factor_leaves_a_matrix_with_duplicates_alone():
    """Factor of a CSC matrix with a duplicate entry: the right solution, the matrix intact."""
    from flexfem.fem.beam.assembly import Factor
    K = sp.csc_matrix((np.array([4.0, 1.0, 1.0, 5.0, 6.0, 0.5]), np.array([0, 1, 0, 1, 2, 2]),
                       np.array([0, 2, 4, 6])), shape=(3, 3))  # (2, 2) = 6 + 0.5, stored twice
    assert not K.has_canonical_format
    dense, data, indices = K.toarray(), K.data.copy(), K.indices.copy()
    x = Factor(K).solve(np.array([1.0, 2.0, 3.0]))
    assert np.allclose(dense @ x, [1.0, 2.0, 3.0], rtol=0, atol=1e-12)
    assert np.array_equal(K.data, data) and np.array_equal(K.indices, indices)
