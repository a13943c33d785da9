"""Vectorised assembly of vector Lagrange elements: the isotropic linear-elastic stiffness, the
consistent mass and the displacement gradient at quadrature points, element block by element
block, straight into CSR.

No global list of triplets is built: the node-to-node pattern of the mesh is found once
(:func:`node_pattern`, one sort of n_elements x n_local^2 keys), each element block's
(dim x dim) node blocks are summed into it with ``bincount``, and the result is converted from
block (BSR) to CSR form. Vector DOFs are interleaved by node, as skfem numbers ElementVector:
DOF dim k + i is component i of scalar DOF k (checked).
"""
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import skfem

# elements per block: bounds the temporaries to ~40 MB in 3-D P2 (30 x 30 element matrices)
BLOCK = 5_000


@dataclass(frozen=True)
class NodePattern:
    """CSR pattern (``indptr``, ``indices``) of the scalar DOF coupling, and ``position``
    (n_elements, n_local, n_local): where each element's pair (a, b) sits in ``indices``."""

    indptr: np.ndarray
    indices: np.ndarray
    position: np.ndarray

    @property
    def n(self) -> int:
        return len(self.indptr) - 1


def _index_dtype(n: int):
    return np.int32 if n <= np.iinfo(np.int32).max else np.int64


def node_dofs(element_dofs: np.ndarray, dim: int) -> np.ndarray:
    """(n_local, n_elements) scalar DOFs of the vector element DOFs ``element_dofs``
    ((n_local dim, n_elements)); ValueError if they are not interleaved by node."""
    nodes = element_dofs[::dim] // dim
    expected = dim * nodes[:, None, :] + np.arange(dim)[None, :, None]
    if not np.array_equal(element_dofs, expected.reshape(element_dofs.shape)):
        raise ValueError("element_dofs are not numbered dim k + i (component i of node k); "
                         "the blocked assembly needs skfem's ElementVector numbering")
    return nodes


def node_pattern(nodes: np.ndarray, n_nodes: int) -> NodePattern:
    """The :class:`NodePattern` of elements with scalar DOFs ``nodes`` ((n_local, n_elements))
    on ``n_nodes`` scalar DOFs."""
    n_local, n_el = nodes.shape
    d = nodes.T.astype(np.int64)
    keys = (d[:, :, None] * n_nodes + d[:, None, :]).ravel()
    unique, position = np.unique(keys, return_inverse=True)
    del keys
    index = _index_dtype(max(len(unique), n_nodes))
    rows = unique // n_nodes
    indptr = np.zeros(n_nodes + 1, dtype=index)
    np.cumsum(np.bincount(rows, minlength=n_nodes), out=indptr[1:])
    return NodePattern(indptr, (unique % n_nodes).astype(index),
                       position.astype(index).reshape(n_el, n_local, n_local))


def element_blocks(mesh: skfem.Mesh, element: skfem.Element, quadrature, dofs=None):
    """(slice, scalar CellBasis of those elements on ``quadrature``) per block of BLOCK
    elements; ``dofs``: the element's skfem Dofs, shared by the blocks."""
    n_el = mesh.t.shape[1]
    dofs = dofs if dofs is not None else skfem.assembly.Dofs(mesh, element)
    for start in range(0, n_el, BLOCK):
        block = slice(start, min(start + BLOCK, n_el))
        yield block, skfem.CellBasis(mesh, element, quadrature=quadrature, dofs=dofs,
                                     elements=np.arange(block.start, block.stop),
                                     disable_doflocs=True)


def scalar_gradients(scalar: skfem.CellBasis) -> np.ndarray:
    """(n_elements, n_local, dim, n_points) gradients (1/m) of the scalar shape functions."""
    return np.stack([phi[0].grad for phi in scalar.basis]).transpose(2, 0, 1, 3)


def _add_blocks(out: np.ndarray, position: np.ndarray, values: np.ndarray) -> None:
    """out[position] += values, duplicates summed; ``position`` (k,) and ``values`` (k,),
    counted over the range of positions the block touches only."""
    lo, hi = int(position.min()), int(position.max()) + 1
    out[lo:hi] += np.bincount(position - lo, weights=values, minlength=hi - lo)


def _to_csr(blocks: np.ndarray, pattern: NodePattern, dim: int):
    """CSR of the (nnz, dim, dim) node blocks on ``pattern``, exact zeros dropped as skfem
    does."""
    n = pattern.n * dim
    K = sp.bsr_matrix((blocks, pattern.indices, pattern.indptr), shape=(n, n)).tocsr()
    K.eliminate_zeros()
    return K


def elasticity_stiffness(mesh: skfem.Mesh, element: skfem.Element, quadrature,
                         pattern: NodePattern, dim: int, lam: float, mu: float,
                         thickness: float):
    """Isotropic linear-elastic stiffness (N/m), CSR, of the vector field of the scalar
    Lagrange ``element`` on ``mesh``, with the (points, weights) ``quadrature`` and the
    :class:`NodePattern` of the mesh; Lame constants ``lam``, ``mu`` (Pa), thickness ``t`` (m;
    1 in 3-D).

    K_e[a i, b j] = t sum_q w_q (lam d_i phi_a d_j phi_b + mu d_j phi_a d_i phi_b
    + mu delta_ij grad phi_a . grad phi_b), i.e. t (2 mu eps(u):eps(v) + lam div u div v).
    """
    blocks = np.zeros((len(pattern.indices), dim, dim))
    flat = blocks.reshape(len(pattern.indices), dim * dim)
    for block, scalar in element_blocks(mesh, element, quadrature):
        G = scalar_gradients(scalar)
        n_b, n_local, _, n_q = G.shape
        G = G.reshape(n_b, n_local * dim, n_q)
        C = np.matmul(G * (thickness * scalar.dx)[:, None, :], G.transpose(0, 2, 1))
        C = C.reshape(n_b, n_local, dim, n_local, dim)  # t sum_q w d_i phi_a d_j phi_b
        laplace = np.einsum("eakbk->eab", C)
        position = pattern.position[block].ravel()
        for i in range(dim):
            for j in range(dim):
                value = lam * C[:, :, i, :, j] + mu * C[:, :, j, :, i]
                if i == j:
                    value += mu * laplace
                _add_blocks(flat[:, i * dim + j], position, value.ravel())
    return _to_csr(blocks, pattern, dim)


def consistent_mass(mesh: skfem.Mesh, element: skfem.Element, quadrature,
                    pattern: NodePattern, dim: int, density: float):
    """Consistent mass matrix (kg), CSR: M_e[a i, b j] = delta_ij sum_q w_q rho t phi_a phi_b,
    ``density`` = rho t (kg/m^3 in 3-D, kg/m^2 in 2-D); other arguments as
    :func:`elasticity_stiffness`. Only the delta_ij entries are stored."""
    values = np.zeros(len(pattern.indices))
    for block, scalar in element_blocks(mesh, element, quadrature):
        # a DiscreteField is the array of values in skfem >= 11, a named tuple before
        phi = np.stack([np.asarray(f[0]) if isinstance(f[0], np.ndarray) else f[0].value
                        for f in scalar.basis]).transpose(1, 0, 2)  # (e, a, q)
        m = np.matmul(phi * (density * scalar.dx)[:, None, :], phi.transpose(0, 2, 1))
        _add_blocks(values, pattern.position[block].ravel(), m.ravel())
    scalar_mass = sp.csr_matrix((values, pattern.indices, pattern.indptr),
                                shape=(pattern.n, pattern.n))
    return sp.kron(scalar_mass, sp.identity(dim), format="csr")


def displacement_gradient(mesh: skfem.Mesh, element: skfem.Element, quadrature,
                          element_dofs: np.ndarray, dim: int, u: np.ndarray) -> np.ndarray:
    """(dim, dim, n_elements, n_points) gradient du_i/dx_j of the DOF vector ``u`` (m) at the
    points of ``quadrature``, from the scalar shape functions of ``element``, block by block
    (the vector basis of a 3-D P2 mesh would hold ~26 kB per element)."""
    n_local = element_dofs.shape[0] // dim
    ue = u[element_dofs].reshape(n_local, dim, -1)  # (a, i, e)
    out = np.empty((dim, dim, mesh.t.shape[1], len(quadrature[1])))
    for block, scalar in element_blocks(mesh, element, quadrature):
        out[:, :, block] = np.einsum("aie,eakq->ikeq", ue[:, :, block], scalar_gradients(scalar),
                                     optimize=True)
    return out
