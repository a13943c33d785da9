"""The robust formulation (topopt/robust.py): the minimum size relation against its
derivation by quadrature, the gradients of the worst-case objective and of every
constraint against central finite differences, the problem file's min_hinge, the
refused combinations and a short run."""
import numpy as np
import pytest
from problems import inverter, mbb
from test_gradients import CONSTRAINTS, fd_check

from flexfem.topopt import (Constraint, Optimizer, Projection, Response, optimize,
                            problem_from_dict)
from flexfem.topopt.problem_file import read_problem_file
from flexfem.topopt.robust import Robust, aggregate, member_ratio, radius_for, size_ratio

ROBUST = dict(projection=Projection(beta=1.0, eta=0.5, beta_max=16.0, every=5),
              robust=Robust(0.3))


def _hat(s: float, r: float = 1.0) -> float:
    return max(r - abs(s), 0.0)


def _cone_across(s: float, r: float = 1.0) -> float:
    """top88's cone r - |d| integrated along a straight member: its profile across it."""
    s = abs(s)
    if s >= r:
        return 0.0
    h = np.sqrt(r * r - s * s)
    log = s * s * np.log((h + r) / s) if s > 0 else 0.0
    return 2.0 * r * h - (h * r + log)


def _bar_width(eta_e: float, kernel=_hat, r: float = 1.0) -> float:
    """The 0.5-level width of the filtered 0/1 bar whose filtered peak is eta_e, by
    quadrature (``kernel`` normalised) and root finding: the bar's half width a from its
    peak, then the point where the filtered field falls to 0.5."""
    from scipy.integrate import quad
    from scipy.optimize import brentq

    norm = quad(kernel, -r, r, points=[0.0])[0]

    def filtered(t, a):    # the kernel centred at t over the bar [-a, a]
        return quad(lambda s: kernel(s - t), -a, a, points=[t], limit=200)[0] / norm

    a = brentq(lambda a: filtered(0.0, a) - eta_e, 1e-9, r)
    return 2.0 * brentq(lambda t: filtered(t, a) - 0.5, 0.0, a + r)


@pytest.mark.parametrize("eta_e", [0.55, 0.6, 0.7, 0.75, 0.8, 0.9])
def test_minimum_size_relation_is_the_hat_filters_bar(eta_e):
    assert size_ratio(eta_e) == pytest.approx(_bar_width(eta_e), abs=1e-8)


def test_top88s_cone_across_a_member_gives_up_to_6_percent_less():
    assert _bar_width(0.75, _cone_across) == pytest.approx(0.9425, abs=1e-3)
    assert _bar_width(0.6, _cone_across) == pytest.approx(0.957 * size_ratio(0.6), abs=1e-3)


@pytest.mark.parametrize("eta_e", [0.6, 0.75, 0.9])
def test_the_radius_is_that_of_the_2d_filters_member(eta_e):
    """member_ratio (what radius_for uses) is the cone's bar width, derived here with
    the radius 2 so that a radius-1 shortcut would show."""
    assert member_ratio(eta_e) == pytest.approx(_bar_width(eta_e, lambda s: _cone_across(
        s, 2.0), r=2.0) / 2.0, abs=1e-8)


def test_minimum_size_relation_values_and_inverse():
    assert size_ratio(0.75) == pytest.approx(1.0)     # both branches meet: b = r
    assert size_ratio(0.5) == 0.0 and size_ratio(1.0) == pytest.approx(2.0)
    r = radius_for(0.6e-3, 0.2e-3, 0.25)
    assert r == pytest.approx(3.0 / _bar_width(0.75, _cone_across), rel=1e-6)   # 3.18
    assert Robust(0.25).minimum_sizes(r, 0.2e-3)["solid"] == pytest.approx(0.6e-3)
    assert Robust(0.3).thresholds == (0.7, 0.5, 0.3)   # eroded: the higher threshold


def test_ks_aggregate_bounds_the_worst():
    v = np.array([-1.0, -0.7, -0.9])
    ks, w, _ = aggregate(v, 1.0)
    assert -0.7 <= ks <= -0.7 + np.log(3) / 20.0
    assert w.sum() == pytest.approx(1.0) and np.argmax(w) == 1


@pytest.mark.parametrize("beta", [1.0, 8.0])
@pytest.mark.parametrize("sense", ["min", "max"])
def test_robust_gradients_of_objective_and_constraints(beta, sense):
    stress = Constraint(Response("stress", pnorm=8.0), upper=1.0)
    fd_check(inverter(6, 4, "density", constraints=CONSTRAINTS + (stress,), sense=sense,
                       **ROBUST), beta=beta)


def test_robust_gradients_with_a_frequency_constraint_and_a_volume_ratio():
    problem = mbb(6, 4, "density", 1.5, mass_density=2.0, optimizer=Optimizer("mma"),
                  constraints=(Constraint(Response("volume"), upper=0.4),
                               Constraint(Response("frequency"), lower=0.01)), **ROBUST)
    fd_check(problem, beta=4.0)


INVERTER_FILE = "examples/topopt/inverter_robust.toml"


def test_min_hinge_sets_the_filter_radius():
    data = read_problem_file(INVERTER_FILE)
    problem = problem_from_dict(data)
    element = problem.grid.dx
    sizes = problem.robust.minimum_sizes(problem.radius, element)
    assert sizes["solid"] == pytest.approx(data["robust"]["min_hinge"], rel=1e-12)
    data["filter"]["radius"] = 2.0
    with pytest.raises(ValueError, match="not both"):
        problem_from_dict(data)


@pytest.mark.parametrize("change, message", [
    ({"filter": {"kind": "helmholtz"}}, "density"),
    ({"optimizer": {"kind": "oc"}}, "oc"),
    ({"robust": {"min_hinge": 1e-4}}, "refine the grid"),
    ({"robust": {"eta": 0.6}}, "eta"),
    ({"projection": {"eta": 0.4}}, "eta = 0.5")])
def test_refused_combinations_name_themselves(change, message):
    data = read_problem_file(INVERTER_FILE)
    for table, values in change.items():
        data.setdefault(table, {}).update(values)
    with pytest.raises(ValueError, match=message):
        problem_from_dict(data)


def test_short_robust_run_reports_its_designs_and_sizes():
    problem = inverter(20, 10, "density", iterations=12, **ROBUST)
    result = optimize(problem)
    robust = result.summary()["robust"]
    designs = robust["designs"]
    assert designs["eroded"]["volume"] < designs["intermediate"]["volume"] \
        < designs["dilated"]["volume"]
    assert robust["min_solid"] == pytest.approx(_bar_width(0.7, _cone_across) * 1.5, rel=1e-6)
    assert result.objective >= max(d["objective"] for d in designs.values()) - 1e-12


@pytest.mark.slow
def test_robust_inverter_keeps_its_minimum_hinge_on_the_body_fitted_shape():
    """examples/topopt/inverter_robust.toml (80 x 40 elements of 0.5 mm, min_hinge 1.5 mm)
    to convergence: every neck of its outline at least min_hinge wide, the body-fitted u_out
    within 15 % of the intermediate design's; the same problem without length control
    (radius 1.5, projection only) has a neck thinner than min_hinge."""
    from dataclasses import replace

    from flexfem.topopt.neck_check import problem_necks
    from flexfem.topopt.outline import extract_outline, problem_anchors
    from flexfem.topopt.verify import verify_mechanism

    problem = problem_from_dict(read_problem_file(INVERTER_FILE))
    hinge = problem.robust.min_size
    widths = {}
    for name, p in (("robust", problem), ("plain", replace(problem, robust=None, radius=1.5))):
        result = optimize(p)
        assert result.converged
        outline = extract_outline(result.density, p.grid, problem_anchors(p))
        widths[name] = [n.width for n in problem_necks(p, outline, 2 * hinge)]
        if name == "robust":
            fitted = verify_mechanism(p, outline)["output"]
            assert fitted == pytest.approx(result.summary()["u_out"], rel=0.15)
    assert widths["robust"] and min(widths["robust"]) >= hinge
    assert min(widths["plain"]) < hinge


def test_robust_run_resumes_to_the_same_design(tmp_path):
    """Stopped at iteration 7 (after the volume ratio's update at 1, before the one at 21)
    and rerun: the same design as one run, the ratio restored from state.npz."""
    from problems import interrupt_at

    problem = inverter(20, 10, "density", iterations=25, **ROBUST)
    whole = optimize(problem)
    interrupt_at(problem, tmp_path, 7)
    resumed = optimize(problem, out_dir=tmp_path)
    assert resumed.iterations == whole.iterations
    np.testing.assert_allclose(resumed.density, whole.density, atol=1e-10)
