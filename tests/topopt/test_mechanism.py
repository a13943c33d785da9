"""Compliant mechanisms: the force inverter turns the input's push into an output motion the
other way, with one connected solid from the supports through the input to the output, and
does so too re-meshed as a body-fitted shape."""
import numpy as np
from problems import inverter, mbb
from scipy import ndimage

from flexfem.topopt import Constraint, Optimizer, Passive, Region, Response, optimize
from flexfem.topopt.outline import extract_outline, problem_anchors
from flexfem.topopt.verify import verify_mechanism


def _connected(problem, density, regions) -> bool:
    grid = problem.grid
    solid = (density > 0.5).reshape(grid.nelx, grid.nely)
    labels, _ = ndimage.label(solid)
    found = [set(labels.ravel()[r.touching(grid)]) - {0} for r in regions]
    return all(found) and bool(set.intersection(*found))


def test_force_inverter_moves_its_output_against_the_input():
    problem = inverter()
    result = optimize(problem)
    summary = result.summary()
    assert summary["u_in"] > 0 and summary["u_out"] < 0
    assert summary["u_out"] < -0.5  # the 99-line code's mechanism reaches about -1
    assert result.volume_fraction <= 0.3 + 1e-3
    ends = [problem.spring("input").where, problem.spring("output").where,
            problem.supports[1].where]
    assert _connected(problem, result.density, ends)
    # re-meshed as a body-fitted shape, solved by flexfem's FEM with the same springs
    outline = extract_outline(result.density, problem.grid, problem_anchors(problem))
    assert len(outline.parts) == 1 and outline.islands == ()
    fitted = verify_mechanism(problem, outline)
    assert fitted["output"] < 0 < fitted["input"]
    assert abs(fitted["input"] / summary["u_in"] - 1) < 0.15
    assert abs(fitted["output"] / summary["u_out"] - 1) < 0.35


def test_an_input_displacement_limit_is_honoured():
    limit = Constraint(Response("displacement", "input"), upper=7.0)  # 9 without it
    problem = inverter(24, 12, iterations=120,
                       constraints=(Constraint(Response("volume"), upper=0.3), limit))
    result = optimize(problem)
    assert result.displacements["input"] <= 7.0 * 1.01
    assert result.displacements["output"] < 0


def test_passive_regions_and_symmetry_are_kept():
    passive = (Passive(Region("box", ((12.0, 0.0), (18.0, 4.0))), "void"),
               Passive(Region("box", ((0.0, 16.0), (60.0, 20.0))), "solid"))
    problem = mbb(30, 20, "density", 1.5, passive=passive, symmetry=("x",),
                  optimizer=Optimizer("oc", 0.2, 15, 0.01))
    result = optimize(problem)
    grid = problem.grid
    assert np.all(result.density[passive[0].where.elements(grid)] == 0.0)
    assert np.all(result.density[passive[1].where.elements(grid)] == 1.0)
    image = grid.image(result.density)
    assert np.allclose(image, image[:, ::-1])
