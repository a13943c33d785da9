"""Geometrically nonlinear static analysis: total Lagrangian, St. Venant-Kirchhoff material.

    result = solve_nonlinear(model, [Fixed("fixed")], [Force("tip", (0.0, -50.0))], steps=10)
    result.path("tip")                  # (n_steps + 1, dim) mean tip displacement, m

Green-Lagrange strain E = (F^T F - I) / 2 with F = I + grad u; second Piola-Kirchhoff stress
S = lambda tr(E) I + 2 mu E (plane stress through the model's lambda*); internal force
f_int(v) = t int (F S) : grad v dX; consistent tangent
K(du, v) = t int [(grad du S) : grad v + (F dS(du)) : grad v] dX, dS = C : sym(F^T grad du).
All loads, prescribed displacements and rigid-face motions are dead and scale with the
load factor, stepped from 0 to 1 by Newton's method, halving a step that fails.
"""
from dataclasses import dataclass, field
import math

import numpy as np
import scipy.sparse as sp

from . import linsolve
from .boundary import component_indices, constrained_dofs, group_dofs, load_vector
from .hyperelastic import (STRAIN_LIMIT, Assembler, _StepFailed, cauchy_stress,  # noqa: F401
                           deformation, final_stress, green_lagrange, max_strain, svk_stress,
                           tangent_modulus)
from .model import Model
from .rigid_face import ReducedSpace
from .rigid_static import check_held
from .arclength import limit_points
from .stability import count_negative_eigenvalues
from .static import mean_field, rigid_body_dof_modes


class NonConvergenceError(ValueError):
    """Newton's method failed at the smallest allowed load step. Attributes: load_factor
    (last converged), attempted (the load factor it failed to reach), iterations,
    residual_history (relative residuals of the last attempt)."""

    def __init__(self, message, load_factor, attempted, iterations, residual_history):
        super().__init__(message)
        self.load_factor = load_factor
        self.attempted = attempted
        self.iterations = iterations
        self.residual_history = residual_history


@dataclass(frozen=True, eq=False)
class NonlinearResult:
    """Converged steps of a nonlinear solve; index 0 is the unloaded state.

    load_factors : (n,) ; u : list of DOF vectors (m) ; reactions : per step {group: force
    (N)} of every supported group ; face_reactions : per step {group: (F_x, F_y, M)} (N, N,
    N m about the current centroid) of every rigid face, equal to the applied load on a free
    coordinate ; face_motion : per step {group:
    (c_x, c_y, theta)} (m, m, rad) ; iterations : Newton iterations per step ;
    von_mises_nodal / von_mises_element_max : final Cauchy von Mises stress (Pa), nodal from
    the L2 projection of the stress components onto linear fields, and the maximum over each
    element's quadrature points ; applied : full-load vector f_ext (N) ; negative_eigenvalues :
    per step, the number of negative eigenvalues of the reduced tangent stiffness (None where
    it is singular, a critical state; None everywhere if not checked) ; max_strain : per step
    the largest absolute principal Green-Lagrange strain (-) ; strain_limit : the validity
    limit of St. Venant-Kirchhoff (see :data:`.hyperelastic.STRAIN_LIMIT`)."""

    model: Model
    load_factors: np.ndarray
    u: list
    reactions: list
    face_reactions: list
    face_motion: list
    iterations: list
    von_mises_nodal: np.ndarray
    von_mises_element_max: np.ndarray
    applied: np.ndarray
    info: dict = field(default_factory=dict)
    negative_eigenvalues: list = field(default_factory=list)
    max_strain: np.ndarray = field(default_factory=lambda: np.zeros(0))
    strain_limit: float = STRAIN_LIMIT

    @property
    def stable(self) -> np.ndarray:
        """(n,) bool per step: the reduced tangent stiffness is positive definite (a strict
        minimum of the potential energy); False at a critical or unstable state, and where
        not checked (negative_eigenvalues None)."""
        return np.array([n == 0 for n in self.negative_eigenvalues], dtype=bool)

    @property
    def strain_valid(self) -> np.ndarray:
        """(n,) bool per step: every Green-Lagrange principal strain within strain_limit."""
        return np.asarray(self.max_strain) <= self.strain_limit

    def stress_at_step(self, step: int) -> tuple[np.ndarray, np.ndarray]:
        """(nodal (n_vertices,), element max (n_elements,)) Cauchy von Mises stress (Pa) at
        ``step`` (as von_mises_nodal / von_mises_element_max at the last step)."""
        if not (isinstance(step, (int, np.integer)) and -len(self.u) <= step < len(self.u)):
            raise ValueError(f"step = {step!r} must index one of the {len(self.u)} steps")
        return final_stress(self.model, self.u[step])

    def mean_displacement(self, group: str, step: int = -1) -> np.ndarray:
        """Measure-averaged displacement (m) of a group at ``step``."""
        return mean_field(self.model, self.u[step], group)

    def path(self, group: str) -> np.ndarray:
        """(n_steps + 1, dim) mean displacement (m) of ``group`` over the steps."""
        return np.array([mean_field(self.model, u, group) for u in self.u])

    def force_displacement(self, group: str) -> tuple[np.ndarray, np.ndarray]:
        """(displacement (n, dim) m, force (n, dim) N) of ``group``: its reaction if it is
        supported, its face force if it is a rigid face, else the applied load on its DOFs."""
        if group in self.reactions[0]:
            force = np.array([r[group] for r in self.reactions])
        elif group in self.face_reactions[0]:
            force = np.array([r[group][:2] for r in self.face_reactions])
        else:
            total = np.array([self.applied[d].sum() for d in group_dofs(self.model, group).values()])
            force = np.outer(self.load_factors, total)
        return self.path(group), force

    @property
    def max_von_mises(self) -> float:
        """Largest nodal von Mises stress (Pa) at the final step."""
        return float(self.von_mises_nodal.max())

    @property
    def max_von_mises_element(self) -> float:
        """Largest von Mises stress (Pa) at any quadrature point at the final step."""
        return float(self.von_mises_element_max.max())

    @property
    def max_von_mises_location(self) -> np.ndarray:
        """Reference coordinates (m) of the vertex with the largest nodal von Mises stress."""
        return self.model.mesh.mesh.p[:, int(np.argmax(self.von_mises_nodal))]


def _check_arguments(steps, max_iterations, tol, min_step):
    if not (isinstance(steps, int) and steps >= 1):
        raise ValueError(f"steps = {steps!r} must be an integer >= 1")
    if not (isinstance(max_iterations, int) and max_iterations >= 1):
        raise ValueError(f"max_iterations = {max_iterations!r} must be an integer >= 1")
    if not (0 < tol < 1):
        raise ValueError(f"tol = {tol!r} must lie in (0, 1)")
    if not (0 < min_step <= 1):
        raise ValueError(f"min_step = {min_step!r} must lie in (0, 1]")


class _Problem:
    """Residual and tangent in the reduced unknowns z at a load factor."""

    def __init__(self, model, supports, loads, rigid_faces, solver):
        D, xD, self.owned = constrained_dofs(model, supports)
        self.space = ReducedSpace(model, D, xD, rigid_faces)
        check_held(model, self.space)
        self.model = model
        self.assembler = Assembler(model)
        self.f_ext = load_vector(model, loads)
        self.solver = linsolve.choose_solver(self.space.n, model.dim, solver)
        if self.solver == "amg" and rigid_faces:
            raise ValueError(f"solver = {solver!r} with rigid faces: AMG is not set up for face "
                             "coordinates; use solver='direct'")

    def evaluate(self, z, lam, tangent=True):
        """(u, r = f_int - lam f_ext (full), r_z, K_zz or None, reference force (N), T = du/dz,
        full tangent or None)."""
        space = self.space
        u = space.displacement(z, lam)
        F, S = self.assembler.state(u)
        r = self.assembler.internal_force(F, S) - lam * self.f_ext
        T = space.jacobian(z, lam)
        g = space.applied(lam)
        rz = T.T @ r - g
        held = np.ones(space.n_dofs, dtype=bool)
        held[space.I] = False
        reference = max(np.linalg.norm(lam * self.f_ext), np.linalg.norm(g), np.linalg.norm(r[held]))
        K = K_zz = None
        if tangent:
            K = self.assembler.tangent(F, S)
            K_zz = (T.T @ K @ T + sp.diags(space.geometric_term(z, lam, r))).tocsr()
        return u, r, rz, K_zz, reference, T, K

    def reduced_tangent(self, z, lam, u, r, T):
        """K_zz = T^T K T + the rotation's geometric term (N/m)."""
        K = self.assembler.tangent(*self.assembler.state(u))
        return (T.T @ K @ T + sp.diags(self.space.geometric_term(z, lam, r))).tocsr()

    def solve(self, K, b):
        try:
            if self.solver == "amg":
                x = linsolve.solve_amg(K, b, self._near_null_space())
            else:
                x = _solve_direct(K, b)
            linsolve.check_solution(K, x, b, "Newton step", rtol=1e-6)
        except (RuntimeError, linsolve.SingularSystemError) as error:
            raise _StepFailed(f"the tangent is singular ({error})", []) from None
        if not np.all(np.isfinite(x)):
            raise _StepFailed("the tangent is singular (non-finite increment)", [])
        return x

    def _near_null_space(self):
        return rigid_body_dof_modes(self.model)[self.space.I]


def _solve_direct(A, b) -> np.ndarray:
    """Direct solve of a Newton step: the tangent is symmetric but need not be positive
    definite (a compressed or buckling flexure), so the symmetric indefinite factorization."""
    return linsolve.solve_direct(A, np.asarray(b, dtype=float), kind="symmetric")


def _newton(problem, z, lam_old, lam, max_iterations, tol, guess=None):
    """Converged z at load factor ``lam`` from the converged ``z`` at ``lam_old``. Starts
    from ``guess`` (extrapolated from earlier steps) if given, else from the tangent
    predictor: the increment of loads and prescribed motions applied through the tangent
    at the old state (counted as the first iteration)."""
    space = problem.space
    history = []
    try:
        if guess is None:
            u_old, r, _, K, _, T, full_K = problem.evaluate(z, lam_old)
            jump = space.displacement(z, lam) - u_old
            rz = T.T @ (r - (lam - lam_old) * problem.f_ext + full_K @ jump) - space.applied(lam)
            dz = problem.solve(K, -rz)
            first = 2
        else:
            dz, first = guess - z, 1
        z = z + dz
        for iteration in range(first, max_iterations + 2):
            u, r, rz, _, reference, T, _ = problem.evaluate(z, lam, tangent=False)
            norm = float(np.linalg.norm(rz))
            history.append(norm / reference if reference > 0 else norm)
            if not math.isfinite(norm) or (len(history) > 1 and norm > 1e8 * max(reference, 1e-300)):
                raise _StepFailed("the residual diverged", history)
            step_small = np.linalg.norm(dz) <= math.sqrt(tol) * max(np.linalg.norm(u), 1e-300)
            if norm <= tol * reference and step_small:
                return z, u, r, iteration - 1, history
            if iteration == max_iterations + 1:
                break
            dz = problem.solve(problem.reduced_tangent(z, lam, u, r, T), -rz)
            z = z + dz
    except _StepFailed as failure:
        raise _StepFailed(failure.reason, history + failure.history) from None
    raise _StepFailed(f"no convergence in {max_iterations} iterations", history)


def _stability(problem, z, u, r, lam):
    """Negative eigenvalues of the reduced tangent at a converged state (None: singular)."""
    K = problem.reduced_tangent(z, lam, u, r, problem.space.jacobian(z, lam))
    try:
        return count_negative_eigenvalues(K)
    except linsolve.SingularSystemError:
        return None


def _record(problem, z, u, r, lam):
    space = problem.space
    comps = component_indices(problem.model)
    reactions = {g: np.array([r[np.intersect1d(dofs, idx)].sum() for idx in comps])
                 for g, dofs in problem.owned.items()}
    qs = space.coordinates(z, lam)
    faces = {fk.face.group: fk.generalised_force(r, q[2]) for fk, q in zip(space.faces, qs)}
    motion = {fk.face.group: q for fk, q in zip(space.faces, qs)}
    return reactions, faces, motion


def _load_control(problem, steps, max_iterations, tol, min_step, lams, on_step) -> int:
    """Step the load factor 0 -> 1 (see :func:`solve_nonlinear`); ``lams`` (the converged
    load factors so far, appended to by ``on_step``) extrapolates each step's start.
    Returns the number of step cuts."""
    nominal = 1.0 / steps
    dlam, lam, cuts, good, cuts_here = nominal, 0.0, 0, 0, 0
    z = z_previous = np.zeros(problem.space.n)
    while lam < 1.0 - 1e-12:
        dlam = min(dlam, 1.0 - lam)
        try:
            guess = None
            if len(lams) > 1 and cuts_here == 0:
                guess = z + dlam / (lams[-1] - lams[-2]) * (z - z_previous)
            z_new, u, r, n_it, history = _newton(problem, z, lam, lam + dlam, max_iterations, tol,
                                                 guess)
        except _StepFailed as failure:
            if dlam / 2 < min_step * (1 - 1e-9):
                raise NonConvergenceError(
                    f"no convergence beyond load factor {lam:.6g} (trying {lam + dlam:.6g}, step "
                    f"{dlam:.3g} after {cuts} cuts): {failure.reason}; relative residuals "
                    f"{', '.join(f'{h:.2e}' for h in failure.history) or 'none'}. Use more steps, "
                    f"a smaller min_step (now {min_step:g}) or more max_iterations (now "
                    f"{max_iterations}); if the residual grows, the structure may buckle or snap "
                    "(a limit point), which load control cannot pass: use control='arc-length' or "
                    "prescribe a displacement instead", lam, lam + dlam, len(failure.history),
                    failure.history) from None
            dlam, cuts, good, cuts_here = dlam / 2, cuts + 1, 0, cuts_here + 1
            continue
        lam, cuts_here = lam + dlam, 0
        z_previous, z = z, z_new
        on_step(z, lam, u, r, n_it)
        good += 1
        if good >= 2 and dlam < nominal:
            dlam, good = min(2 * dlam, nominal), 0
    return cuts


def solve_nonlinear(model: Model, supports, loads, steps: int = 10, max_iterations: int = 25,
                    tol: float = 1e-8, min_step: float = 1e-4, rigid_faces=(),
                    solver: str = "direct", check_stability: bool | None = None,
                    strain_limit: float = STRAIN_LIMIT, control: str = "load",
                    max_steps: int | None = None) -> NonlinearResult:
    """Large-deflection static solve of ``model`` under ``supports`` (Fixed, Prescribed),
    ``loads`` (Force, Traction, PointForce, BodyForce, Gravity; dead loads, N) and
    ``rigid_faces`` (RigidFace, 2-D), all scaled by a load factor stepped 0 -> 1 in
    ``steps`` equal increments. A step whose Newton iterations fail (``max_iterations``
    reached, residual diverging, an element inverted, a singular tangent) is halved, down
    to ``min_step`` (a load-factor increment); below that NonConvergenceError is raised.
    Converged when |r| <= tol * reference force (applied loads and reactions, N) and the
    last increment |dz| <= sqrt(tol) |u| (Newton converges quadratically, so the error
    left is about |dz|^2). ``solver``: 'direct', 'amg' (symmetric positive tangent only) or
    'auto'. ``check_stability``: count the negative eigenvalues of the tangent at each
    converged step (one extra sparse LDL^T factorization per step; result.stable); default
    on with the direct solver, off with AMG (a model too large to factorize). ``strain_limit``: the
    Green-Lagrange strain (-) beyond which result.strain_valid flags a step. ``control``:
    'load' (the load factor stepped as above) or 'arc-length' (:mod:`.arclength`: the path is
    followed through limit points, which result.info['limit_points'] lists; the first arc
    length is that of a load step 1 / ``steps`` along the initial tangent; at most
    ``max_steps`` steps, default 20 ``steps``)."""
    _check_arguments(steps, max_iterations, tol, min_step)
    if control not in ("load", "arc-length"):
        raise ValueError(f"control = {control!r}; choose 'load' or 'arc-length'")
    if not (isinstance(strain_limit, (int, float)) and 0 < strain_limit < math.inf):
        raise ValueError(f"strain_limit = {strain_limit!r} must be a finite number > 0")
    problem = _Problem(model, supports, loads, rigid_faces, solver)
    if check_stability is None:
        check_stability = problem.solver == "direct"
    z = np.zeros(problem.space.n)
    u0 = np.zeros(model.n_dofs)
    r0 = np.zeros(model.n_dofs)
    lams, us, its = [0.0], [u0], [0]
    records = [_record(problem, z, u0, r0, 0.0)]
    negative, strains = [0 if check_stability else None], [0.0]

    def on_step(z, lam, u, r, n_it):
        lams.append(lam)
        us.append(u)
        its.append(n_it)
        records.append(_record(problem, z, u, r, lam))
        negative.append(_stability(problem, z, u, r, lam) if check_stability else None)
        strains.append(max_strain(model, u))

    if control == "arc-length":
        from .arclength import trace
        cuts = trace(problem, steps, max_iterations, tol, min_step,
                     20 * steps if max_steps is None else max_steps, on_step)
    else:
        cuts = _load_control(problem, steps, max_iterations, tol, min_step, lams, on_step)
    vm_nodal, vm_element = final_stress(model, us[-1])
    return NonlinearResult(
        model=model, load_factors=np.array(lams), u=us, reactions=[rec[0] for rec in records],
        face_reactions=[rec[1] for rec in records], face_motion=[rec[2] for rec in records],
        iterations=its, von_mises_nodal=vm_nodal, von_mises_element_max=vm_element,
        applied=problem.f_ext,
        info={"n_dofs": model.n_dofs, "n_unknowns": problem.space.n, "step_cuts": cuts,
              "solver": problem.solver, "control": control,
              "limit_points": limit_points(lams)},
        negative_eigenvalues=negative, max_strain=np.array(strains), strain_limit=strain_limit)
