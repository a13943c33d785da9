"""The memory-lean paths of fem/assembly.py and fem/model.py give what skfem's own gives: the
lazily evaluated basis, the node pattern and the stress from the scalar shape functions."""
import numpy as np
import pytest
import scipy.sparse as sp
import skfem
from flexfem.fem import FEMesh, Model, PlaneStress, Solid3D, assembly
from flexfem.fem.model import LazyCellBasis
from skfem.helpers import grad

def _bent(mesh):
    """``mesh`` with its vertices moved off a regular grid (non-parallelogram cells)."""
    return mesh.morphed(lambda p: p[0] + 0.1 * np.sin(3 * p[1]) * p[0],
                        lambda p: p[1] + 0.08 * np.cos(2 * p[0]) * p[1])


MESHES = {
    "tri": lambda: skfem.MeshTri().refined(2),
    "quad": lambda: skfem.MeshQuad().refined(2),
    "tet": lambda: skfem.MeshTet().refined(1),
    "hex": lambda: skfem.MeshHex().refined(1),
    "bent quad": lambda: _bent(skfem.MeshQuad().refined(2)),
    "bent hex": lambda: _bent(skfem.MeshHex().refined(1)),
}


def _curved_tet(mesh):
    """A FEMesh of ``mesh`` (tetrahedra) with every edge's middle node moved off its
    midpoint (isoparametric cells, fem/curved.py's edge_nodes)."""
    middle = (mesh.p[:, mesh.edges[0]] + mesh.p[:, mesh.edges[1]]) / 2
    return FEMesh(mesh, edge_nodes=middle + 0.02 * np.sin(7 * middle[::-1]))


@pytest.mark.parametrize("name", list(MESHES))
def test_lazy_basis_equals_skfem_basis(name):
    mesh, kind = MESHES[name](), name.split()[-1]
    element = skfem.ElementVector(skfem.ElementTriP2() if kind == "tri" else
                                  skfem.ElementQuad2() if kind == "quad" else
                                  skfem.ElementTetP2() if kind == "tet" else skfem.ElementHex2())
    lazy, eager = LazyCellBasis(mesh, element, intorder=4), skfem.CellBasis(mesh, element, intorder=4)
    assert "basis" not in lazy.__dict__  # nothing evaluated on construction
    assert np.array_equal(lazy.element_dofs, eager.element_dofs)
    assert np.array_equal(lazy.doflocs, eager.doflocs)
    assert np.array_equal(lazy.dx, eager.dx)
    for a, b in zip(lazy.basis, eager.basis):
        assert np.array_equal(np.asarray(a[0].grad), np.asarray(b[0].grad))
    some = lazy.with_elements(np.arange(3))
    assert isinstance(some, LazyCellBasis) and some.dx.shape == (3, len(lazy.W))
    u = np.random.default_rng(0).standard_normal(lazy.N)
    assert np.array_equal(grad(lazy.interpolate(u)), grad(eager.interpolate(u)))


def test_node_pattern_positions_hold_each_element_pair():
    mesh = skfem.MeshTet().refined(1)
    nodes = skfem.CellBasis(mesh, skfem.ElementTetP2()).element_dofs
    pattern = assembly.node_pattern(nodes, nodes.max() + 1)
    rows = np.repeat(np.arange(pattern.n), np.diff(pattern.indptr))
    # entry position[e, a, b] is the pair (min, max) of (nodes[a, e], nodes[b, e]): the upper
    # pattern, each row's diagonal first, no pair stored twice; ``upper`` marks node a <= b
    pos = pattern.position
    a = np.broadcast_to(nodes.T[:, :, None], pos.shape)
    b = np.broadcast_to(nodes.T[:, None, :], pos.shape)
    assert np.array_equal(rows[pos], np.minimum(a, b))
    assert np.array_equal(pattern.indices[pos], np.maximum(a, b))
    assert np.array_equal(pattern.indices[pattern.indptr[:-1]], np.arange(pattern.n))
    assert np.array_equal(pattern.upper, a <= b)
    assert len(set(zip(rows, pattern.indices))) == len(rows)


@pytest.mark.parametrize("name", list(MESHES))
def test_stiffness_and_mass_equal_skfem_asm(name, steel, monkeypatch):
    """K (upper triangle, from the reference gradients on simplices) and M equal skfem's own
    ``asm`` of the same forms to round-off (measured <= 6e-16 of the largest entry), over
    several blocks, the last one short."""
    from skfem.helpers import dot
    from skfem.models.elasticity import linear_elasticity
    mesh = MESHES[name]()
    monkeypatch.setattr(assembly, "BLOCK", 7)
    form = PlaneStress(0.01) if mesh.dim() == 2 else Solid3D()
    model = Model(FEMesh(mesh), steel, form, order=2)
    lam, mu = model.lame
    K = skfem.asm(linear_elasticity(lam, mu), model.stiffness_basis) * model.thickness
    rho_t = steel.rho * model.thickness
    M = skfem.asm(skfem.BilinearForm(lambda u, v, w: rho_t * dot(u, v)), model.basis)
    assert abs(model.stiffness - K).max() <= 1e-12 * abs(K).max()
    assert abs(model.stiffness_upper - sp.triu(model.stiffness)).max() == 0
    assert abs(model.mass - M).max() <= 1e-12 * abs(M).max()


def test_curved_cells_stiffness_and_mass_equal_skfem_asm(steel, monkeypatch):
    """On isoparametric (curved) P2 tetrahedra the Jacobian at each point comes from the
    geometry nodes (assembly.mapped_gradients): K and M equal skfem's asm on MeshTet2."""
    from skfem.helpers import dot
    from skfem.models.elasticity import linear_elasticity
    monkeypatch.setattr(assembly, "BLOCK", 7)
    model = Model(_curved_tet(skfem.MeshTet().refined(1)), steel, Solid3D(), order=2)
    assert isinstance(model.cell_mesh, skfem.MeshTet2) and not model.is_affine
    lam, mu = model.lame
    K = skfem.asm(linear_elasticity(lam, mu), model.stiffness_basis)
    M = skfem.asm(skfem.BilinearForm(lambda u, v, w: steel.rho * dot(u, v)), model.basis)
    assert abs(model.stiffness - K).max() <= 1e-12 * abs(K).max()
    assert abs(model.mass - M).max() <= 1e-12 * abs(M).max()
    straight = Model(FEMesh(model.mesh.mesh), steel, Solid3D(), order=2)
    assert abs(straight.stiffness - K).max() > 1e-3 * abs(K).max()   # the curving counts


def test_node_dofs_refuses_a_numbering_not_by_node():
    dofs = np.arange(12).reshape(6, 2)  # DOF a dim + i is not dim k + i here
    with pytest.raises(ValueError, match="not numbered dim k"):
        assembly.node_dofs(dofs[::-1], 3)


@pytest.mark.parametrize("dim", [2, 3])
def test_stress_from_scalar_functions_equals_vector_basis(steel, dim, monkeypatch):
    mesh = skfem.MeshTri().refined(2) if dim == 2 else skfem.MeshTet().refined(1)
    model = Model(FEMesh(mesh), steel, PlaneStress(0.01) if dim == 2 else Solid3D(), order=2)
    u = np.random.default_rng(1).standard_normal(model.n_dofs) * 1e-6
    monkeypatch.setattr(assembly, "BLOCK", 7)  # several blocks, the last one short
    lean = model.stress(u)
    assert "basis" not in model.basis.__dict__  # the vector basis was not evaluated
    full = model.stress(u, model.basis)
    assert np.abs(lean - full).max() <= 1e-12 * np.abs(full).max()


def test_blocks_of_any_size_give_the_same_matrices(steel, monkeypatch):
    mesh = skfem.MeshTet().refined(1)
    K0, M0 = (m := Model(FEMesh(mesh), steel, Solid3D())).stiffness, m.mass
    monkeypatch.setattr(assembly, "BLOCK", 5)
    K1, M1 = (m := Model(FEMesh(mesh), steel, Solid3D())).stiffness, m.mass
    assert abs(K1 - K0).max() <= 1e-14 * abs(K0).max()
    assert abs(M1 - M0).max() <= 1e-14 * abs(M0).max()


@pytest.mark.parametrize("name", ["tri", "tet", "hex"])
def test_geometric_stiffness_equals_skfem_asm(name, steel):
    """The initial-stress stiffness on the node pattern equals skfem's assembly of
    t grad v . sigma . grad du on the vector basis (measured <= 7e-16 of its largest entry)."""
    from flexfem.fem.hyperelastic import geometric_stiffness

    @skfem.BilinearForm
    def form(du, v, w):
        return w.t * np.einsum("ij...,jl...,il...->...", grad(v), w.S, grad(du))

    mesh = MESHES[name]()
    model = Model(FEMesh(mesh), steel, PlaneStress(0.01) if name == "tri" else Solid3D(), order=2)
    u = np.random.default_rng(2).standard_normal(model.n_dofs) * 1e-5
    stress = model.stress(u, model.basis)[:model.dim, :model.dim]
    expected = form.assemble(model.basis, S=stress, t=model.thickness)
    G = geometric_stiffness(model, u)
    assert abs(G - expected).max() <= 1e-12 * abs(expected).max()
