"""Convergence studies: observed order, Richardson extrapolation, GCI, the coarsest level
within a tolerance, on pure power laws (exact) and on the toy cantilever (known order 2)."""
import json
import math

import pytest
from flexfem.studies.cli import main
from flexfem.studies.engine.convergence import (
    coarsest_within,
    converge,
    default_levels,
    observed_order,
    parse_tolerance,
    plot_convergence,
    richardson_extrapolate,
)
from flexfem.studies.run import run_convergence
from flexfem.studies.toy.model import CantileverParams, tip_deflection_exact
from flexfem.studies.toy.model import evaluate as toy_evaluate
from flexfem.studies.toy.report import reproduce


def power_law(f_exact, c, p):
    """evaluate(params, h) -> f_exact + c h^p: a sequence on which Richardson is exact."""
    def evaluate(params, h):
        return {"f": f_exact + c * h**p, "h": h, "dofs": round(1 / h**2)}
    return evaluate


@pytest.mark.parametrize("p", [1.0, 1.5, 2.0, 4.0])
def test_pure_power_law_gives_exact_order_and_extrapolation(p):
    levels = [{"h": 0.1 / 2**k} for k in range(4)]
    result = converge(power_law(3.0, 0.7, p), "f", levels, tol=1e-3)
    # only round-off separates the estimates from the truth: |f - f_exact| >= 0.7 * 0.0125^4
    assert result.order == pytest.approx(p, abs=1e-6)
    assert result.extrapolated == pytest.approx(3.0, rel=1e-12)
    assert result.behaviour == "monotone"
    expected = coarsest_within([3.0 + 0.7 * lv["h"] ** p for lv in levels], 3.0, 1e-3)
    assert result.coarsest_within_tol == expected


def test_non_constant_refinement_ratio_is_solved_exactly():
    # Celik et al. eq. (3): with r_cm != r_mf the order needs the fixed-point iteration
    h = [1 / 5, 1 / 7, 1 / 11]
    f = [2.0 - 0.3 * hi**2 for hi in h]
    p = observed_order(*f, r_cm=h[0] / h[1], r_mf=h[1] / h[2])
    assert p == pytest.approx(2.0, abs=1e-8)
    assert richardson_extrapolate(f[1], f[2], h[1] / h[2], p) == pytest.approx(2.0, rel=1e-12)


def test_toy_uniform_beam_extrapolates_to_the_closed_form():
    # uniform beam: the trapezoid error is exactly delta h^2 / (2 L^2), a pure power law
    result = converge(toy_evaluate, "tip_deflection", default_levels(4))
    exact = tip_deflection_exact(CantileverParams())
    assert result.order == pytest.approx(2.0, abs=1e-6)
    assert result.extrapolated == pytest.approx(exact, rel=1e-10)


def test_toy_taper_observed_order_is_two():
    # tapered beam: the integrand is not polynomial, the error is h^2 + O(h^4); on 8..64
    # elements the observed order must be within 0.1 of the trapezoid rule's 2
    taper = {"thickness_tip_m": 0.001}
    result = converge(toy_evaluate, "tip_deflection", default_levels(4), params=taper, tol="0.5%")
    exact = tip_deflection_exact(CantileverParams(**taper))
    assert abs(result.order - 2.0) < 0.1
    # the GCI error band (safety factor 1.25) must contain the exact value
    assert abs(result.extrapolated - exact) <= result.error_estimate
    assert result.coarsest_within_tol == 0  # 8 elements are within 0.5 % already
    # sized by dofs (n + 1 nodes in 1-D) the order is still close to 2
    by_dofs = converge(toy_evaluate, "tip_deflection", default_levels(4), params=taper,
                       mesh_size_key="dofs", dim=1)
    assert abs(by_dofs.order - 2.0) < 0.1 and by_dofs.size_key == "dofs"


def test_oscillating_diverging_and_exact_sequences_are_flagged():
    def sequence(values):
        def evaluate(params, level):
            return {"f": values[level], "h": 2.0 ** -level}
        return [{"level": i} for i in range(len(values))], evaluate

    levels, ev = sequence([1.0, 1.4, 1.3, 1.325])
    assert converge(ev, "f", levels).behaviour == "oscillatory"
    levels, ev = sequence([1.0, 1.1, 1.3, 1.7])
    diverging = converge(ev, "f", levels)
    assert diverging.behaviour == "divergent" and math.isnan(diverging.error_estimate)
    levels, ev = sequence([1.0, 2.0, 2.0, 2.0])
    assert converge(ev, "f", levels).behaviour == "exact"


def test_bad_inputs_raise_value_errors():
    ev = power_law(1.0, 1.0, 2.0)
    with pytest.raises(ValueError, match=">= 3"):
        converge(ev, "f", [{"h": 0.1}, {"h": 0.05}])
    with pytest.raises(ValueError, match="refine"):
        converge(ev, "f", [{"h": 0.1}, {"h": 0.2}, {"h": 0.05}])
    with pytest.raises(ValueError, match="metric"):
        converge(ev, "g", [{"h": 0.1}, {"h": 0.05}, {"h": 0.025}])
    with pytest.raises(ValueError, match="'h'"):
        converge(lambda params, h: {"f": h}, "f", [{"h": 0.1}, {"h": 0.05}, {"h": 0.025}])
    with pytest.raises(ValueError, match="levels"):
        default_levels(2)


@pytest.mark.parametrize("text, value", [("0.5%", 0.005), (" 2 % ", 0.02), ("0.005", 0.005), (0.01, 0.01)])
def test_tolerance_accepts_percent_and_fraction(text, value):
    assert parse_tolerance(text) == pytest.approx(value, rel=1e-15)


@pytest.mark.parametrize("text", ["abc", 0, "150%", "-1%", 1.0])
def test_tolerance_rejects_nonsense(text):
    with pytest.raises(ValueError, match="tol"):
        parse_tolerance(text)


def test_converge_command_and_plot(tmp_path, capsys):
    assert main(["converge", "toy", "--metric", "tip_deflection", "--tol", "0.5%", "--levels", "5",
                 "--params", '{"thickness_tip_m": 0.001}', "--out", str(tmp_path), "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["tol"] == 0.005 and len(result["values"]) == 5
    assert abs(result["order"] - 2.0) < 0.1
    assert (tmp_path / "convergence_tip_deflection.png").read_bytes()[:4] == b"\x89PNG"
    assert main(["converge", "toy", "--metric", "tip_deflection", "--out", str(tmp_path)]) == 0
    assert "observed order 2 (" in capsys.readouterr().out
    assert main(["converge", "toy", "--metric", "nope", "--out", str(tmp_path)]) == 2
    assert "nope" in capsys.readouterr().err


def test_run_convergence_and_plot_by_dofs(tmp_path):
    summary = run_convergence("toy", "root_stress", tol=0.01, n_levels=3, out_dir=tmp_path)
    assert summary["behaviour"] == "exact"  # root stress does not depend on the mesh
    result = converge(power_law(1.0, 1.0, 2.0), "f", [{"h": 0.1 / 2**k} for k in range(4)],
                      mesh_size_key="dofs")
    assert result.order == pytest.approx(2.0, abs=0.05)  # dofs rounded to integers
    assert plot_convergence(result, tmp_path / "d.png", 2.0).stat().st_size > 5000


def test_reproduce_quick_writes_its_files_and_agrees_with_theory(tmp_path, section_contract):
    summary = reproduce(tmp_path, quick=True)
    section_contract(tmp_path, summary)
    rows = {row["quantity"]: row for row in summary["comparisons"]}
    # 8 elements: the trapezoid excess is exactly 1/(2 * 8^2) = 0.78125 %
    tip = rows["toy tip deflection, L = 0.1 m, 8 elements"]
    assert tip["difference"] == pytest.approx(1 / 128, rel=1e-9) and tip["verdict"] == "agrees"
    assert abs(rows["toy taper, observed convergence order"]["difference"]) < 0.05
    assert abs(rows["toy taper, Richardson-extrapolated tip deflection"]["difference"]) < 1e-6


def test_run_convergence_starts_from_the_mechanisms_coarsest_level():
    from flexfem.studies.mechanisms import coarsest_size_factor
    assert coarsest_size_factor("dbma") > 1.0  # the FEM mechanisms start coarser than default
    summary = run_convergence("toy", "tip_deflection", n_levels=3, start=2.0)
    assert [level["size_factor"] for level in summary["levels"]] == [2.0, 1.0, 0.5]
    with pytest.raises(ValueError, match="start"):
        run_convergence("toy", "tip_deflection", n_levels=3, start=0.0)


def test_levels_that_agree_within_noise_are_converged_not_nan(capsys):
    """Round-off on a converged metric makes the observed order meaningless: the study says
    it converged within the spread and recommends the coarsest level, with no nan printed."""
    noise = [1e-10, -3e-10, 2e-10, -1e-10]

    def evaluate(params, h):
        return {"f": 2.0 * (1 + noise[int(round(-math.log2(h)))]), "h": h}

    result = converge(evaluate, "f", [{"h": 2.0 ** -k} for k in range(4)], tol=0.005)
    assert result.behaviour == "converged" and result.coarsest_within_tol == 0
    assert result.extrapolated == pytest.approx(2.0, rel=1e-9) and result.gci < 1e-9
    from flexfem.studies.run_cli import summarize_convergence
    text = summarize_convergence({"mechanism": "noise", **result.to_dict()})
    assert "converged within" in text and "order not measurable" in text and "nan" not in text
    assert "coarsest level within 0.5 %: 0 (h 1)" in text


def test_a_progress_line_per_level():
    import io

    from flexfem.studies.engine.convergence import converge, default_levels
    from flexfem.studies.mechanisms import get_evaluator

    stream = io.StringIO()
    converge(get_evaluator("toy"), "tip_deflection", default_levels(3), progress=stream)
    lines = stream.getvalue().splitlines()
    assert [line.split(" (")[0] for line in lines] == ["level 1/3", "level 2/3", "level 3/3"]
    assert all("DOFs, tip_deflection = " in line for line in lines)


def _synthetic(values):
    """An evaluate returning ``values`` level by level, h halving from 1."""
    from flexfem.studies.engine.convergence import converge, default_levels

    def evaluate(params, size_factor):
        return {"h": size_factor, "f": values[round(-math.log2(size_factor))]}

    return converge(evaluate, "f", default_levels(len(values)))


def test_a_sequence_that_goes_down_and_up_is_not_monotone():
    result = _synthetic([10.0, 9.0, 9.5, 9.6])  # the last three alone look monotone
    assert result.behaviour == "oscillatory"


def test_a_singular_stress_is_not_extrapolated():
    """A stress at a sharp re-entrant corner grows as h^-0.46: the changes grow and no order or
    extrapolation is reported; a quantity converging at order 2 is extrapolated."""
    singular = _synthetic([2.0 ** (0.455 * k) for k in range(4)])
    assert singular.behaviour == "divergent" and math.isnan(singular.error_estimate)
    slow = _synthetic([1 + 2.0 ** (-0.3 * k) for k in range(4)])  # order 0.3
    assert slow.behaviour == "divergent"
    smooth = _synthetic([1 + 4.0 ** -k for k in range(4)])
    assert smooth.behaviour == "monotone" and smooth.order == pytest.approx(2.0)
    assert smooth.extrapolated == pytest.approx(1.0)
