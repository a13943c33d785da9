"""Linear (eigenvalue) buckling of a planar beam model with named groups:
``solve_buckling(model, supports, loads, n) -> BeamBuckling``, the continuum's
:func:`flexfem.fem.buckling.solve_buckling` on the beam model.

About the linear static state of the loads (and the supports' prescribed values), the
critical load factors lambda and shapes phi solve (K + lambda K_g) phi = 0. K_g is each
element's consistent geometric (initial-stress) stiffness of its axial force N,
N int (N_w'^T N_w' + N_u'^T N_u') dx with the element's own interpolation (the cubic
Hermite functions, or Friedman & Kosmatka's for a Timoshenko element), plus the rigid links'
second-order term of the prebuckling forces (the load a rigid arm carries turns with it).
Shear-force and bending-moment terms are left out, as in the classical frame element: a
member that buckles while carrying mostly bending is outside it.
"""
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .assembly import DENSE_EIGEN_LIMIT, SingularBeamError
from .supports import load_vector
from .banded import spd_factor
from .element import (AXIAL, BEND, WXI, XI, gram, bending_shape_functions,
                      rotation_to_global, shear_parameter)
from .face import BeamResult, node_loads, node_supports, supported_groups
from .linear import linear_system
from .model import BeamModel
from .pattern import global_matrix
from .spatial.buckling import prebuckling as spatial_prebuckling
from .static import solve_beam_static


@dataclass(frozen=True, eq=False)
class BeamBuckling:
    """load_factors : (k,) critical multipliers (-) of the loads and prescribed values,
    ascending; shapes : (k, n_nodes, dofs per node) buckling shapes scaled to a largest
    translation of 1 (m per m; rotations rad per m, arbitrary sign); prebuckling : the face's
    static result (BeamResult, or Beam3DResult on a spatial model) that was scaled."""

    model: object
    load_factors: np.ndarray
    shapes: np.ndarray
    prebuckling: object

    def vertex_shape(self, k: int) -> np.ndarray:
        """(n_nodes, 2 or 3) translations of buckling shape k at the nodes (m per m)."""
        return self.shapes[k][:, :_translations(self.shapes.shape[2])].copy()

    def critical_reaction(self, group: str, k: int = 0) -> np.ndarray:
        """Reaction (N) of supported ``group`` at the k-th critical load: the prebuckling
        reaction times the load factor."""
        return self.load_factors[k] * self.prebuckling.reactions[group]


def geometric_stiffness(model: BeamModel, axial_force) -> np.ndarray:
    """(n_e, 6, 6) element geometric stiffness (N/m, N, N m) in global DOF order for the
    axial forces ``axial_force`` (n_e,) N (tension > 0)."""
    L = model.lengths
    _, dNw, _, _ = bending_shape_functions(XI, L, shear_parameter(model))
    local = np.zeros((model.n_elements, 6, 6))
    local[:, np.array(BEND)[:, None], np.array(BEND)[None, :]] = gram(
        WXI[None, :] * L[:, None], dNw, dNw)
    bar = np.array([[1.0, -1.0], [-1.0, 1.0]])
    local[:, np.array(AXIAL)[:, None], np.array(AXIAL)[None, :]] = bar / L[:, None, None]
    local *= np.asarray(axial_force, dtype=float)[:, None, None]
    T = rotation_to_global(model.angles)
    return np.matmul(T.transpose(0, 2, 1), local @ T)


def lowest_load_factors(K, G, n: int) -> tuple:
    """(lambda (k,) ascending, vectors (N, k)): the k <= n lowest positive load factors of
    (K + lambda G) phi = 0, solved as -G phi = mu K phi for the largest mu = 1 / lambda
    (dense up to DENSE_EIGEN_LIMIT unknowns, else Lanczos on a factor of K). ValueError
    where none is positive (the loads compress nothing)."""
    size = K.shape[0]
    if n >= size:
        raise ValueError(f"n = {n} buckling modes asked for but only {size} free DOFs exist")
    if size <= DENSE_EIGEN_LIMIT:
        try:
            mu, vectors = sla.eigh(-G.toarray(), K.toarray(), subset_by_index=[size - n, size - 1])
        except np.linalg.LinAlgError:
            raise SingularBeamError("solve_buckling: the stiffness is not positive definite: "
                                    "a mechanism; the supports leave a motion free") from None
    else:
        solve = spd_factor(K).solve
        op = spla.LinearOperator(K.shape, matvec=solve, matmat=solve, dtype=float)
        k = min(size - 1, n + 4)  # a few more: tension modes may take some slots
        try:
            mu, vectors = spla.eigsh(-G, k=k, M=K, Minv=op, which="LA", tol=1e-10,
                                     maxiter=100 * k)
        except spla.ArpackNoConvergence as partial:
            mu, vectors = partial.eigenvalues, partial.eigenvectors
    keep = np.flatnonzero(mu > 1e-12 * max(np.abs(mu).max(), 1e-300))
    if len(keep) == 0:
        raise ValueError("the loads put no beam in compression: no positive buckling load "
                         "factor")
    keep = keep[np.argsort(-mu[keep])][:n]
    return 1.0 / mu[keep], vectors[:, keep]


def scaled_shapes(full: np.ndarray, per_node: int) -> np.ndarray:
    """(k, n_nodes, per_node) shapes from (k, n_dofs), each scaled to a largest translation
    of 1 (to a largest rotation of 1 where it has no translation)."""
    shapes = full.reshape(len(full), -1, per_node)
    for s in shapes:
        big = np.abs(s[:, :_translations(per_node)]).max()
        s /= big if big > 1e-12 * np.abs(s).max() else np.abs(s).max()
    return shapes


def _translations(per_node: int) -> int:
    """Translations among a node's DOFs: 2 of the planar model's 3, 3 of the spatial 6."""
    return 2 if per_node == 3 else 3


def check_n(n) -> None:
    if isinstance(n, bool) or not (isinstance(n, (int, np.integer)) and n >= 1):
        raise ValueError(f"number of buckling modes n = {n!r} must be a positive integer")


def planar_prebuckling(model: BeamModel, held, nodal) -> tuple:
    """(linear state, reduced K, reduced K_g, T = dq/dz) of a planar model under node
    supports ``held`` and loads ``nodal``: K_g the elements' geometric stiffness of the
    state's axial forces plus the rigid links' second-order term of its forces about the
    reference configuration (zero rotation: linear buckling, whose factor does not depend
    on the size of the load)."""
    if model.superelements:
        raise ValueError("solve_buckling: the model has superelements, whose geometric "
                         "stiffness is unknown; solve the continuum")
    state = solve_beam_static(model, held, nodal)
    system = linear_system(model, held)
    space, ev = system.space, system.ev
    r = ev.full_times(state.q.ravel()) - load_vector(model, nodal)  # the prebuckling forces
    G = space.condense_global(global_matrix(model, geometric_stiffness(model,
                                                                       state.axial_force)),
                              ev.w)
    G = G + sp.diags(space.constraint_diagonal(np.zeros_like(state.q), r)[space.free])
    return state, ev.K, G.tocsc(), space.jacobian(ev.w)


def solve_buckling(model, supports, loads, n: int = 3, **options) -> BeamBuckling:
    """The ``n`` lowest positive critical load factors and shapes (per node: u_x, u_y, theta
    planar; u_x, u_y, u_z, r_x, r_y, r_z spatial) of the loads (Force on a group, N) and the
    prescribed values of the supports (held at zero in the shapes) of a grouped planar or
    spatial beam model. Raises ValueError if the loads compress no beam."""
    check_n(n)
    if options:
        raise TypeError(f"solve_buckling: option(s) {sorted(options)} are the continuum's; "
                        "the beam model takes none of them")
    prebuckling = planar_prebuckling if model.dim == 2 else spatial_prebuckling
    state, K, G, T = prebuckling(model, node_supports(model, supports),
                                 node_loads(model, loads))
    if not np.any(G.data):
        raise ValueError("the loads leave every beam without axial force: no buckling")
    factors, vectors = lowest_load_factors(K, G, n)
    full = np.asarray(T @ vectors).T
    return BeamBuckling(model, factors, scaled_shapes(full, model.PER_NODE),
                        BeamResult(model, state, tuple(supported_groups(supports))))
