"""RMS-optimal balancers (Eqs. 13-26, Appendix 2) against brute-force minimisation."""
import numpy as np
import pytest
from scipy.optimize import least_squares
from flexfem.studies.balancing.gravity import load_robot, workspace_torques
from flexfem.studies.balancing.optimum import (
    counterweight_torque,
    max_reduction_pct,
    optimal_counterweight,
    optimal_coupled_springs,
    optimal_spring,
    optimal_spring_and_torsion,
    optimal_torsion_spring,
    rms_reduction_pct,
    spring_polynomial,
    spring_torque,
    torsion_spring_torque,
)
from flexfem.studies.balancing.report import default_workspace


def minimise_rms_numerically(torque_model, q, tau, starts):
    """Brute force: minimise sum (tau + torque_model(q, *p))^2 from every start p0.

    torque_model(q, *p) -> N m; starts: iterable of parameter tuples. Each start is driven to
    a local minimum by Levenberg-Marquardt on the residuals with finite-difference Jacobians
    (scipy.optimize.least_squares), independent of the closed forms; the best is kept.
    """
    def residual(p):
        return tau + torque_model(q, *p)

    best = None
    for p0 in starts:
        r = least_squares(residual, np.asarray(p0, float), method="lm",
                          xtol=1e-15, ftol=1e-15, gtol=1e-15)
        if best is None or r.cost < best.cost:
            best = r
    return best.x


WT = workspace_torques(load_robot(), default_workspace(quick=True))
MOTORS = range(4)


def _f(tau, balancer_torque):
    return np.sum((tau + balancer_torque) ** 2)


def _phasor(C, angle):
    """C sin(q - angle) = C cos(angle) sin q - C sin(angle) cos q: the torque's coefficients,
    the same for (C, angle) and (-C, angle + pi), so closed form and brute force compare."""
    return np.array([C * np.cos(angle), -C * np.sin(angle)])


@pytest.mark.parametrize("i", MOTORS)
def test_spring_closed_form_matches_brute_force(i):
    """Eqs. 18-19 through the sextic vs Nelder-Mead + BFGS from 15 starts: the optimum is a
    smooth isolated minimum, BFGS to gtol 1e-12 lands within ~1e-9 of it; 1e-6 relative."""
    q, tau = WT.q[:, i], WT.tau[:, i]
    closed = optimal_spring(q, tau)
    starts = [(c, a) for c in (-10.0, 1.0, 10.0) for a in np.linspace(-3.0, 3.0, 5)]
    C, a = minimise_rms_numerically(spring_torque, q, tau, starts)
    ours, brute = _phasor(closed.C, closed.q_k), _phasor(C, a)
    assert np.linalg.norm(ours - brute) <= 1e-6 * np.linalg.norm(brute)
    assert closed.C > 0
    np.testing.assert_allclose(_f(tau, closed.torque(q)), _f(tau, spring_torque(q, C, a)),
                               rtol=1e-9)


@pytest.mark.parametrize("i", MOTORS)
def test_appendix2_sextic_has_the_optimum_as_a_root(i):
    """The linear least-squares solution in (sin q, cos q) is the global optimum; its
    t = tan(q_k / 2) must be a root of the printed polynomial (relative residual ~ eps)."""
    q, tau = WT.q[:, i], WT.tau[:, i]
    basis = np.column_stack([np.sin(q), np.cos(q)])
    (u, v), *_ = np.linalg.lstsq(basis, -tau, rcond=None)
    q_k = np.arctan2(-v, u)
    coefficients = spring_polynomial(q, tau)
    t = np.tan(q_k / 2)
    scale = np.sum(np.abs(coefficients) * np.abs(t) ** np.arange(6, -1, -1))
    assert abs(np.polyval(coefficients, t)) <= 1e-12 * scale
    spring = optimal_spring(q, tau)
    np.testing.assert_allclose(_phasor(spring.C, spring.q_k), [u, v], rtol=1e-9)


@pytest.mark.parametrize("i", MOTORS)
def test_torsion_closed_form_matches_brute_force(i):
    """Eqs. 23-24 vs brute force on (K, q_k). Compared as (K, K q_k): the torque's two
    coefficients, well conditioned even when q_k is large (K ~ 0); 1e-6 relative."""
    q, tau = WT.q[:, i], WT.tau[:, i]
    closed = optimal_torsion_spring(q, tau)
    K, qk = minimise_rms_numerically(torsion_spring_torque, q, tau,
                                     [(k, a) for k in (-5.0, 0.5, 5.0) for a in (-2.0, 0.0, 3.0)])
    np.testing.assert_allclose(_f(tau, closed.torque(q)), _f(tau, torsion_spring_torque(q, K, qk)),
                               rtol=1e-9)
    ours, brute = np.array([closed.K, closed.K * closed.q_k]), np.array([K, K * qk])
    assert np.linalg.norm(ours - brute) <= 1e-6 * np.linalg.norm(brute)


@pytest.mark.parametrize("i", MOTORS)
def test_counterweight_closed_form_matches_brute_force(i):
    q, tau = WT.q[:, i], WT.tau[:, i]
    closed = optimal_counterweight(q, tau)
    starts = [(c, a) for c in (-10.0, 1.0, 10.0) for a in np.linspace(-3.0, 3.0, 5)]
    C, a = minimise_rms_numerically(counterweight_torque, q, tau, starts)
    ours, brute = _phasor(-closed.C, closed.q_c), _phasor(-C, a)
    assert np.linalg.norm(ours - brute) <= 1e-6 * np.linalg.norm(brute)
    assert -2 * np.pi < closed.q_c <= 0.0 and closed.C > 0
    # Section V.C: the counterweight's optimum is the spring's, turned by pi
    np.testing.assert_allclose(closed.torque(q), optimal_spring(q, tau).torque(q), atol=1e-12)


def test_reductions_of_exact_and_no_balancing():
    tau = np.array([1.0, -2.0, 3.0])
    assert rms_reduction_pct(tau, 0 * tau) == 100.0 and max_reduction_pct(tau, tau) == 0.0


def test_more_variables_never_do_worse():
    """Nested least-squares models: spring + torsion spring contains each alone; the coupled
    five-bar problem contains the two independent arm springs (c = 0)."""
    for i in MOTORS:
        q, tau = WT.q[:, i], WT.tau[:, i]
        both = _f(tau, optimal_spring_and_torsion(q, tau).torque(q))
        assert both <= _f(tau, optimal_spring(q, tau).torque(q)) * (1 + 1e-12)
        assert both <= _f(tau, optimal_torsion_spring(q, tau).torque(q)) * (1 + 1e-12)
    for a, b in ((0, 1), (2, 3)):
        qa, qb, ta, tb = WT.q[:, a], WT.q[:, b], WT.tau[:, a], WT.tau[:, b]
        sa, sb, c = optimal_coupled_springs(qa, qb, ta, tb)
        d = c * np.sin(qa - qb)
        coupled = _f(ta, sa.torque(qa) + d) + _f(tb, sb.torque(qb) - d)
        separate = (_f(ta, optimal_spring(qa, ta).torque(qa))
                    + _f(tb, optimal_spring(qb, tb).torque(qb)))
        assert coupled <= separate * (1 + 1e-12)


def test_coupled_springs_brute_force():
    """The five-parameter coupled problem against brute force on its objective (1e-6)."""
    qa, qb, ta, tb = WT.q[:, 0], WT.q[:, 1], WT.tau[:, 0], WT.tau[:, 1]
    sa, sb, c = optimal_coupled_springs(qa, qb, ta, tb)

    def model(q, Ca, ka, Cb, kb, cc):
        d = cc * np.sin(qa - qb)
        return np.concatenate([spring_torque(qa, Ca, ka) + d, spring_torque(qb, Cb, kb) - d])

    tau = np.concatenate([ta, tb])
    x = minimise_rms_numerically(model, None, tau, [(5.0, 0.0, 10.0, -0.5, 0.0),
                                                    (-5.0, 1.0, -10.0, 1.0, -5.0)])
    np.testing.assert_allclose(_f(tau, model(None, *x)),
                               _f(tau, model(None, sa.C, sa.q_k, sb.C, sb.q_k, c)), rtol=1e-8)
    assert abs(x[4] - c) <= 1e-6 * abs(c)
