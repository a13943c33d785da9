"""Linear static analysis: ``solve_static(model, supports, loads) -> StaticResult``."""
import numpy as np

from . import linsolve, memory
from .block_factor import BlockFactorization
from .budget import factor_plan
from .factor import factor
from .boundary import component_indices, constrained_dofs, load_vector
from .model import Model, von_mises
from .pmultigrid import solve_pmg
from .rigid_static import solve_static_faces
from .solver_choice import solver_choice
from .symmetric import symmetric_matvec
from .static_result import (StaticResult, UnderConstrainedError, body_parts,  # noqa: F401
                            check_supports, mean_field, nodal_average, rigid_body_dof_modes,
                            vertex_displacement)


def solve_static(model: Model, supports, loads, solver: str = "auto",
                 rigid_faces=()) -> StaticResult:
    """Solve K u = f with the displacement ``supports`` (Fixed, Prescribed) and ``loads``
    (Force, Traction, Pressure, PointForce, BodyForce, Gravity). ``solver``: 'auto', 'direct'
    or 'amg' (the iterative path: p-multigrid CG on quadratic elements, 'pmg-cg', AMG-CG on
    linear ones, 'amg-cg'); the one used, by name, is ``result.solver``. ``rigid_faces``: RigidFace (2-D),
    linearised; see :mod:`.rigid_static`."""
    if rigid_faces:
        return solve_static_faces(model, supports, loads, rigid_faces, solver)
    D, xD, owned = constrained_dofs(model, supports)
    check_supports(model, D)
    K = model.stiffness_upper  # symmetric: its upper triangle only
    f = load_vector(model, loads)
    u = np.zeros(model.n_dofs)
    u[D] = xD
    I = np.setdiff1d(np.arange(model.n_dofs), D)
    rhs = f[I] - symmetric_matvec(K, u)[I]  # f_I - K_ID u_D
    # K_II only as an operator on K, and its upper triangle for the factorization: no copy
    # of the full block
    K_II = linsolve.Restriction(K, I, upper=True)
    if not np.any(rhs):
        chosen, why = "none", "no load"
    else:
        chosen, why = solver_choice(
            len(I), model.dim, solver,
            lambda: linsolve.block_to_factorize(K, I, "spd", upper=True))
        if chosen == "amg":
            u[I], chosen, why = _iterative(model, K, I, K_II, rhs, why)
        else:
            try:
                u[I], chosen, why = _direct(K, I, K_II, rhs, why)
            except MemoryError as error:
                if solver != "auto":
                    raise
                u[I], chosen, why = _iterative(
                    model, K, I, K_II, rhs, f"{why}; but the direct factorization ran out "
                    f"of memory ({error}), so the iterative path")

    Ku = symmetric_matvec(K, u)
    residual = Ku - f
    reactions = {g: np.array([residual[np.intersect1d(dofs, idx)].sum()
                              for idx in component_indices(model)])
                 for g, dofs in owned.items()}
    applied = np.array([f[idx].sum() for idx in component_indices(model)])

    sig = model.stress(u)
    vm_qp = von_mises(sig)
    nodal = nodal_average(model, sig)
    memory.release_freed()  # the factorization's and the stress recovery's leftovers
    return StaticResult(
        model=model, u=u, displacement=vertex_displacement(model, u),
        von_mises_nodal=von_mises(nodal), von_mises_element_max=vm_qp.max(axis=1),
        reactions=reactions, applied_force=applied, strain_energy=0.5 * float(u @ Ku),
        solver=chosen, info={"n_dofs": model.n_dofs, "n_constrained": len(D),
                             "solver_choice": why},
        nodal_stress_full=np.moveaxis(nodal, 2, 0))


def _iterative(model, K, I, K_II, rhs, why: str) -> tuple:
    """(u_I, solver, why) by the iterative path: p-multigrid CG on quadratic elements (AMG on
    the P1 level, fem/pmultigrid.py), AMG-CG on linear ones."""
    if model.order > 1:
        u_I, iterative = solve_pmg(model, K, I, rhs)
        linsolve.check_solution(K_II, u_I, rhs, rtol=1e-6)
        return u_I, "pmg-cg", f"{why}; {iterative['iterations']} CG iterations"
    with factor(linsolve.block_to_factorize(K, I, "general", upper=True), "spd",
                "amg-cg", near_null_space=rigid_body_dof_modes(model)[I]) as F:
        u_I = F.solve(rhs)
    linsolve.check_solution(K_II, u_I, rhs, rtol=1e-6)
    return u_I, "amg-cg", why


def _direct(K, I, K_II, rhs, why: str) -> tuple:
    """(u_I, backend, why) by the direct factorization: K_II is symmetric positive definite
    once check_supports has passed (Cholesky, on K's own arrays: no copy of the block)."""
    with BlockFactorization(K, I, "spd") as F:
        u_I = linsolve.refine_and_check(K_II, rhs, F.solve, rtol=1e-6)
        if F.backend == "mkl-pardiso-ooc" and why == "asked for":
            why = f"asked for; {factor_plan(*F.memory)[1]}"
        return u_I, F.backend, why
