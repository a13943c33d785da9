"""Vectorised assembly of vector Lagrange elements: the isotropic linear-elastic stiffness, the
consistent mass and the displacement gradient at quadrature points, element block by element
block, straight into CSR.

No global list of triplets is built: the upper node-to-node pattern of the mesh (pairs of
nodes A <= B) is found once (:func:`node_pattern`, one sort of the elements' node pairs) and
shared by the stiffness and the mass; each element block's node blocks of its pairs
(node a <= node b) are summed into it with ``bincount`` over the block's distinct positions,
and the upper triangle is read from the node blocks into CSR directly. On affine simplices
the shape functions' gradients come from the reference gradients, computed once, and each
element's Jacobian. Vector DOFs are interleaved by node, as skfem numbers ElementVector: DOF
dim k + i is component i of scalar DOF k (checked).
"""
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import skfem

from .symmetric import symmetric_from_upper

# elements per block: bounds the temporaries to ~40 MB in 3-D P2 (30 x 30 element matrices)
BLOCK = 5_000


@dataclass(frozen=True)
class NodePattern:
    """Upper CSR pattern (``indptr``, ``indices``: row A holds the columns B >= A, the
    diagonal first) of the scalar DOF coupling; ``position`` (n_elements, n_local,
    n_local): where each element's pair (a, b) sits in ``indices``, the same slot for
    (a, b) and (b, a); ``upper`` (same shape, bool): node a <= node b, the pairs that are
    summed (each unordered pair once)."""

    indptr: np.ndarray
    indices: np.ndarray
    position: np.ndarray
    upper: np.ndarray

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
    on ``n_nodes`` scalar DOFs: the keys (min, max) of each element's local pairs a <= b
    sorted once."""
    n_local, n_el = nodes.shape
    d = nodes.T.astype(np.int64)
    a, b = np.triu_indices(n_local)
    lo, hi = np.minimum(d[:, a], d[:, b]), np.maximum(d[:, a], d[:, b])
    unique, position = np.unique((lo * n_nodes + hi).ravel(), return_inverse=True)
    del lo, hi
    index = _index_dtype(max(len(unique), n_nodes))
    indptr = np.zeros(n_nodes + 1, dtype=index)
    np.cumsum(np.bincount(unique // n_nodes, minlength=n_nodes), out=indptr[1:])
    full = np.empty((n_el, n_local, n_local), dtype=index)
    full[:, a, b] = position.reshape(n_el, len(a))
    full[:, b, a] = full[:, a, b]
    return NodePattern(indptr, (unique % n_nodes).astype(index), full,
                       d[:, :, None] <= d[:, None, :])


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


def reference_gradients(element: skfem.Element, points: np.ndarray) -> np.ndarray:
    """(n_local, dim, n_points) gradients of the scalar ``element``'s shape functions on the
    reference element at the reference ``points`` ((dim, n_points)), evaluated once per
    assembly (dimensionless)."""
    return np.stack([np.asarray(element.lbasis(points, a)[1]) for a in range(len(element.doflocs))])


def affine_jacobians(mesh: skfem.Mesh, block: slice) -> tuple[np.ndarray, np.ndarray]:
    """(A^-1 (n_elements, dim, dim) (1/m), |det A| (n_elements,) (m^dim)) of the elements
    ``block`` of an affine simplex mesh, A the Jacobian of the map from the reference element
    (the edge vectors from the first vertex)."""
    p = mesh.p[:, mesh.t[:, block]]                    # (dim, n_vertices, n_elements)
    A = (p[:, 1:] - p[:, :1]).transpose(2, 0, 1)      # (e, x, reference direction)
    return np.linalg.inv(A), np.abs(np.linalg.det(A))


def affine_gradients(mesh: skfem.Mesh, reference: np.ndarray, weights: np.ndarray,
                     block: slice) -> tuple[np.ndarray, np.ndarray]:
    """(G, dx) of the elements ``block`` of an affine simplex mesh: G (n_elements, n_local,
    dim, n_points) the physical gradients (1/m), A^-T times the ``reference`` gradients of
    :func:`reference_gradients`; dx (n_elements, n_points) = |det A| w (m^dim)."""
    inverse, determinant = affine_jacobians(mesh, block)  # inverse: (e, reference, x)
    G = np.einsum("erx,arq->eaxq", inverse, reference, optimize=True)
    return G, determinant[:, None] * weights[None, :]


def mapped_gradients(nodes: np.ndarray, geometry: np.ndarray, reference: np.ndarray,
                     weights: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(G, dx) of elements mapped isoparametrically: ``nodes`` (n_elements, n_geometry,
    dim) their geometry nodes (m), ``geometry`` (n_geometry, dim, n_points) the geometry
    shape functions' reference gradients, ``reference`` (n_local, dim, n_points) the field's;
    G (n_elements, n_local, dim, n_points) (1/m), dx (n_elements, n_points) = |det J| w
    (m^dim), J the map's Jacobian at each point."""
    J = np.einsum("eax,arq->eqxr", nodes, geometry, optimize=True)
    inverse = np.linalg.inv(J)                                       # (e, q, r, x)
    G = np.einsum("eqrx,arq->eaxq", inverse, reference, optimize=True)
    return G, np.abs(np.linalg.det(J)) * weights[None, :]


def block_gradients(mesh: skfem.Mesh, element: skfem.Element, quadrature):
    """(slice, G, dx) per block of BLOCK elements: the scalar shape functions' gradients
    (n_elements, n_local, dim, n_points) (1/m) and the quadrature weights times the Jacobian
    (n_elements, n_points) (m^dim), from the reference gradients computed once. Affine
    meshes (straight-sided triangles, tetrahedra): each element's constant Jacobian; others
    (curved, quadrilaterals, hexahedra): the Jacobian at each point from the mesh's geometry
    element (:func:`mapped_gradients`)."""
    points, weights = quadrature
    reference = reference_gradients(element, points)
    n_el = mesh.t.shape[1]
    if getattr(mesh, "affine", False):
        for start in range(0, n_el, BLOCK):
            block = slice(start, min(start + BLOCK, n_el))
            yield (block, *affine_gradients(mesh, reference, weights, block))
        return
    shape = mesh.elem()
    geometry = reference_gradients(shape, points)
    nodes = skfem.assembly.Dofs(mesh, shape).element_dofs        # (n_geometry, n_elements)
    for start in range(0, n_el, BLOCK):
        block = slice(start, min(start + BLOCK, n_el))
        X = mesh.doflocs[:, nodes[:, block]].transpose(2, 1, 0)  # (e, a, x)
        yield (block, *mapped_gradients(X, geometry, reference, weights))


def add_node_blocks(out: np.ndarray, pattern: NodePattern, block: slice,
                    values: np.ndarray) -> None:
    """Sum the element matrices ``values`` (n_elements, n_local dim, n_local dim; skfem's
    interleaved order) of the elements ``block`` into the node blocks ``out`` (nnz, dim, dim)
    of the upper ``pattern``: out[position[e, a, b], i, j] += values[e, a i, b j] over the
    pairs node a <= node b, counted over the block's distinct positions only (a block of P2
    elements touches rows of vertices and of edges, numbered far apart)."""
    n_b = values.shape[0]
    dim = out.shape[1]
    n_local = values.shape[1] // dim
    taken = np.flatnonzero(pattern.upper[block].ravel())
    slots, inverse = np.unique(pattern.position[block].ravel()[taken], return_inverse=True)
    values = values.reshape(n_b, n_local, dim, n_local, dim)
    summed = np.empty((len(slots), dim, dim))
    for i in range(dim):
        for j in range(dim):
            summed[:, i, j] = np.bincount(inverse, weights=values[:, :, i, :, j].ravel()[taken],
                                          minlength=len(slots))
    out[slots] += summed


def elasticity_blocks(mesh: skfem.Mesh, element: skfem.Element, quadrature,
                      pattern: NodePattern, dim: int, lam: float, mu: float,
                      thickness: float) -> np.ndarray:
    """(nnz, dim, dim) node blocks (N/m) of the isotropic linear-elastic stiffness on the
    :class:`NodePattern`; see :func:`elasticity_stiffness`. The form is linear in
    C[a i, b j] = t sum_q w d_i phi_a d_j phi_b, and each of its terms is a function of the
    node block (A, B) of C alone: C is summed over the elements first and the blocks
    combined once, K_AB = lam C_AB + mu C_AB^T + mu tr(C_AB) I."""
    C = np.zeros((len(pattern.indices), dim, dim))
    for block, G, dx in block_gradients(mesh, element, quadrature):
        n_b, n_local, _, n_q = G.shape
        G = G.reshape(n_b, n_local * dim, n_q)
        add_node_blocks(C, pattern, block,
                        np.matmul(G * (thickness * dx)[:, None, :], G.transpose(0, 2, 1)))
    blocks = lam * C
    blocks += mu * C.transpose(0, 2, 1)
    trace = np.einsum("pii->p", C)
    for i in range(dim):
        blocks[:, i, i] += mu * trace
    return blocks


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
    return symmetric_from_upper(elasticity_stiffness_upper(mesh, element, quadrature, pattern,
                                                           dim, lam, mu, thickness))


def elasticity_stiffness_upper(mesh: skfem.Mesh, element: skfem.Element, quadrature,
                               pattern: NodePattern, dim: int, lam: float, mu: float,
                               thickness: float):
    """The upper triangle (diagonal included, CSR, sorted) of :func:`elasticity_stiffness`,
    built from the node blocks directly (no full matrix)."""
    blocks = elasticity_blocks(mesh, element, quadrature, pattern, dim, lam, mu, thickness)
    return upper_csr(blocks, pattern, dim)


def tangent_stiffness_upper(mesh: skfem.Mesh, element: skfem.Element, quadrature,
                            pattern: NodePattern, dim: int, modulus: np.ndarray):
    """Upper triangle (CSR, sorted) of the tangent K_e[a i, b k] = sum_q w_q d_J phi_a
    A_iJkL d_L phi_b of a ``modulus`` A (dim, dim, dim, dim, n_elements, n_points) (N/m^2
    times the thickness in 2-D) at the points of ``quadrature``, with A's major symmetry
    (A_iJkL = A_kLiJ, as a hyperelastic tangent has): K symmetric. Element blocks batched
    (two matrix products per block), summed on the node pattern as the linear stiffness."""
    blocks = np.zeros((len(pattern.indices), dim, dim))
    for block, G, dx in block_gradients(mesh, element, quadrature):
        n_b, n_local, _, n_q = G.shape
        A = np.moveaxis(modulus[..., block, :], (4, 5), (0, 1)) * dx[:, :, None, None, None, None]
        Gq = G.transpose(0, 3, 1, 2)                                       # (e, q, a, J)
        W = np.matmul(Gq, A.transpose(0, 1, 3, 2, 4, 5).reshape(n_b, n_q, dim, -1))
        W = W.reshape(n_b, n_q, n_local, dim, dim, dim)                    # (e, q, a, i, k, L)
        W = W.transpose(0, 2, 3, 4, 1, 5).reshape(n_b, n_local * dim * dim, n_q * dim)
        K = np.matmul(W, Gq.transpose(0, 1, 3, 2).reshape(n_b, n_q * dim, n_local))  # (e, aik, b)
        K = K.reshape(n_b, n_local, dim, dim, n_local).transpose(0, 1, 2, 4, 3)
        add_node_blocks(blocks, pattern, block, K.reshape(n_b, n_local * dim, n_local * dim))
    return upper_csr(blocks, pattern, dim)


def upper_csr(blocks: np.ndarray, pattern: NodePattern, dim: int):
    """Upper triangle (diagonal included), CSR with sorted indices, of the symmetric matrix
    of the (nnz, dim, dim) node ``blocks`` on the upper ``pattern``, exact zeros dropped.
    Row dim A + i holds the diagonal block's columns j >= i and every block right of it:
    the contiguous range [dim d_A + i, dim e_A) of (block, column) pairs q = dim p + j,
    d_A the row's first (diagonal) block and e_A its end."""
    n_nodes, nnz = pattern.n, len(pattern.indices)
    first = pattern.indptr[:-1].astype(np.int64)
    if not np.array_equal(pattern.indices[first], np.arange(n_nodes)):
        raise ValueError("the node pattern lacks a diagonal entry: a node in no element")
    index = _index_dtype(nnz * dim * dim)
    start = (dim * first[:, None] + np.arange(dim)).ravel()
    length = np.repeat(dim * pattern.indptr[1:].astype(np.int64), dim) - start
    indptr = np.zeros(n_nodes * dim + 1, dtype=np.int64)
    np.cumsum(length, out=indptr[1:])
    q = np.arange(indptr[-1], dtype=index)
    q += np.repeat((start - indptr[:-1]).astype(index), length)
    p, j = np.divmod(q, dim)
    del q
    component = np.repeat(np.tile(np.arange(dim, dtype=index), n_nodes), length)
    data = blocks.reshape(-1)[p * (dim * dim) + component * dim + j]
    del component
    columns = pattern.indices[p].astype(index) * dim + j
    del p, j
    n = n_nodes * dim
    U = sp.csr_matrix((data, columns, indptr.astype(_index_dtype(len(data)))), shape=(n, n))
    U.has_sorted_indices = True
    U.eliminate_zeros()
    return U


def consistent_mass(mesh: skfem.Mesh, element: skfem.Element, quadrature,
                    pattern: NodePattern, dim: int, density: float):
    """Consistent mass matrix (kg), CSR: M_e[a i, b j] = delta_ij sum_q w_q rho t phi_a phi_b,
    ``density`` = rho t (kg/m^3 in 3-D, kg/m^2 in 2-D); other arguments as
    :func:`elasticity_stiffness`. Only the delta_ij entries are stored."""
    values = np.zeros((len(pattern.indices), 1, 1))
    if getattr(mesh, "affine", False):  # M_e = rho t |det A| times the reference element's
        points, weights = quadrature
        phi = np.stack([np.asarray(element.lbasis(points, a)[0])
                        for a in range(len(element.doflocs))])  # (a, q)
        reference = (phi * weights) @ phi.T
        for start in range(0, mesh.t.shape[1], BLOCK):
            block = slice(start, min(start + BLOCK, mesh.t.shape[1]))
            determinant = affine_jacobians(mesh, block)[1]
            add_node_blocks(values, pattern, block,
                            (density * determinant)[:, None, None] * reference)
    else:
        for block, scalar in element_blocks(mesh, element, quadrature):
            # a DiscreteField is the array of values in skfem >= 11, a named tuple before
            phi = np.stack([np.asarray(f[0]) if isinstance(f[0], np.ndarray) else f[0].value
                            for f in scalar.basis]).transpose(1, 0, 2)  # (e, a, q)
            m = np.matmul(phi * (density * scalar.dx)[:, None, :], phi.transpose(0, 2, 1))
            add_node_blocks(values, pattern, block, m)
    scalar_upper = sp.csr_matrix((values.ravel(), pattern.indices, pattern.indptr),
                                 shape=(pattern.n, pattern.n))
    return sp.kron(symmetric_from_upper(scalar_upper), sp.identity(dim), format="csr")


def geometric_stiffness(mesh: skfem.Mesh, element: skfem.Element, quadrature,
                        pattern: NodePattern, dim: int, stress: np.ndarray, thickness: float):
    """Initial-stress (geometric) stiffness (N/m), CSR, of the in-plane Cauchy ``stress``
    (dim, dim, n_elements, n_points) (Pa) at the points of ``quadrature``:
    K_e[a i, b j] = delta_ij t sum_q w_q grad phi_a . sigma . grad phi_b; other arguments as
    :func:`elasticity_stiffness`. Only the delta_ij entries are stored."""
    values = np.zeros((len(pattern.indices), 1, 1))
    for block, G, dx in block_gradients(mesh, element, quadrature):
        stressed = np.einsum("jleq,eblq->ebjq", stress[:, :, block], G, optimize=True)
        g = np.einsum("eajq,ebjq->eab", G * (thickness * dx)[:, None, None, :], stressed,
                      optimize=True)
        add_node_blocks(values, pattern, block, g)
    scalar_upper = sp.csr_matrix((values.ravel(), pattern.indices, pattern.indptr),
                                 shape=(pattern.n, pattern.n))
    return sp.kron(symmetric_from_upper(scalar_upper), sp.identity(dim), format="csr")


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
