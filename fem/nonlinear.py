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
import skfem
from skfem.helpers import ddot, eye, grad, mul, transpose, trace

from . import linsolve
from .boundary import component_indices, constrained_dofs, follower_pressure, group_dofs, load_vector
from .model import Model, PlaneStrain, von_mises
from .rigid_face import ReducedSpace
from .static import (UnderConstrainedError, check_supports, mean_field, nodal_average,
                                rigid_body_dof_modes)


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


class _StepFailed(Exception):
    def __init__(self, reason, history):
        super().__init__(reason)
        self.reason, self.history = reason, history


def green_lagrange(F: np.ndarray) -> np.ndarray:
    """E = (F^T F - I) / 2 of a (dim, dim, ...) deformation gradient."""
    return 0.5 * (mul(transpose(F), F) - eye(np.ones_like(F[0, 0]), F.shape[0]))


def svk_stress(E: np.ndarray, lam: float, mu: float) -> np.ndarray:
    """Second Piola-Kirchhoff stress (Pa) S = lam tr(E) I + 2 mu E."""
    return lam * trace(E) * eye(np.ones_like(E[0, 0]), E.shape[0]) + 2.0 * mu * E


def cauchy_stress(F: np.ndarray, S: np.ndarray) -> np.ndarray:
    """sigma = F S F^T / det F (Pa)."""
    return mul(mul(F, S), transpose(F)) / np.linalg.det(np.moveaxis(F, (0, 1), (-2, -1)))


def deformation(basis, u: np.ndarray):
    """F = I + grad u at the quadrature points of ``basis``, (dim, dim, n_elements, n_points)."""
    gu = basis.interpolate(u).grad
    return gu + eye(np.ones_like(gu[0, 0]), gu.shape[0])


@skfem.LinearForm
def _internal_force(v, w):
    return w.t * ddot(mul(w.F, w.S), grad(v))


@skfem.BilinearForm
def _tangent(du, v, w):
    return np.einsum("ij...,ijkl...,kl...->...", grad(v), np.asarray(w.A), grad(du))


def tangent_modulus(F: np.ndarray, S: np.ndarray, lam: float, mu: float) -> np.ndarray:
    """A_iJkL = delta_ik S_JL + F_iM C_MJNL F_kN (Pa), (dim,) * 4 + (n_elements, n_points):
    dP = A : grad du, the consistent tangent of P = F S for St. Venant-Kirchhoff."""
    d = F.shape[0]
    I = np.eye(d)
    A = np.einsum("ik,jl...->ijkl...", I, S)
    A += lam * np.einsum("ij...,kl...->ijkl...", F, F)
    A += mu * (np.einsum("il...,kj...->ijkl...", F, F) + np.einsum("ik...,jl...->ijkl...",
                                                                    np.einsum("im...,km...->ik...", F, F),
                                                                    I[..., None, None] + 0 * S))
    return A


class Assembler:
    """Internal force (N) and tangent (N/m) of a model, on the model's stiffness quadrature
    (exact for the linear part, so the tangent at u = 0 is ``model.stiffness``). The sparse
    pattern is computed once and reused."""

    def __init__(self, model: Model):
        self.basis = model.stiffness_basis
        self.lam, self.mu = model.lame
        self.t = model.thickness
        self._pattern = None

    def state(self, u: np.ndarray):
        """(F, S) at the quadrature points; raises _StepFailed where det F <= 0."""
        F = deformation(self.basis, u)
        J = np.linalg.det(np.moveaxis(F, (0, 1), (-2, -1)))
        if not np.all(np.isfinite(J)) or J.min() <= 0:
            raise _StepFailed(f"an element turned inside out (min det F = {J.min():.2g})", [])
        return F, svk_stress(green_lagrange(F), self.lam, self.mu)

    def internal_force(self, F, S) -> np.ndarray:
        return _internal_force.assemble(self.basis, F=F, S=S, t=self.t)

    def tangent(self, F, S) -> sp.csr_matrix:
        A = self.t * tangent_modulus(F, S, self.lam, self.mu)
        coo = _tangent.coo_data(self.basis, A=A)
        if self._pattern is None:
            n = coo.shape[0]
            keys = coo.indices[0].astype(np.int64) * n + coo.indices[1]
            unique, where = np.unique(keys, return_inverse=True)
            rows, cols = np.divmod(unique, n)
            indptr = np.searchsorted(rows, np.arange(n + 1))
            self._pattern = (where, cols.astype(np.int32), indptr.astype(np.int32), len(unique), n)
        where, cols, indptr, nnz, n = self._pattern
        data = np.bincount(where, weights=coo.data, minlength=nnz)
        return sp.csr_matrix((data, cols, indptr), shape=(n, n))


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
    element's quadrature points ; applied : full-load vector f_ext (N)."""

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


def final_stress(model: Model, u: np.ndarray):
    """(nodal von Mises (n_vertices,), element max (n_elements,)) of the Cauchy stress (Pa).
    2-D: sigma_zz = 0 in plane stress, S_zz / det F in plane strain; the thickness change
    is neglected in det F (strains small beside rotations)."""
    basis = model.basis
    lam, mu = model.lame
    F = deformation(basis, u)
    E = green_lagrange(F)
    sig = cauchy_stress(F, svk_stress(E, lam, mu))
    if model.dim == 2:
        full = np.zeros((3, 3) + sig.shape[2:])
        full[:2, :2] = sig
        if isinstance(model.formulation, PlaneStrain):
            full[2, 2] = lam * trace(E) / np.linalg.det(np.moveaxis(F, (0, 1), (-2, -1)))
        sig = full
    return von_mises(nodal_average(model, sig)), von_mises(sig).max(axis=1)


def _check_arguments(steps, max_iterations, tol, min_step):
    if not (isinstance(steps, int) and steps >= 1):
        raise ValueError(f"steps = {steps!r} must be an integer >= 1")
    if not (isinstance(max_iterations, int) and max_iterations >= 1):
        raise ValueError(f"max_iterations = {max_iterations!r} must be an integer >= 1")
    if not (0 < tol < 1):
        raise ValueError(f"tol = {tol!r} must lie in (0, 1)")
    if not (0 < min_step <= 1):
        raise ValueError(f"min_step = {min_step!r} must lie in (0, 1]")


def _check_held(model, space):
    """Raise UnderConstrainedError if supports and rigid faces leave a rigid-body motion."""
    if not space.faces:
        check_supports(model, space.D)
        return
    rows = space.held_mode_rows(model)
    s = np.linalg.svd(rows, compute_uv=False) if len(rows) else np.zeros(0)
    free = 3 - int(np.sum(s > 1e-9 * max(np.abs(rows).max(initial=0.0), 1e-300)))
    if free:
        raise UnderConstrainedError(f"the supports and rigid faces leave {free} of 3 rigid-body "
                                    "modes free; prescribe more coordinates or add supports")


class _Problem:
    """Residual and tangent in the reduced unknowns z at a load factor."""

    def __init__(self, model, supports, loads, rigid_faces, solver):
        D, xD, self.owned = constrained_dofs(model, supports)
        self.space = ReducedSpace(model, D, xD, rigid_faces)
        _check_held(model, self.space)
        self.model = model
        self.assembler = Assembler(model)
        self.f_ext, self.follower = load_vector(model, loads), follower_pressure(model, loads)
        self.solver = linsolve.choose_solver(self.space.n, model.dim, solver)
        if self.solver == "amg" and (rigid_faces or self.follower.active):
            raise ValueError(f"solver = {solver!r} with rigid faces or follower pressure: AMG is "
                             "not set up for them; use solver='direct'")

    def evaluate(self, z, lam, tangent=True):
        """(u, r = f_int - lam f_ext (full), r_z, K_zz or None, reference force (N), T = du/dz,
        full tangent or None)."""
        space = self.space
        u = space.displacement(z, lam)
        F, S = self.assembler.state(u)
        r = self.assembler.internal_force(F, S) - lam * (self.f_ext + self.follower.force(u))
        T = space.jacobian(z, lam)
        g = space.applied(lam)
        rz = T.T @ r - g
        held = np.ones(space.n_dofs, dtype=bool)
        held[space.I] = False
        reference = max(np.linalg.norm(lam * self.f_ext), np.linalg.norm(g), np.linalg.norm(r[held]))
        K = K_zz = None
        if tangent:
            K = self.assembler.tangent(F, S) + lam * self.follower.stiffness(u)
            K_zz = (T.T @ K @ T + sp.diags(space.geometric_term(z, lam, r))).tocsr()
        return u, r, rz, K_zz, reference, T, K

    def reduced_tangent(self, z, lam, u, r, T):
        """K_zz = T^T K T + the rotation's geometric term (N/m)."""
        K = self.assembler.tangent(*self.assembler.state(u)) + lam * self.follower.stiffness(u)
        return (T.T @ K @ T + sp.diags(self.space.geometric_term(z, lam, r))).tocsr()

    def solve(self, K, b):
        try:
            if self.solver == "amg":
                x = linsolve.solve_amg(K, b, self._near_null_space())
            else:
                x = _solve_direct(K, b, self.follower.matrix_kind)
            linsolve.check_solution(K, x, b, "Newton step", rtol=1e-6)
        except (RuntimeError, linsolve.SingularSystemError) as error:
            raise _StepFailed(f"the tangent is singular ({error})", []) from None
        if not np.all(np.isfinite(x)):
            raise _StepFailed("the tangent is singular (non-finite increment)", [])
        return x

    def _near_null_space(self):
        return rigid_body_dof_modes(self.model)[self.space.I]


def _solve_direct(A, b, kind="symmetric") -> np.ndarray:
    """Direct solve of a Newton step: the tangent is symmetric but need not be positive
    definite (a compressed or buckling flexure); ``kind`` 'general' for follower pressure."""
    return linsolve.solve_direct(A, np.asarray(b, dtype=float), kind=kind)


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


def _record(problem, z, u, r, lam):
    space = problem.space
    comps = component_indices(problem.model)
    reactions = {g: np.array([r[np.intersect1d(dofs, idx)].sum() for idx in comps])
                 for g, dofs in problem.owned.items()}
    qs = space.coordinates(z, lam)
    faces = {fk.face.group: fk.generalised_force(r, q[2]) for fk, q in zip(space.faces, qs)}
    motion = {fk.face.group: q for fk, q in zip(space.faces, qs)}
    return reactions, faces, motion


def solve_nonlinear(model: Model, supports, loads, steps: int = 10, max_iterations: int = 25,
                    tol: float = 1e-8, min_step: float = 1e-4, rigid_faces=(),
                    solver: str = "direct") -> NonlinearResult:
    """Large-deflection static solve of ``model`` under ``supports`` (Fixed, Prescribed),
    ``loads`` (Force, Traction, PointForce, BodyForce, Gravity: dead; Pressure: follower) and
    ``rigid_faces`` (RigidFace, 2-D), all scaled by a load factor stepped 0 -> 1 in
    ``steps`` equal increments. A step whose Newton iterations fail (``max_iterations``
    reached, residual diverging, an element inverted, a singular tangent) is halved, down
    to ``min_step`` (a load-factor increment); below that NonConvergenceError is raised.
    Converged when |r| <= tol * reference force (applied loads and reactions, N) and the
    last increment |dz| <= sqrt(tol) |u| (Newton converges quadratically, so the error
    left is about |dz|^2). ``solver``: 'direct', 'amg' (symmetric positive tangent only) or
    'auto'."""
    _check_arguments(steps, max_iterations, tol, min_step)
    problem = _Problem(model, supports, loads, rigid_faces, solver)
    z = np.zeros(problem.space.n)
    u0 = np.zeros(model.n_dofs)
    r0 = np.zeros(model.n_dofs)
    lams, us, its = [0.0], [u0], [0]
    records = [_record(problem, z, u0, r0, 0.0)]
    nominal = 1.0 / steps
    dlam, lam, cuts, good, cuts_here = nominal, 0.0, 0, 0, 0
    z_previous = z
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
                    "(a limit point), which load control cannot pass: prescribe a displacement "
                    "instead", lam, lam + dlam, len(failure.history), failure.history) from None
            dlam, cuts, good, cuts_here = dlam / 2, cuts + 1, 0, cuts_here + 1
            continue
        lam, cuts_here = lam + dlam, 0
        z_previous, z = z, z_new
        lams.append(lam)
        us.append(u)
        its.append(n_it)
        records.append(_record(problem, z, u, r, lam))
        good += 1
        if good >= 2 and dlam < nominal:
            dlam, good = min(2 * dlam, nominal), 0
    vm_nodal, vm_element = final_stress(model, us[-1])
    return NonlinearResult(
        model=model, load_factors=np.array(lams), u=us, reactions=[rec[0] for rec in records],
        face_reactions=[rec[1] for rec in records], face_motion=[rec[2] for rec in records],
        iterations=its, von_mises_nodal=vm_nodal, von_mises_element_max=vm_element,
        applied=problem.f_ext,
        info={"n_dofs": model.n_dofs, "n_unknowns": problem.space.n, "step_cuts": cuts,
              "solver": problem.solver})
