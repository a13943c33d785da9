"""Linear static analysis: ``solve_static(model, supports, loads) -> StaticResult``."""
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.sparse.csgraph import connected_components
import skfem

from . import linsolve, stress
from .boundary import component_indices, constrained_dofs, load_vector
from .model import Model, rigid_body_modes, scalar_element, von_mises


class UnderConstrainedError(linsolve.SingularSystemError):
    """The supports leave rigid-body motions free."""


@dataclass(frozen=True, eq=False)
class StaticResult:
    """Fields and metrics of a static solve. Displacements in m, stresses in Pa, forces in N,
    energy in J.

    u : DOF vector; displacement : (n_vertices, dim) at the mesh vertices;
    von_mises_nodal : (n_vertices,) from the stress components L2-projected onto
    continuous linear fields; nodal_stress_full : (n_vertices, 3, 3) those projected Cauchy
    stress components (2-D: with sigma_zz); von_mises_element_max :
    (n_elements,) maximum over each element's quadrature points; reactions : {group: force
    vector} on every supported group; strain_energy : 1/2 u.K.u; solver : the linear solver
    used, 'mkl-pardiso', 'cholmod', 'superlu' (direct) or 'amg-cg' ('none': no load).
    """

    model: Model
    u: np.ndarray
    displacement: np.ndarray
    von_mises_nodal: np.ndarray
    von_mises_element_max: np.ndarray
    reactions: dict
    applied_force: np.ndarray
    strain_energy: float
    solver: str = "none"
    info: dict = field(default_factory=dict)
    nodal_stress_full: np.ndarray | None = None

    @property
    def nodal_stress(self) -> np.ndarray:
        """(n_vertices, dim, dim) Cauchy stress (Pa), L2-projected onto continuous linear
        fields (``nodal_stress_full`` has the 3 x 3 tensors)."""
        d = self.model.dim
        return self.nodal_stress_full[:, :d, :d]

    def stress_at(self, points, full: bool = False) -> np.ndarray:
        """(n, dim, dim) Cauchy stress (Pa) at ``points`` ((n, dim), m), evaluated in the
        element containing each point (no smoothing); (n, 3, 3) with ``full``. A point outside
        the body raises ValueError."""
        return stress.stress_at(self, points, full)

    @property
    def max_von_mises(self) -> float:
        """Largest nodal (recovered) von Mises stress, Pa."""
        return float(self.von_mises_nodal.max())

    @property
    def max_von_mises_location(self) -> np.ndarray:
        """Coordinates (m) of the vertex with the largest nodal von Mises stress."""
        return self.model.mesh.mesh.p[:, int(np.argmax(self.von_mises_nodal))]

    @property
    def max_von_mises_element(self) -> float:
        """Largest von Mises stress at any quadrature point, Pa (unsmoothed)."""
        return float(self.von_mises_element_max.max())

    def mean_displacement(self, group: str) -> np.ndarray:
        """Area- (or volume-) averaged displacement (m) of a boundary group or subdomain."""
        return mean_field(self.model, self.u, group)


def mean_field(model: Model, u: np.ndarray, group: str) -> np.ndarray:
    """Average of the vector field ``u`` (DOF vector) over a boundary group or subdomain."""
    mesh = model.mesh
    if group in mesh.boundaries:
        basis = skfem.FacetBasis(mesh.mesh, model.basis.elem, facets=mesh.facets(group),
                                 intorder=2 * model.order)
    else:
        basis = model.basis.with_elements(mesh.elements(group))
    uh = basis.interpolate(u)
    w = basis.dx
    return np.array([np.sum(uh[i] * w) for i in range(model.dim)]) / np.sum(w)


def nodal_average(model: Model, values: np.ndarray) -> np.ndarray:
    """L2 projection of quadrature-point values ((..., n_elements, n_points)) onto continuous
    piecewise-linear fields at the mesh vertices (consistent P1 mass matrix, so a linear stress
    field is recovered exactly; scikit-fem issue #618)."""
    mesh = model.mesh.mesh
    hat = skfem.CellBasis(mesh, scalar_element(mesh, 1), quadrature=(model.basis.X, model.basis.W))
    flat = values.reshape((-1,) + hat.dx.shape)
    M = skfem.BilinearForm(lambda u, v, w: u * v).assemble(hat).tocsr()
    jacobi = sp.diags(1.0 / M.diagonal())
    nodal = np.zeros((len(flat), mesh.p.shape[1]))
    done = []  # components projected so far; a zero or repeated one (sigma_ji) is not redone
    for k, component in enumerate(flat):
        if not np.any(component):
            continue
        same = next((j for j in done if np.array_equal(flat[j], component)), None)
        if same is not None:
            nodal[k] = nodal[same]
            continue
        b = skfem.LinearForm(lambda v, w: w["s"] * v).assemble(hat, s=component)
        nodal[k], info = spla.cg(M, b, rtol=1e-12, atol=0.0, M=jacobi, maxiter=1000)
        done.append(k)
    return nodal.reshape(values.shape[:-2] + (mesh.p.shape[1],))


def vertex_displacement(model: Model, u: np.ndarray) -> np.ndarray:
    """(n_vertices, dim) displacement at the mesh vertices."""
    return np.stack([u[dofs] for dofs in model.basis.nodal_dofs], axis=1)


def rigid_body_dof_modes(model: Model) -> np.ndarray:
    """Rigid-body modes as DOF vectors, (n_dofs, 3) in 2-D or (n_dofs, 6) in 3-D."""
    locs = model.basis.doflocs
    comp = np.empty(model.n_dofs, dtype=int)
    for i, idx in enumerate(component_indices(model)):
        comp[idx] = i
    per_node = rigid_body_modes(locs)  # (n_modes, n_dofs, dim), evaluated at every DOF location
    return per_node[:, np.arange(model.n_dofs), comp].T


def check_supports(model: Model, D: np.ndarray) -> None:
    """Raise :class:`UnderConstrainedError` if the constrained DOFs ``D`` leave a rigid-body
    motion free."""
    modes = rigid_body_dof_modes(model)
    n_modes = modes.shape[1]
    if len(D) == 0:
        raise UnderConstrainedError(f"the model has no supports: all {n_modes} rigid-body modes are "
                                    "free; add a Fixed or Prescribed support")
    parts = body_parts(model)
    held = np.zeros(model.n_dofs, dtype=bool)
    held[D] = True
    for k, part in enumerate(parts):
        rows = modes[part[held[part]]]
        s = np.linalg.svd(rows, compute_uv=False) if len(rows) else np.zeros(0)
        free = n_modes - int(np.sum(s >= 1e-9 * max(np.abs(modes).max(), 1.0) * np.sqrt(len(D))))
        if not free:
            continue
        if len(parts) == 1:
            raise UnderConstrainedError(
                f"the supports leave {free} of {n_modes} rigid-body modes free (e.g. a "
                "translation along an unheld axis, or a rotation about a point or line of held "
                "nodes); add supports")
        where = model.basis.doflocs[:, part].mean(axis=1)
        raise UnderConstrainedError(
            f"the mesh has {len(parts)} disconnected parts and part {k + 1} (centred near "
            f"{np.round(where, 6).tolist()} m) has {free} of {n_modes} rigid-body modes free: "
            "connect it to the rest of the body or give it its own supports")


def body_parts(model: Model) -> list[np.ndarray]:
    """DOF indices of each connected part of the mesh (elements sharing a vertex are
    connected), largest part first."""
    mesh = model.mesh.mesh
    n_vertices = mesh.p.shape[1]
    # a chain through each element's vertices connects them all: enough for the components
    heads, tails = mesh.t[:-1].ravel(), mesh.t[1:].ravel()
    chain = sp.coo_matrix((np.ones(heads.size), (heads, tails)), shape=(n_vertices, n_vertices))
    n_parts, label = connected_components(chain, directed=False)
    if n_parts == 1:
        return [np.arange(model.n_dofs)]
    element_part = label[mesh.t[0]]
    dofs = model.basis.element_dofs
    parts = [np.unique(dofs[:, element_part == k]) for k in range(n_parts)]
    return sorted(parts, key=len, reverse=True)


def solve_static(model: Model, supports, loads, solver: str = "auto") -> StaticResult:
    """Solve K u = f with the displacement ``supports`` (Fixed, Prescribed) and ``loads``
    (Force, Traction, Pressure, PointForce, BodyForce, Gravity). ``solver``: 'auto', 'direct'
    or 'amg'; the one used, by name, is ``result.solver``."""
    D, xD, owned = constrained_dofs(model, supports)
    check_supports(model, D)
    K = model.stiffness
    f = load_vector(model, loads)
    u = np.zeros(model.n_dofs)
    u[D] = xD
    I = np.setdiff1d(np.arange(model.n_dofs), D)
    K_II = K[I][:, I]
    rhs = f[I] - K[I][:, D] @ xD
    if not np.any(rhs):
        chosen = "none"
    else:
        chosen = linsolve.choose_solver(len(I), model.dim, solver)
        if chosen == "amg":
            u[I] = linsolve.solve_amg(K_II, rhs, rigid_body_dof_modes(model)[I])
            linsolve.check_solution(K_II, u[I], rhs, rtol=1e-6)
            chosen = "amg-cg"
        else:
            chosen = linsolve.direct_backend("spd")
            # K_II is symmetric positive definite once check_supports has passed: Cholesky
            u[I] = linsolve.solve_and_check(K_II, rhs, kind="spd", rtol=1e-6)

    residual = K @ u - f
    reactions = {g: np.array([residual[np.intersect1d(dofs, idx)].sum()
                              for idx in component_indices(model)])
                 for g, dofs in owned.items()}
    applied = np.array([f[idx].sum() for idx in component_indices(model)])

    sig = model.stress(u)
    vm_qp = von_mises(sig)
    nodal = nodal_average(model, sig)
    return StaticResult(
        model=model, u=u, displacement=vertex_displacement(model, u),
        von_mises_nodal=von_mises(nodal), von_mises_element_max=vm_qp.max(axis=1),
        reactions=reactions, applied_force=applied, strain_energy=0.5 * float(u @ (K @ u)),
        solver=chosen, info={"n_dofs": model.n_dofs, "n_constrained": len(D)},
        nodal_stress_full=np.moveaxis(nodal, 2, 0))
