"""The amplifier problem in the DBMA's envelope: its quarter, the actuator's room void, the
pad and the output solid, the input stiffness a limit; a few coarse iterations run. The
body-fitted readings (modes, peak stress and its corner) against closed forms, and the
report section."""
import numpy as np
import pytest
from shapely.geometry import Polygon, box

from flexfem.topopt import (Grid, Interpolation, Load, Optimizer, Problem, Region, Response,
                            Spring, Support, optimize)
from flexfem.topopt.amplifier import (amplifier_problem, dbma_envelope, dbma_quarter,
                                      verify_amplifier)
from flexfem.topopt.model import Discrete
from flexfem.topopt.outline import Outline
from flexfem.topopt.verify import interior_angles, mirror_lines, verify_modes, verify_static


def test_the_envelope_is_the_dbmas_quarter():
    env = dbma_envelope()
    assert env["width"] == pytest.approx(0.04322) and env["height"] == pytest.approx(0.04547)
    assert env["pad"][0][0] == pytest.approx(0.03122) and env["thickness"] == 0.01


def test_a_coarse_amplifier_moves_its_output_up():
    problem = amplifier_problem(800.0, 4.36e6, 4e7, 1e5, element=2e-3, iterations=15,
                                radius=1.5)
    d = Discrete(problem)
    assert d.void.sum() > 0 and d.solid.sum() > 0
    result = optimize(problem)
    s = result.summary()
    assert s["u_out"] > 0 and s["u_in"] > 0
    assert s["u_in"] <= 400.0 / 4.36e6 * (1 + 1e-3)
    assert np.all(result.density[d.void] == 0.0)


# --- the body-fitted readings: modes, stress and the corner it sits at ---------------------

E, NU, RHO, T = 200e9, 0.3, 7800.0, 0.005


def _strip(L=0.1, H=0.01, supports=("x", "y"), force=(1000.0, 0.0)) -> Problem:
    """A strip L x H (m) on a 2 mm grid: the left edge held along x, the bottom along y
    (symmetry lines), pulled at the right edge; a spring 'output' there along x."""
    return Problem(Grid(round(L / 2e-3), round(H / 2e-3), L, H),
                   Response("displacement", "output"), sense="max", nu=NU, thickness=T,
                   mass_density=RHO, interpolation=Interpolation("simp", 3.0, E, 1e-9 * E),
                   supports=(Support(Region("edge", "left"), (supports[0],)),
                             Support(Region("edge", "bottom"), (supports[1],))),
                   loads=(Load(Region("edge", "right"), force),),
                   springs=(Spring("output", Region("edge", "right"), "x", 1.0),),
                   optimizer=Optimizer("mma"))


def test_a_strips_working_mode_is_the_rods_quarter_wave():
    """Held along x at one end, symmetric about its bottom edge, free at the other: the
    axial quarter wave sqrt(E / rho) / 4L (slender: Love's lateral-inertia term ~1e-4)."""
    modes = verify_modes(_strip(), Outline(box(0.0, 0.0, 0.1, 0.01), (), 0.0), n=3)
    assert modes["working_mode"] == 1
    assert modes["fn_working"] == pytest.approx(np.sqrt(E / RHO) / 0.4, rel=2e-3)


def test_a_bar_in_tension_reads_f_over_a_and_its_stretch():
    out = verify_static(_strip(), Outline(box(0.0, 0.0, 0.1, 0.01), (), 0.0))
    assert out["peak_stress"] == pytest.approx(1000.0 / (0.01 * T), rel=1e-6)
    assert out["displacements"]["output"] == pytest.approx(1000.0 * 0.1 / (E * 0.01 * T),
                                                           rel=1e-6)
    assert out["singularity_exponent"] == 0.0


def test_an_l_shapes_peak_sits_at_its_reentrant_corner_and_grows_as_williams_says():
    """An L (20 mm square less its top-right quarter) clamped at the left and loaded down
    at the right: the peak sits at the inner corner (10, 10) mm and grows by about
    2^(1 - lambda) per halving of the mesh, lambda = 0.5445 at 270 deg (Williams 1952)."""
    problem = Problem(Grid(20, 20, 0.02, 0.02), Response("displacement", "output"),
                      sense="max", nu=NU, thickness=T,
                      interpolation=Interpolation("simp", 3.0, E, 1e-9 * E),
                      supports=(Support(Region("edge", "left")),),
                      loads=(Load(Region("box", ((0.02, 0.0), (0.02, 0.01))), (0.0, -1e3)),),
                      springs=(Spring("output", Region("point", (0.02, 0.0)), "y", 1.0),),
                      optimizer=Optimizer("mma"))
    ell = Outline(Polygon([(0, 0), (0.02, 0), (0.02, 0.01), (0.01, 0.01), (0.01, 0.02),
                           (0, 0.02)]), (), 0.0)
    coarse, fine = (verify_static(problem, ell, size) for size in (0.5e-3, 0.25e-3))
    assert fine["peak_where"] == pytest.approx([0.01, 0.01], abs=1e-9)
    assert fine["corner_angle"] == pytest.approx(270.0)
    assert 1.0 - fine["singularity_exponent"] == pytest.approx(0.5445, abs=1e-4)
    growth = fine["peak_stress"] / coarse["peak_stress"]
    assert growth == pytest.approx(2 ** fine["singularity_exponent"], rel=0.05)


def test_the_dbma_quarter_read_as_a_shape_gives_the_dbmas_r_and_k_in():
    """The quarter path (symmetry lines, the pad's force spread on its face, the groups'
    mean displacements) against flexfem's whole-part 2-D FEM of the DBMA (its own graded
    mesh, the mounting face held): R and k_in within 1 %; its square hinge roots are its
    re-entrant corners (4 a hinge, 4 hinges) with the pad's root, and the cuts at x = 0
    are no corners of the part."""
    from flexfem.studies.dbma.analysis import analyze_dbma

    problem = amplifier_problem(800.0, 4.36e6, 4e7, 1e5, element=0.5e-3)
    quarter = dbma_quarter()
    out = verify_static(problem, quarter, 0.25e-3)
    u = out["displacements"]
    full = analyze_dbma(dim=2, n_modes=1)
    assert u["output"] / u["input"] == pytest.approx(full["R_fem"], rel=0.01)
    assert 400.0 / u["input"] == pytest.approx(full["k_in"], rel=0.01)
    xy, angles = interior_angles(quarter, mirror_lines(problem))
    assert np.sum(np.isclose(angles, 270.0)) == 17
    assert np.allclose(angles[np.isclose(xy[:, 0], 0.0) & (xy[:, 1] > 0)], 180.0)


def test_a_solid_quarter_reads_alike_in_both_models_and_holding_the_pad_raises_its_modes():
    """The envelope all solid but the actuator's room (2 mm grid, no iteration): the density
    model and the body-fitted shape are one elastic body, so R and k_in agree to the coarse
    grid's error (Q4 against quadratic triangles, node against facet loads: 8 % and 4 % at
    2 mm, 3 % and 1.5 % at 1 mm); holding the pad
    (a rigid actuator) can only raise each mode (Rayleigh's theorem of constraint)."""
    from dataclasses import replace

    problem = replace(amplifier_problem(800.0, 4.36e6, 4e7, 1e5, element=2e-3, iterations=0),
                      initial=1.0, filter_kind="none")
    out = verify_amplifier(optimize(problem), threshold=0.5)
    assert out["R_fitted"] == pytest.approx(out["R_density"], rel=0.1)
    assert out["k_in"] == pytest.approx(out["k_in_density"], rel=0.1)
    free = verify_modes(problem, out["outline"], size=1e-3)
    assert np.all(np.array(out["frequencies_hz"]) >= np.array(free["frequencies_hz"]))
    assert out["frequencies_hz"][0] > 1.1 * free["frequencies_hz"][0]


def test_the_report_section_keeps_its_contract_in_quick(tmp_path, section_contract):
    from flexfem.studies.dbma.topopt_report import reproduce

    summary = reproduce(tmp_path, quick=True)
    section_contract(tmp_path, summary)
    rows = summary["key_tables"][0]["rows"]
    assert [r[0] for r in rows][:2] == ["DBMA, flexfem 2-D FEM (whole part)", "DBMA, paper"]
    assert "default report" in rows[2][1]
    assert [r[0] for r in rows][3:] == ["optimised, min_hinge 0.6 mm, density model",
                                        rows[4][0]] and "body-fitted" in rows[4][0]
    w = summary["min_hinge"]["verdict"]
    assert w["R_dbma"] == pytest.approx(8.6, abs=0.01)       # computed in this run
    necks = summary["min_hinge"]["necks"]
    assert w["narrowest_neck"] == min(n["width"] for n in necks)


@pytest.mark.slow
def test_the_report_section_verifies_the_optimised_design(tmp_path, section_contract):
    """The default section (the design without length control run, the stored one with the
    minimum hinge width verified again): the figure, the seven rows, and what
    the page says: the body-fitted optimised design without length control amplifies less
    than the DBMA read the same way."""
    from flexfem.studies.dbma.topopt_report import reproduce

    summary = reproduce(tmp_path)
    section_contract(tmp_path, summary)
    assert len(summary["figures"]) == 1 and len(summary["key_tables"][0]["rows"]) == 7
    assert summary["optimised"]["R_fitted"] < 8.0 < summary["optimised"]["R_density"]
