"""Geometrically nonlinear static analysis: total Lagrangian, St. Venant-Kirchhoff material.

    result = solve_nonlinear(model, [Fixed("fixed")], [Force("tip", (0.0, -50.0))], steps=10)
    result.path("tip")                  # (n_steps + 1, dim) mean tip displacement, m

Green-Lagrange strain E = (F^T F - I) / 2 with F = I + grad u; second Piola-Kirchhoff stress
S = lambda tr(E) I + 2 mu E (plane stress through the model's lambda*); internal force
f_int(v) = t int (F S) : grad v dX; consistent tangent
K(du, v) = t int [(grad du S) : grad v + (F dS(du)) : grad v] dX, dS = C : sym(F^T grad du).
All loads, prescribed displacements and rigid-face motions are dead and scale with the
load factor, stepped from 0 to 1 by Newton's method, halving a step that fails, or followed
by arc-length continuation; preloads (:mod:`.preload`) are applied first and then held.
"""
import math

import numpy as np

from . import linsolve
from .factor import SingularStiffness, factor
from .boundary import component_indices, constrained_dofs, load_vector
from .hyperelastic import (STRAIN_LIMIT, Assembler, StepFailed, cauchy_stress,  # noqa: F401
                           deformation, final_stress, green_lagrange, max_strain, svk_stress,
                           tangent_modulus)
from .model import Model
from .pressure import FollowerPressure
from .preload import PreloadedSpace, preload_faces, split_preloads
from .rigid_face import ReducedSpace
from .rigid_static import check_held
from .solver_choice import choose_solver
from .arclength import limit_points, trace
from .newton import (NonConvergenceError, newton_step, solve_tangent,  # noqa: F401
                     check_step_arguments)
from .nonlinear_result import NonlinearResult
from .stability import count_negative_eigenvalues
from .stepping import march
from .static import rigid_body_dof_modes


class _Problem:
    """Residual and tangent in the reduced unknowns z at a load factor: ``loads`` scaled by
    it, the nodal ``preloads`` (and the space's face preloads) held at full value."""

    def __init__(self, model, space, owned, loads, solver, assembler, preloads=()):
        self.model, self.space, self.owned, self.assembler = model, space, owned, assembler
        self.f_ext, self.follower = load_vector(model, loads), FollowerPressure(model, loads)
        self.f_pre = load_vector(model, preloads)
        self.pre_follower = FollowerPressure(model, preloads)
        self.solver = choose_solver(space.n, model.dim, solver)
        follower = self.follower.active or self.pre_follower.active
        if self.solver == "amg" and (space.faces or follower):
            raise ValueError(f"solver = {solver!r} with rigid faces or follower pressure: AMG is "
                             "not set up for them; use solver='direct'")
        self._follower_kind = "general" if follower else "symmetric"

    @property
    def matrix_kind(self) -> str:
        """The tangent's factorization: 'general' with follower pressure or a 3-D face's dead
        moment (a non-symmetric load stiffness), else 'symmetric'."""
        return self._follower_kind if self.space.symmetric else "general"

    def _load_stiffness(self, u, lam):
        """The follower loads' stiffness and the model's added linear stiffness (N/m)."""
        return (lam * self.follower.stiffness(u) + self.pre_follower.stiffness(u)
                + self.model.extra_stiffness)

    def evaluate(self, z, lam, tangent=True):
        """(u, r = f_int - lam f_ext - preloads (full), r_z, K_zz or None, reference force (N),
        T = du/dz, full tangent or None)."""
        space = self.space
        u = space.displacement(z, lam)
        F, S = self.assembler.state(u)
        r = (self.assembler.internal_force(F, S) + self.model.extra_stiffness @ u
             - lam * (self.f_ext + self.follower.force(u)) - self.f_pre
             - self.pre_follower.force(u))
        T = space.jacobian(z, lam)
        g = space.applied(lam, z)
        rz = T.T @ r - g
        held = np.ones(space.n_dofs, dtype=bool)
        held[space.I] = False
        reference = max(np.linalg.norm(lam * self.f_ext + self.f_pre), np.linalg.norm(g),
                        np.linalg.norm(r[held]))
        K = K_zz = None
        if tangent:
            K = self.assembler.tangent(F, S) + self._load_stiffness(u, lam)
            K_zz = (T.T @ K @ T + space.geometric_matrix(z, lam, r)).tocsr()
        return u, r, rz, K_zz, reference, T, K

    def reduced_tangent(self, z, lam, u, r, T):
        """K_zz = T^T K T + the rotation's geometric term (N/m)."""
        K = self.assembler.tangent(*self.assembler.state(u)) + self._load_stiffness(u, lam)
        return (T.T @ K @ T + self.space.geometric_matrix(z, lam, r)).tocsr()

    def solve(self, K, b):
        try:
            if self.solver == "amg" and self.model.order > 1:  # p-multigrid CG
                with factor(K, "spd", "pmg-cg", model=self.model, free=self.space.I) as F:
                    x = F.solve(b)
            elif self.solver == "amg":
                with factor(K, "spd", "amg-cg", near_null_space=self._near_null_space()) as F:
                    x = F.solve(b)
            else:
                x = solve_tangent(K, b, self.matrix_kind)
            linsolve.check_solution(K, x, b, "Newton step", rtol=1e-6)
        except (RuntimeError, SingularStiffness) as error:
            raise StepFailed(f"the tangent is singular ({error})", []) from None
        if not np.all(np.isfinite(x)):
            raise StepFailed("the tangent is singular (non-finite increment)", [])
        return x

    def _near_null_space(self):
        return rigid_body_dof_modes(self.model)[self.space.I]


def _stability(problem, z, u, r, lam):
    """Negative eigenvalues of the reduced tangent at a converged state (None: singular)."""
    K = problem.reduced_tangent(z, lam, u, r, problem.space.jacobian(z, lam))
    try:
        return count_negative_eigenvalues(K)
    except SingularStiffness:
        return None


def _record(problem, z, u, r, lam):
    space = problem.space
    comps = component_indices(problem.model)
    reactions = {g: np.array([r[np.intersect1d(dofs, idx)].sum() for idx in comps])
                 for g, dofs in problem.owned.items()}
    qs = space.coordinates(z, lam)
    faces = {fk.face.group: fk.generalised_force(r, q) for fk, q in zip(space.faces, qs)}
    motion = {fk.face.group: q for fk, q in zip(space.faces, qs)}
    return reactions, faces, motion


def _load_control(problem, steps, max_iterations, tol, min_step, on_step, z0) -> int:
    """Step the load factor 0 -> 1 from the converged ``z0`` at load factor 0 (see
    :func:`solve_nonlinear`; :func:`.stepping.march`); the last two converged steps
    extrapolate each step's start. Returns the number of step cuts."""
    path = {"z": z0, "z_previous": z0, "lam_previous": None}

    def advance(lam, dlam, cuts_here):
        z, guess = path["z"], None
        if path["lam_previous"] is not None and cuts_here == 0:
            guess = z + dlam / (lam - path["lam_previous"]) * (z - path["z_previous"])
        z_new, u, r, n_it, _ = newton_step(problem, z, lam, lam + dlam, max_iterations, tol, guess)
        path.update(z=z_new, z_previous=z, lam_previous=lam)
        return on_step(z_new, lam + dlam, u, r, n_it)

    def failed(lam, dlam, cuts, failure):
        return NonConvergenceError(
            f"no convergence beyond load factor {lam:.6g} (trying {lam + dlam:.6g}, step "
            f"{dlam:.3g} after {cuts} cuts): {failure.reason}; relative residuals "
            f"{', '.join(f'{h:.2e}' for h in failure.history) or 'none'}. Use more steps, "
            f"a smaller min_step (now {min_step:g}) or more max_iterations (now "
            f"{max_iterations}); if the residual grows, the structure may buckle or snap "
            "(a limit point), which load control cannot pass: use control='arc-length' or "
            "prescribe a displacement instead", lam, lam + dlam, len(failure.history),
            failure.history)

    return march(advance, steps, min_step, failed)


def _problems(model, supports, loads, rigid_faces, preloads, solver) -> tuple:
    """(preload-stage problem or None, problem of the scaled loads): the preload stage steps
    the preloads with the prescribed motions held at 0 (:mod:`.preload`)."""
    D, xD, owned = constrained_dofs(model, supports)
    space = ReducedSpace(model, D, xD, rigid_faces)
    check_held(model, space)
    assembler = Assembler(model)
    if not preloads:
        return None, _Problem(model, space, owned, loads, solver, assembler)
    nodal, face_loads = split_preloads(preloads, rigid_faces, model.dim)
    pre_space = ReducedSpace(model, D, np.zeros_like(xD), preload_faces(rigid_faces, face_loads))
    pre = _Problem(model, pre_space, owned, nodal, solver, assembler)
    held = PreloadedSpace(space, pre_space)
    return pre, _Problem(model, held, owned, loads, solver, assembler, preloads=nodal)


def _check_arguments(steps, max_iterations, tol, min_step, control, strain_limit, preload_steps):
    check_step_arguments(steps, max_iterations, tol, min_step)
    if control not in ("load", "arc-length"):
        raise ValueError(f"control = {control!r}; choose 'load' or 'arc-length'")
    if not (isinstance(strain_limit, (int, float)) and 0 < strain_limit < math.inf):
        raise ValueError(f"strain_limit = {strain_limit!r} must be a finite number > 0")
    if preload_steps is not None and not (isinstance(preload_steps, (int, np.integer))
                                          and not isinstance(preload_steps, bool)
                                          and preload_steps >= 1):
        raise ValueError(f"preload_steps = {preload_steps!r} must be an integer >= 1 or None")


def solve_nonlinear(model: Model, supports, loads, steps: int = 10, max_iterations: int = 25,
                    tol: float = 1e-8, min_step: float = 1e-4, rigid_faces=(),
                    solver: str = "direct", check_stability: bool | None = None,
                    strain_limit: float = STRAIN_LIMIT, control: str = "load",
                    max_steps: int | None = None, preloads=(),
                    preload_steps: int | None = None, stop_when=None) -> NonlinearResult:
    """Large-deflection static solve of ``model`` under ``supports`` (Fixed, Prescribed),
    ``loads`` (Force, Traction, PointForce, BodyForce, Gravity: dead; Pressure: follower) and
    ``rigid_faces`` (RigidFace, 2-D or 3-D), all scaled by a load factor stepped 0 -> 1 in
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
    ``max_steps`` steps, default 20 ``steps``). ``preloads`` (:mod:`.preload`): loads applied
    first, by load control in ``preload_steps`` increments (default ``steps``), then held
    at full value while the scaled loads follow ``control``; result.preload_end is the step
    that ends the preload stage. ``stop_when(load_factor, u, face_motion) -> bool`` (u the
    DOF vector (m), face_motion {group: (c_x, c_y, theta)}), called at each converged step of
    the scaled loads, ends the solve there when true (result.info['stopped']): the end of a
    path that does not come back to load factor 1, e.g. past a limit point."""
    _check_arguments(steps, max_iterations, tol, min_step, control, strain_limit, preload_steps)
    pre, problem = _problems(model, supports, loads, rigid_faces, preloads, solver)
    if check_stability is None:
        check_stability = problem.solver == "direct"
    if stop_when is not None and not callable(stop_when):
        raise ValueError(f"stop_when = {stop_when!r} must be a function (load_factor, u, "
                         "face_motion) -> bool or None")
    steps_out = _Steps(model, check_stability, strain_limit, stop_when)
    z, cuts_pre = np.zeros(problem.space.n), 0
    if pre is not None:
        cuts_pre = _load_control(pre, preload_steps or steps, max_iterations, tol, min_step,
                                 steps_out.recorder(pre, preload=True), z)
        z = steps_out.z
    on_step = steps_out.recorder(problem)
    if control == "arc-length":
        cuts = trace(problem, steps, max_iterations, tol, min_step,
                     20 * steps if max_steps is None else max_steps, on_step, z)
    else:
        cuts = _load_control(problem, steps, max_iterations, tol, min_step, on_step, z)
    return steps_out.result(problem, {"step_cuts": cuts, "preload_step_cuts": cuts_pre,
                                      "control": control, "stopped": steps_out.stopped})


class _Steps:
    """The converged steps of both stages, and the result they make."""

    def __init__(self, model, check_stability, strain_limit, stop_when=None):
        self.model, self.check, self.strain_limit = model, check_stability, strain_limit
        self.stop_when, self.stopped = stop_when, False
        self.lams, self.pre, self.us, self.its = [0.0], [0.0], [np.zeros(model.n_dofs)], [0]
        self.records = [({}, {}, {})]
        self.negative, self.strains = [0 if check_stability else None], [0.0]
        self.preload_end, self.z = 0, None

    def recorder(self, problem, preload=False):
        """on_step(z, lam, u, r, iterations) -> stop of a stage: in the preload stage lam is
        the preloads' factor and the scaled loads' factor is 0."""
        def on_step(z, lam, u, r, n_it):
            self.lams.append(0.0 if preload else lam)
            self.pre.append(lam if preload else (1.0 if self.preload_end else 0.0))
            self.us.append(u)
            self.its.append(n_it)
            self.records.append(_record(problem, z, u, r, lam))
            self.negative.append(_stability(problem, z, u, r, lam) if self.check else None)
            self.strains.append(max_strain(self.model, u))
            self.z = z
            if preload:
                self.preload_end = len(self.lams) - 1
            elif self.stop_when is not None:
                self.stopped = bool(self.stop_when(lam, u, self.records[-1][2]))
            return self.stopped
        return on_step

    def result(self, problem, info) -> NonlinearResult:
        z0 = np.zeros(problem.space.n)
        self.records[0] = _record(problem, z0, self.us[0], np.zeros(self.model.n_dofs), 0.0)
        lams, start = np.array(self.lams), self.preload_end
        limits = [(k + start, lam, kind) for k, lam, kind in limit_points(lams[start:])]
        vm_nodal, vm_element = final_stress(self.model, self.us[-1])
        return NonlinearResult(
            model=self.model, load_factors=lams, u=self.us,
            reactions=[rec[0] for rec in self.records],
            face_reactions=[rec[1] for rec in self.records],
            face_motion=[rec[2] for rec in self.records], iterations=self.its,
            von_mises_nodal=vm_nodal, von_mises_element_max=vm_element, applied=problem.f_ext,
            info={"n_dofs": self.model.n_dofs, "n_unknowns": problem.space.n,
                  "solver": problem.solver, "limit_points": limits, **info},
            negative_eigenvalues=self.negative, max_strain=np.array(self.strains),
            strain_limit=self.strain_limit, preload_factors=np.array(self.pre),
            preload_end=start, preloaded=problem.f_pre)
