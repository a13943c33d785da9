"""A density design written as a model file (.geo + .toml) that ``flexfem analyze`` solves
like the body-fitted re-solve, its STEP re-imported with the outline's area, and the
body-fitted difference within the tolerance that tolerance.py derives."""
import numpy as np
import pytest
from problems import inverter

from flexfem.geometry.user_model.spec import load_spec
from flexfem.studies.user_model.analysis import analyze_model
from flexfem.topopt import Interpolation, Load, Region, Spring, Support, optimize
from flexfem.topopt.export import step_area, write_step
from flexfem.topopt.model_file import write_model
from flexfem.topopt.outline import extract_outline, problem_anchors
from flexfem.topopt.tolerance import body_fitted_tolerance
from flexfem.topopt.verify import verify_mechanism

E, T = 2e9, 1e-3  # Pa, m: a polymer sheet; the unit problem's design, scaled to 40 x 20 mm


def _physical(problem):
    """The unit problem scaled to elements of 1 mm with E and thickness T (same design)."""
    from dataclasses import replace

    s = 1e-3

    def region(r):
        v = r.value
        return Region(r.kind, tuple(tuple(c * s for c in p) for p in v) if r.kind == "box"
                      else tuple(c * s for c in v) if r.kind == "point" else v)

    g = problem.grid
    return replace(problem, grid=type(g)(g.nelx, g.nely, g.lx * s, g.ly * s), thickness=T,
                   interpolation=Interpolation("simp", 3.0, E, 1e-9 * E),
                   supports=tuple(Support(region(x.where), x.fix) for x in problem.supports),
                   loads=tuple(Load(region(x.where), x.force) for x in problem.loads),
                   springs=tuple(Spring(x.name, region(x.where), x.dof, x.stiffness * E * T)
                                 for x in problem.springs))


@pytest.fixture(scope="module")
def design():
    problem = _physical(inverter(40, 20))
    result = optimize(problem)
    return problem, result, extract_outline(result.density, problem.grid,
                                            problem_anchors(problem))


def test_flexfem_analyze_of_the_written_model_matches_the_body_fitted_solve(design, tmp_path):
    problem, result, outline = design
    path = write_model(problem, outline, tmp_path, rho=1200.0, yield_strength=5e7)
    assert {p.name for p in tmp_path.iterdir()} == {"design.geo", "design.toml"}
    analysed = analyze_model(load_spec(path))
    free = verify_mechanism(problem, outline, springs=False)
    u = analysed["mean_displacement"]
    assert u["output"][0] < 0 < u["input"][0]
    assert u["output"][0] == pytest.approx(free["output"], rel=0.08)
    assert u["input"][0] == pytest.approx(free["input"], rel=0.08)
    assert u["support1"] == pytest.approx([0.0, 0.0], abs=1e-12)


def test_the_step_file_reimports_with_the_outlines_area(design, tmp_path):
    _, _, outline = design
    path = write_step(outline, tmp_path / "design.step")
    assert step_area(path) == pytest.approx(outline.shape.area, rel=1e-9)


def test_the_body_fitted_output_lies_within_the_derived_tolerance(design):
    problem, result, outline = design
    tol = body_fitted_tolerance(problem, result.density)
    assert tol["u"] == pytest.approx(result.summary()["u_out"], rel=1e-9)
    fitted = verify_mechanism(problem, outline)["output"]
    assert abs(fitted - tol["u"]) <= tol["tolerance"]
    assert np.sign(fitted - tol["u"]) == np.sign(tol["threshold_shift"])


def test_every_load_case_reaches_the_body_fitted_check_and_a_model_file(tmp_path):
    """A solid strip (nu = 0, one element deep) pulled along its axis, by F1 in load case 1
    and F2 in case 2: the body-fitted compliances are F^2 L / (E A) (an axial bar), and each
    case has its model file, which flexfem analyze solves to the same end displacement."""
    from shapely.geometry import box

    from flexfem.topopt.outline import Outline
    from flexfem.topopt.problem_file import problem_from_dict
    from flexfem.topopt.verify import verify_compliances

    L, h, E, forces = 0.1, 0.01, 2e9, (50.0, 120.0)
    problem = problem_from_dict({
        "domain": {"nelx": 10, "nely": 1, "size": [L, h], "thickness": 1e-3},
        "material": {"E": E, "nu": 0.0},
        "support": [{"where": {"edge": "left"}, "fix": ["x", "y"]}],
        "load": [{"where": {"edge": "right"}, "force": [f, 0.0], "case": c}
                 for c, f in enumerate(forces, start=1)],
        "objective": {"kind": "compliance"}, "constraint": [{"kind": "volume", "max": 1.0}]})
    outline = Outline(box(0.0, 0.0, L, h), (), 0.0)
    axial = L / (E * h * 1e-3)
    assert verify_compliances(problem, outline) == pytest.approx(
        [f**2 * axial for f in forces], rel=1e-9)
    solid = np.ones(problem.grid.n_elements)
    for c, f in enumerate(forces, start=1):
        tol = body_fitted_tolerance(problem, solid, None, c)
        assert tol["u"] == pytest.approx(f**2 * axial, rel=1e-9)
        assert tol["threshold_shift"] == 0.0
    write_model(problem, outline, tmp_path, rho=1000.0, yield_strength=1e8)
    for c, f in enumerate(forces, start=1):
        path = tmp_path / ("design.toml" if c == 1 else f"design_case{c}.toml")
        out = analyze_model(load_spec(path))
        assert out["mean_displacement"][f"load{c - 1}"][0] == pytest.approx(f * axial,
                                                                             rel=1e-6)
