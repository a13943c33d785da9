"""One load step of a beam model's nonlinear solve, planar or spatial: Newton's iterations
(the package's one driver, :func:`..newton.newton`) from a converged state to a load factor
(load control) or to a control DOF's value (displacement control, the load factor the extra
unknown: Batoz & Dhatt).

The model's Assembler gives the states: ``at(config, lam)`` (an evaluation with ``r``,
``rz`` and the reduced tangent ``K``) and ``load_rate(ev)`` (d rz / d lam); its Space the
configuration's arithmetic: ``advance(config, dz, dlam)``, ``size(config)``, ``value(config,
k)`` (free unknown k's value), ``control_index(control)`` and ``FLOOR``.
"""
import math

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..newton import NonConvergenceError, newton
from ..stepping import StepFailed
from .assembly import Factor, SingularBeamError


class Stepper:
    """Newton's iterations to a load factor or a control value (``control=(node, dof,
    value)``) of the model behind ``asm``; ``tol`` and ``max_iterations`` as the solve's.
    Converged when |rz| <= tol * reference and the last correction |dz| <= sqrt(tol) |z|,
    or at round-off (Space.FLOOR: the correction below FLOOR[0] of the configuration and
    the residual below FLOOR[1] of the reference)."""

    def __init__(self, asm, control, tol, max_iterations):
        self.asm, self.tol, self.max_iterations = asm, tol, max_iterations
        self.c_index, self.last_count = None, None
        if control is not None:
            self.c_value = control[2]
            self.c_index = asm.space.control_index(control)

    def reference(self, r, lam) -> float:
        """The force scale the residual is relative to: |lam f_ext| + |reactions| (N)."""
        f_ext, held = self.asm.f_ext, self.asm.space.held
        ref = np.linalg.norm(lam * f_ext) + np.linalg.norm(r[held])
        return max(ref, 1e-12 * (1.0 + np.abs(f_ext).max()))

    def correction(self, ev, config, lam, target, signs, first=False):
        """(dz, dlam): the Newton correction at the evaluation ``ev`` of (config, lam); the
        first one (the predictor) takes the load factor to ``target`` under load control.
        Appends the sign of det K to ``signs``."""
        try:
            F = Factor(ev.K)
        except SingularBeamError as exc:
            raise StepFailed(str(exc), []) from None
        signs.append(F.sign)
        if self.c_index is None and not first:
            return F.solve(-ev.rz), 0.0
        a, b = F.solve(np.column_stack([-ev.rz, self.asm.load_rate(ev)])).T
        if self.c_index is None:
            return a - (target - lam) * b, target - lam
        if abs(b[self.c_index]) < 1e-300:
            raise StepFailed("the control DOF does not respond to the load", [])
        now = self.asm.space.value(config, self.c_index)
        dlam = (now + a[self.c_index] - target) / b[self.c_index]
        return a - dlam * b, dlam

    def step(self, config, lam, target) -> tuple:
        """Converged (config, lam, ev, iterations, flipped) reaching ``target`` (a load
        factor, or the control DOF's value) from the converged (config, lam); flipped: the
        tangent's determinant changed sign over the step (a limit or bifurcation point)."""
        asm, space, signs = self.asm, self.asm.space, []
        floor_step, floor_residual = space.FLOOR
        predictor = self.correction(asm.at(config, lam), config, lam, target, signs, True)

        def residual(x):
            ev = asm.at(*x)
            return ev.rz, self.reference(ev.r, x[1]), ev

        def update(x, d):
            return space.advance(x[0], d[0], d[1]), x[1] + d[1]

        def converged(x, d, size, reference, ev):
            step, scale = np.linalg.norm(d[0]), space.size(x[0])
            return (size <= self.tol * reference
                    and step <= math.sqrt(self.tol) * max(scale, 1e-14)) \
                or (step <= floor_step * scale and size <= floor_residual * reference)

        found = newton(update((config, lam), predictor), residual,
                       lambda x, r, ev: self.correction(ev, *x, target, signs),
                       tol=self.tol, max_iterations=self.max_iterations, update=update,
                       converged=converged, done=1, dx=predictor)
        self.last_count = negative_eigenvalues(found.state.K)
        (config, lam), ev = found.x, found.state
        return config, lam, ev, found.iterations, signs[0] != signs[-1]


def negative_eigenvalues(K):
    """The number of negative eigenvalues of (the symmetric part of) the tangent ``K``, a
    Sturm count: the negative pivots of its LDL^T (SuperLU without row pivoting, Jacobi
    scaled); None where a pivot is (nearly) zero or SuperLU had to pivot."""
    K = sp.csc_matrix(0.5 * (K + K.T))
    scale = sp.diags(1.0 / np.sqrt(np.abs(K.diagonal())))
    try:
        lu = spla.splu(sp.csc_matrix(scale @ K @ scale), permc_spec="MMD_AT_PLUS_A",
                       diag_pivot_thresh=0.0, options={"SymmetricMode": True})
    except RuntimeError:
        return None
    d = lu.U.diagonal()
    if not np.array_equal(lu.perm_r, lu.perm_c) or np.abs(d).min() <= 1e-13:
        return None
    return int(np.count_nonzero(d < 0))


def step_failure(t, dt, lam, cuts, failure) -> NonConvergenceError:
    """The error of a beam solve whose step from fraction ``t`` by ``dt`` (last converged load
    factor ``lam``) failed at the smallest step allowed (planar and spatial alike)."""
    return NonConvergenceError(
        f"no convergence beyond step fraction {t:.6g} (load factor {lam:.6g}; trying "
        f"{t + dt:.6g}) after {cuts} cuts: {failure.reason}; relative residuals "
        f"{', '.join(f'{h:.2e}' for h in failure.history) or 'none'}. Use more steps or a "
        "smaller min_step; under load control a limit point (buckling, snap-through) cannot "
        "be passed: use control=(node, dof, value)", lam, t + dt, len(failure.history),
        failure.history)
