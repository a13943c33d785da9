"""The DBMA-envelope amplifier with a minimum hinge width: its grid and filter from min_hinge,
the verdict's logic on records with known answers, and the stored design (what the quick
report reads) against the code that wrote it."""
import numpy as np
import pytest

from flexfem.studies.dbma.topopt_robust import (density_binding, density_violated, min_hinge,
                                                read_stored, robust_problem, verdict)
from flexfem.topopt.amplifier import amplifier_problem, dbma_envelope, spring_free
from flexfem.topopt.model import Discrete
from flexfem.topopt.robust import member_ratio


def test_min_hinge_gives_square_elements_inside_the_envelope_and_the_filters_radius():
    env = dbma_envelope()
    p = amplifier_problem(800.0, 4.36e6, 4e7, 1e5, element=0.3e-3, min_hinge=0.6e-3)
    g = p.grid
    assert g.dx == pytest.approx(g.dy, rel=1e-12) == pytest.approx(0.3e-3, rel=1e-12)
    assert g.lx <= env["width"] < g.lx + g.dx and g.ly <= env["height"] < g.ly + g.dy
    assert p.robust.thresholds == (0.75, 0.5, 0.25)
    assert p.radius * g.dx * member_ratio(0.75) == pytest.approx(0.6e-3, rel=1e-12)
    d = Discrete(p)
    top = d.solid.reshape(g.nelx, g.nely)[:, -1]          # the output strip at the top
    assert top[0] and d.void.sum() > 0


def test_the_dbmas_hinge_is_its_leaf_thickness():
    assert min_hinge() == pytest.approx(0.6e-3)


def _record(**verified):
    """A record of the stored form with round numbers: limits k_in 4 MN/m, 700 Hz, 600 MPa."""
    base = {"R_fitted": 9.0, "R_density": 10.0, "k_in": 5e6, "fn_working": 800.0,
            "peak_stress": 500e6}
    return {"problem": {"force": 800.0},
            "limits": {"k_in_min": 4e6, "fn_min": 700.0, "stress_max": 600e6},
            "result": {"constraints": {"volume": 0.25, "displacement_input": 1e-4,
                                       "frequency": 900.0, "stress": 300e6}},
            "verified": {**base, **verified}, "necks": [{"width": 7e-4}, {"width": 6e-4}]}


def test_a_neck_under_min_hinge_fails_the_verdict():
    r = _record()
    r["problem"]["min_hinge"] = 6.5e-4
    w = verdict(r, 8.6)
    assert not w["beats"] and w["failed"] == ["min_hinge"]


def test_the_verdict_beats_the_bow_only_with_every_constraint_met_on_the_shape():
    assert verdict(_record(), 8.6)["beats"]
    w = verdict(_record(k_in=3e6), 8.6)
    assert not w["beats"] and w["failed"] == ["k_in"]
    w = verdict(_record(R_fitted=4.3), 8.6)
    assert not w["beats"] and w["shortfall"] == pytest.approx(0.5) and not w["failed"]
    assert w["fitted_over_density"] == pytest.approx(0.43) and w["narrowest_neck"] == 6e-4


def test_binding_constraints_are_those_at_their_bounds():
    r = _record()
    assert density_binding(r) == ["k_in"]         # u_in = (F / 2) / k_in_min = 1e-4 m
    r["result"]["constraints"].update(frequency=701.0, volume=0.2, displacement_input=5e-5)
    assert density_binding(r) == ["frequency"] and density_violated(r) == []
    r["result"]["constraints"].update(frequency=100.0)
    assert density_binding(r) == [] and density_violated(r) == ["frequency"]


@pytest.fixture(scope="module")
def stored():
    return read_stored()


def test_the_stored_design_reads_as_stored(stored):
    """The stored densities on the stored limits' problem give the stored density-model R,
    and its body-fitted R and necks are of the hinge asked for."""
    problem = robust_problem(stored["limits"], stored["problem"]["iterations"],
                             stored["problem"]["element"])
    g = problem.grid
    assert (g.nelx, g.nely) == (stored["problem"]["nelx"], stored["problem"]["nely"])
    d = Discrete(spring_free(problem))
    u = d.system.solve(problem.interpolation.modulus(stored["density"]), d.force)[:, 0]
    r = (d.spring_vectors["output"] @ u) / (d.spring_vectors["input"] @ u)
    assert r == pytest.approx(stored["verified"]["R_density"], rel=1e-6)
    widths = [n["width"] for n in stored["necks"]]
    assert all(np.isfinite(widths))


def test_robust_gradients_with_the_structures_own_input_stiffness_frequency_and_stress():
    """The amplifier's constraints together, by the robust formulation: u_in without the
    springs (the input stiffness), u_in with them, the lowest frequency, the stress norm."""
    from dataclasses import replace

    from problems import inverter
    from test_gradients import fd_check
    from flexfem.topopt import Constraint, Projection, Response
    from flexfem.topopt.robust import Robust

    constraints = (Constraint(Response("volume"), upper=0.5),
                   Constraint(Response("displacement", "input", springs=False), upper=5.0),
                   Constraint(Response("displacement", "input"), upper=5.0),
                   Constraint(Response("frequency"), lower=0.01),
                   Constraint(Response("stress", pnorm=8.0), upper=1.0))
    problem = inverter(6, 4, "density", constraints=constraints, sense="min",
                       projection=Projection(beta=1.0, eta=0.5, beta_max=16.0, every=5),
                       robust=Robust(0.3))
    fd_check(replace(problem, mass_density=2.0), beta=4.0)


def test_the_displacement_without_springs_is_that_of_springs_made_negligible():
    from dataclasses import replace

    from problems import inverter
    from flexfem.topopt import Constraint, Response

    free = Constraint(Response("displacement", "input", springs=False), upper=1.0)
    problem = inverter(6, 4, "density", constraints=(free,))
    weak = replace(problem, springs=tuple(replace(s, stiffness=1e-12 * s.stiffness)
                                          for s in problem.springs), constraints=())
    d, w = Discrete(problem), Discrete(weak)
    z = np.full(d.n_variables, 0.4)
    assert d.evaluate(z).constraints[0] == pytest.approx(w.evaluate(z).displacements["input"],
                                                         rel=1e-9)


def test_the_large_displacement_reading_is_that_of_the_nonlinear_solver():
    """At the DBMA's force the large-displacement R of a coarse grey quarter is within 1 % of
    the small one's, and not equal to it (the nonlinear solver ran); at 100 times the force
    u_out departs from the small-displacement one over ten times more (the geometry changes)."""
    from dataclasses import replace

    from flexfem.studies.dbma.topopt_robust import FORCE, large_reading

    p = amplifier_problem(FORCE, 4.36e6, 4e7, 1e5, element=2e-3)
    rho = np.full(p.grid.n_elements, 0.6)
    r = large_reading(p, rho)
    assert r["large"]["R"] == pytest.approx(r["small"]["R"], rel=1e-2)
    assert r["large"]["u_out"] != r["small"]["u_out"]
    strong = replace(p, loads=tuple(replace(ld, force=(100 * ld.force[0], 0.0))
                                    for ld in p.loads))
    big = large_reading(strong, rho)
    assert abs(big["large"]["u_out"] / big["small"]["u_out"] - 1) > 10 * abs(
        r["large"]["u_out"] / r["small"]["u_out"] - 1)
