"""A user's flexure from its model file, against closed forms: the parallel guide's lateral
stiffness 24 E I / L^3, the cross-spring pivot's rotational stiffness (8 E I / L for leaves
joined where they cross, 2 E I / L for leaves passing each other), the guide's first natural
frequency; the same shape from .geo, STEP and .msh; --set overrides; the analyze command."""
import argparse
import json
import math
from pathlib import Path
import shutil

import pytest

from flexfem.geometry.user_model import load_spec
from flexfem.studies.balancing.pivots import cross_spring_stiffness
from flexfem.studies.engine.serialize import jsonable
from flexfem.studies.user_model import analyze_model, evaluate
from flexfem.studies.user_model import cli

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
GUIDE = EXAMPLES / "parallel_guide" / "guide.toml"
PIVOT = EXAMPLES / "cross_pivot" / "pivot.toml"
PIVOT3D = EXAMPLES / "cross_pivot" / "pivot3d.toml"
E, NU, W = 200e9, 0.3, 0.01  # structural_steel; out-of-plane thickness of the 2-D examples, m


def guide_stiffness(L, t, w=W):
    """Two fixed-guided leaves, Euler-Bernoulli: k = 2 * 12 E I / L^3, I = w t^3 / 12 (N/m)."""
    return 24 * E * (w * t**3 / 12) / L**3


def guide_bounds(L, t):
    """Range of k_FEM / k_beam for a guide whose leaves are built into elastic blocks.

    Root compliance lengthens each leaf by Delta L per end, 0 <= Delta L <= t / 2 (the leaf
    rotates a little inside the block): k ~ (L + 2 Delta L)^-3, softer by up to 1 - (1 + t/L)^-3
    (7.1 % at L/t = 40). Shear adds the fraction 12 E I / (kappa G A L^2) = 2 (1 + nu) / kappa
    (t/L)^2 (kappa = 5/6: 0.2 %). P2 triangles, two across a leaf, are stiff by < 1 %."""
    shear = 2 * (1 + NU) / (5 / 6) * (t / L) ** 2
    return (1 + t / L) ** -3 / (1 + shear), 1.01


def test_guide_lateral_stiffness_against_beam_theory():
    result = analyze_model(load_spec(GUIDE))
    L, t = result["parameters"]["L"], result["parameters"]["t"]
    assert L / t >= 40
    ratio = result["stiffness"]["stage"]["x"] / guide_stiffness(L, t)
    low, high = guide_bounds(L, t)
    assert low < ratio < high, ratio  # measured 0.943
    # the base takes the whole load; the stage hardly moves along y (~1e-5 of x)
    assert result["reactions"]["fixed"] == pytest.approx([-1.0, 0.0], abs=1e-6)
    u = result["mean_displacement"]["stage"]
    assert abs(u[1]) < 1e-4 * u[0] and result["mean_displacement"]["fixed"] == [0.0, 0.0]


def test_guide_error_is_the_root_effect_of_order_t_over_L():
    """Doubling L/t halves k_FEM / k_beam - 1 (an O(t/L) end effect, not a modelling error),
    and the linear extrapolation to t/L -> 0 recovers beam theory within 1 %."""
    r40, r80 = (evaluate({"L": L}, model=str(GUIDE))["stiffness_stage_x"]
                / guide_stiffness(L, 0.001) for L in (0.04, 0.08))
    assert 0.4 < (1 - r80) / (1 - r40) < 0.6, (r40, r80)  # measured 0.52
    assert 2 * r80 - r40 == pytest.approx(1.0, abs=0.01)  # measured 0.9975


def test_guide_first_frequency_against_rayleigh():
    """f1 = sqrt(k / m) / 2 pi with k the FEM stiffness and m the stage plus 13/35 of each
    fixed-guided leaf's mass (the kinetic energy of the static shape 3 s^2 - 2 s^3)."""
    result = analyze_model(load_spec(GUIDE))
    p, rho = result["parameters"], 7850.0
    stage = rho * W * (p["d"] + p["t"] + 2 * p["m"]) * p["hs"]
    leaf = rho * W * p["t"] * p["L"]
    k = result["stiffness"]["stage"]["x"]
    f1 = math.sqrt(k / (stage + 2 * 13 / 35 * leaf)) / (2 * math.pi)
    assert result["frequencies_hz"][0] == pytest.approx(f1, rel=0.01)  # measured 262.0 / 261.7 Hz
    assert len(result["frequencies_hz"]) == 3


def pivot_stiffness(metrics, arm, force=1.0):
    """K = M / theta: the couple M = F 2 arm on the stage's side faces, theta = (v_right -
    v_left) / (2 arm) from their mean displacements (N m/rad)."""
    theta = (metrics["mean_displacement_right_y"] - metrics["mean_displacement_left_y"]) / (2 * arm)
    return 2 * arm * force / theta


def joined_cross_stiffness(L, t, w=W):
    """Two leaves of length L crossing at their middles at 90 degrees and joined there (a 2-D,
    monolithic pivot): the joint does not move, so each side is two half-leaves (l = L/2)
    rotated about an end, 4 E I / l each; the two sides in series: K = 8 E I / L. (Leaves that
    pass each other bend uniformly instead: 2 E I / L, cross_spring_stiffness.)"""
    return 8 * E * (w * t**3 / 12) / L


def test_cross_pivot_against_beam_theory():
    """The joint (a rhombus of side ~t) stiffens and the four roots soften the pivot, both by
    O(t/L): within 3 t/L (5 % at L/t = 60); halving t halves the deviation, and the
    extrapolation to t/L -> 0 recovers 8 E I / L within 1 %."""
    spec = load_spec(PIVOT)
    L, t, arm = (spec.constants[k] for k in ("L", "t", "arm"))
    r60 = pivot_stiffness(evaluate(model=str(PIVOT)), arm) / joined_cross_stiffness(L, t)
    assert abs(r60 - 1) < 3 * t / L, r60  # measured 1.030
    thinner = evaluate({"t": t / 2}, model=str(PIVOT))
    r120 = pivot_stiffness(thinner, arm) / joined_cross_stiffness(L, t / 2)
    assert 0.4 < (r120 - 1) / (r60 - 1) < 0.7, (r60, r120)  # measured 0.56
    assert 2 * r120 - r60 == pytest.approx(1.0, abs=0.01)  # measured 1.003


def test_3d_cross_spring_pivot_against_wittrick():
    """The classic pivot in 3-D (leaves in two layers, not touching): K = 2 E I / L
    (cross_spring_stiffness, Wittrick 1948). End effects O(t/L) = 3 % at L/t = 30 (root
    compliance softens; the blocks clamp the leaves' anticlastic bending, stiffening by up to
    nu^2 ~ 9 % near the roots): within 5 %."""
    spec = load_spec(PIVOT3D)
    L, t, w, arm = (spec.constants[k] for k in ("L", "t", "w", "arm"))
    metrics = evaluate(model=str(PIVOT3D))
    ratio = pivot_stiffness(metrics, arm) / cross_spring_stiffness(E, w, t, L, 2)
    assert abs(ratio - 1) < 0.05, ratio  # measured 1.006
    assert metrics["h"] < 2 * t and metrics["dofs"] > 5000


def write_guide_step(path, L=0.04, t=0.001, d=0.02, hb=0.005, hs=0.008, m=0.005, z=0.0):
    """The default guide.geo outline, in the plane at height z (m), as a STEP file
    (OpenCASCADE, written in mm)."""
    import gmsh

    gmsh.initialize(readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")
        occ, e = gmsh.model.occ, d / 2 + t / 2 + m
        base = occ.addRectangle(-e, -hb, z, 2 * e, hb)
        stage = occ.addRectangle(-e, L, z, 2 * e, hs)
        leaves = [occ.addRectangle(x - t / 2, 0, z, t, L) for x in (-d / 2, d / 2)]
        occ.fuse([(2, base)], [(2, stage)] + [(2, s) for s in leaves])
        occ.synchronize()
        gmsh.write(str(path))
    finally:
        gmsh.finalize()


STEP_MODEL = """\
geometry = "guide.step"
dim = 2
[material]
name = "structural_steel"
[section]
kind = "plane_stress"
thickness = 0.01
[mesh]
size = 0.004
refine = [{ group = "leaves", size = 0.0005, distance = 0.0005 }]
[[select]]
group = "fixed"
dim = 1
where = "ymax < -0.004999"
[[select]]
group = "stage"
dim = 1
where = "ymin > 0.047999"
[[select]]
group = "leaves"
dim = 1
where = "ymin > -1e-6 and ymax < 0.040001 and xmax - xmin < 1e-6"
[[supports]]
group = "fixed"
[[loads]]
group = "stage"
force = [1.0, 0.0]
"""


def test_step_guide_matches_geo_guide(tmp_path):
    write_guide_step(tmp_path / "guide.step")
    (tmp_path / "guide.toml").write_text(STEP_MODEL)
    spec = load_spec(tmp_path / "guide.toml")
    assert spec.groups == {"fixed": 1, "stage": 1, "leaves": 1, "body": 2}
    step = analyze_model(spec)
    geo = analyze_model(load_spec(GUIDE))
    k = step["stiffness"]["stage"]["x"]
    assert k == pytest.approx(geo["stiffness"]["stage"]["x"], rel=0.02)
    low, high = guide_bounds(0.04, 0.001)
    assert low < k / guide_stiffness(0.04, 0.001) < high
    # a rule that selects nothing is named with its line
    (tmp_path / "guide.toml").write_text(STEP_MODEL.replace("ymax < -0.004999", "ymax < -1"))
    with pytest.raises(ValueError, match=r"guide.toml line 14: \[\[select\]\] group 'fixed' "
                                         r"\(where 'ymax < -1'\) matches no curve of .*guide.step"):
        load_spec(tmp_path / "guide.toml")


def test_2d_step_off_the_plane_is_refused(tmp_path):
    write_guide_step(tmp_path / "guide.step", z=0.01)
    (tmp_path / "guide.toml").write_text(STEP_MODEL)
    with pytest.raises(ValueError, match=r"guide.step: a 2-D model must lie in the plane z = 0"):
        analyze_model(load_spec(tmp_path / "guide.toml"))


def test_step_example_3d():
    """The committed 3-D STEP guide (L/t = 20, w = 3 t): within the root-compliance bound
    (softer by at most 1 - (1 + t/L)^-3 = 13.6 %); plate action (w/t = 3) stiffens by at most
    nu^2 / (1 - nu^2) = 9.9 %."""
    result = analyze_model(load_spec(EXAMPLES / "step_guide" / "guide_step.toml"))
    ratio = result["stiffness"]["stage"]["x"] / guide_stiffness(0.02, 0.001, w=0.003)
    assert 1 - 0.136 < ratio < 1.099, ratio  # measured 0.930


def test_msh_gives_the_geo_result(tmp_path):
    import gmsh

    gmsh.initialize(readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.merge(str(GUIDE.parent / "guide.geo"))
        gmsh.model.mesh.generate(2)
        gmsh.write(str(tmp_path / "guide.msh"))
    finally:
        gmsh.finalize()
    text = GUIDE.read_text().replace('"guide.geo"', '"guide.msh"')
    text = text.replace("L = 0.04\nt = 0.001\n", "")  # a mesh has no parameters
    text = text.split("# The reduced beam model")[0]  # nor the names its beams are drawn with
    (tmp_path / "guide.toml").write_text(text)
    from_msh = analyze_model(load_spec(tmp_path / "guide.toml"))
    from_geo = analyze_model(load_spec(GUIDE))
    assert from_msh["dofs"] == from_geo["dofs"]
    # the same mesh read back: equal up to the round-off of a solve, ~eps cond(K) (the
    # factorization's ordering follows the node numbering; measured 1.1e-9 to 1.6e-9)
    assert from_msh["stiffness"]["stage"]["x"] == pytest.approx(
        from_geo["stiffness"]["stage"]["x"], rel=1e-8)
    with pytest.raises(ValueError, match="guide.msh: a .msh mesh cannot be remeshed"):
        evaluate(model=str(tmp_path / "guide.toml"), size_factor=0.5)
    (tmp_path / "guide.toml").write_text(text.replace("order = 2", "order = 2\nsize = 0.001"))
    with pytest.raises(ValueError, match=r"guide.toml line 16: \[mesh\] size and refine need a "
                                         r"geometry to mesh; guide.msh is a finished mesh"):
        load_spec(tmp_path / "guide.toml")


def parser():
    p = argparse.ArgumentParser(prog="flexfem")
    cli.register(p.add_subparsers(dest="command", required=True))
    return p


def test_set_override_scales_as_one_over_L_cubed():
    """L 40 -> 50 mm: k ~ 1 / (L + 2 Delta L)^3, 0 <= Delta L <= t / 2, so k40 / k50 lies
    between (51/41)^3 = 1.925 and (50/40)^3 = 1.953."""
    base = parser().parse_args(["analyze", str(GUIDE)])
    longer = parser().parse_args(["analyze", str(GUIDE), "--set", "L=0.05", "--set",
                                  "analysis.modes=1"])
    k40 = base.run(base)["stiffness"]["stage"]["x"]
    result = longer.run(longer)
    assert result["parameters"]["L"] == 0.05 and len(result["frequencies_hz"]) == 1
    ratio = k40 / result["stiffness"]["stage"]["x"]
    assert (51 / 41) ** 3 * 0.995 < ratio < (50 / 40) ** 3 * 1.005, ratio  # measured 1.931


def test_analyze_command_json_and_summary():
    args = parser().parse_args(["analyze", str(GUIDE), "--json"])
    result = args.run(args)
    assert args.json
    assert {"dofs", "solver", "max_von_mises", "max_von_mises_location", "mean_displacement",
            "reactions", "frequencies_hz"} <= set(result)
    assert result["solver"] in ("mkl-pardiso", "cholmod", "superlu")  # a direct solver, named
    assert set(result["mean_displacement"]) == {"fixed", "stage"}
    json.dumps(jsonable(result))
    text = args.summarize(result)
    k = result["stiffness"]["stage"]["x"]
    assert f"stiffness of 'stage' along x: {k:.4g} N/m" in text
    assert "MPa" in text and " Hz" in text and "DOFs" in text
    with pytest.raises(ValueError, match="--set 'L0.05': write NAME=VALUE"):
        cli.parse_sets(["L0.05"])


def test_evaluate_metric_names():
    metrics = evaluate({"L": 0.04}, model=str(GUIDE), **{"analysis.modes": 2})
    assert set(metrics) == {
        "dofs", "h", "max_von_mises", "mean_displacement_fixed_x", "mean_displacement_fixed_y",
        "mean_displacement_stage_x", "mean_displacement_stage_y", "reaction_fixed_x",
        "reaction_fixed_y", "stiffness_stage_x", "f1_hz", "f2_hz", "stroke_limit_yield",
        "stroke_limit_fatigue"} | {f"observed_{g}_{c}" for g in ("fixed", "stage")
                                   for c in ("ux", "uy", "rz")}  # the groups' observations
    assert all(isinstance(v, float) for v in metrics.values())
    assert metrics["h"] < 0.002 and metrics["f1_hz"] < metrics["f2_hz"]
    with pytest.raises(ValueError, match="unknown option"):
        evaluate(model=str(GUIDE), modes=2)


def test_large_deflection_at_small_load_is_linear():
    result = analyze_model(load_spec(GUIDE, {"analysis.steps": 2, "analysis.modes": 1}))
    linear = result["mean_displacement"]["stage"][0]
    assert result["nonlinear"]["steps"] == 2
    assert result["nonlinear"]["mean_displacement"]["stage"][0] == pytest.approx(linear, rel=1e-3)


def test_under_supported_model_names_the_file(tmp_path):
    shutil.copy(GUIDE.parent / "guide.geo", tmp_path / "guide.geo")
    text = GUIDE.read_text().replace('group = "fixed"', 'group = "fixed"\ny = 0.0')
    (tmp_path / "guide.toml").write_text(text)
    with pytest.raises(ValueError, match=r"guide.toml: the supports leave .* rigid-body modes"):
        analyze_model(load_spec(tmp_path / "guide.toml"))


def test_doc_python_blocks_run(monkeypatch, capsys):
    """Every Python block of docs/model_files.md runs (from the repository root)."""
    import re

    doc = EXAMPLES.parent / "docs" / "model_files.md"
    blocks = re.findall(r"```python\n(.*?)```", doc.read_text(), re.S)
    assert len(blocks) >= 3
    monkeypatch.chdir(EXAMPLES.parent)
    for i, code in enumerate(blocks):
        exec(compile(code, f"{doc}:python block {i}", "exec"), {})
    out = capsys.readouterr().out
    assert "True" in out and "N/m, beam theory" in out and "L = 0.05 m" in out


def test_the_step_example_is_what_its_script_writes(tmp_path):
    """examples/step_guide/make_guide_step.py regenerates guide.step: the model file gives the
    same stiffness on the regenerated file as on the committed one."""
    import runpy
    import shutil
    script = runpy.run_path(str(EXAMPLES / "step_guide" / "make_guide_step.py"))
    script["write_guide_step"](str(tmp_path / "guide.step"))
    shutil.copy(EXAMPLES / "step_guide" / "guide_step.toml", tmp_path / "guide_step.toml")
    fresh = analyze_model(load_spec(tmp_path / "guide_step.toml"))
    committed = analyze_model(load_spec(EXAMPLES / "step_guide" / "guide_step.toml"))
    assert fresh["stiffness"]["stage"]["x"] == pytest.approx(
        committed["stiffness"]["stage"]["x"], rel=1e-6)
