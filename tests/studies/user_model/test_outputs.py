"""[outputs] and observations of groups: bodies, faces of bodies (stage.top, face(+x)), the
least-squares rotation, both models under the same names, the bridge amplifier's ratio
against its bending-and-axial closed form, a sweep over its angle, converge --metric R, and
the refusals of an unknown group, component or metric."""
import json
import math
from pathlib import Path
import shutil

import numpy as np
import pytest
import skfem

from flexfem.fem import FEMesh, Model, PlaneStress, Solid3D
from flexfem.fem.materials import material
from flexfem.geometry.mechanism.faces import face_point
from flexfem.geometry.user_model import load_spec, mesh_geometry
from flexfem.studies.cli import main
from flexfem.studies.user_model import analyze_model, evaluate
from flexfem.studies.user_model.observe import observe_continuum

EXAMPLES = Path(__file__).resolve().parents[3] / "examples" / "bodies"
BRIDGE = EXAMPLES / "bridge.toml"
GUIDE = EXAMPLES / "guide.toml"


def closed_form(l, t, a):
    """R of a bridge amplifier's leaf between guided blocks (bending and axial stiffness)."""
    return l**2 * math.sin(a) * math.cos(a) / (t**2 * math.cos(a) ** 2 + l**2 * math.sin(a) ** 2)


@pytest.fixture
def guide(tmp_path) -> Path:
    path = tmp_path / "guide.toml"
    shutil.copy(GUIDE, path)
    return path


def _with_outputs(path: Path, table: str) -> Path:
    path.write_text(path.read_text() + "\n[outputs]\n" + table)
    return path


# --- the least-squares rotation of a group -------------------------------------------------

def test_rotation_of_a_rigid_motion_is_exact_in_2d_and_3d():
    """A field t + omega x r gives omega back (linear fit), and a finite rotation by 0.5 rad
    gives 0.5 rad (the large-deflection fit), on a subdomain and on a face."""
    steel = material("structural_steel")
    mesh = skfem.MeshTri.init_tensor(*(np.linspace(0, 0.01, 5),) * 2)
    fe = FEMesh(mesh, boundaries={"right": mesh.facets_satisfying(lambda x: x[0] > 0.01 - 1e-9)},
                subdomains={"all": np.arange(mesh.t.shape[1])})
    model = Model(fe, steel, PlaneStress(0.01), order=2)
    theta = 2e-3
    u = model.basis.project(lambda x: np.array([1e-4 - theta * x[1], -3e-4 + theta * x[0]]))
    for group in ("all", "right"):
        o = observe_continuum(model, u, [group])[group]
        assert o["rz"] == pytest.approx(theta, rel=1e-9)
        assert o["ux"] != pytest.approx(0.0)
    c, s = math.cos(0.5), math.sin(0.5)
    u = model.basis.project(lambda x: np.array([c * x[0] - s * x[1] - x[0],
                                                s * x[0] + c * x[1] - x[1]]))
    assert observe_continuum(model, u, ["all"], large=True)["all"]["rz"] == pytest.approx(0.5)
    assert observe_continuum(model, u, ["all"])["all"]["rz"] != pytest.approx(0.5, rel=0.01)
    box = skfem.MeshTet.init_tensor(*(np.linspace(0, 0.01, 4),) * 3)
    solid = Model(FEMesh(box, subdomains={"all": np.arange(box.t.shape[1])}), steel,
                  Solid3D(), order=1)
    omega = np.array([1e-3, -2e-3, 3e-3])
    v = solid.basis.project(lambda x: np.array([omega[1] * x[2] - omega[2] * x[1],
                                                omega[2] * x[0] - omega[0] * x[2],
                                                omega[0] * x[1] - omega[1] * x[0]]))
    o = observe_continuum(solid, v, ["all"])["all"]
    assert [o["rx"], o["ry"], o["rz"]] == pytest.approx(omega.tolist(), rel=1e-9)


# --- faces of bodies ----------------------------------------------------------------------

def test_a_face_of_a_body_is_its_outline_on_that_side(guide):
    """stage.top: the facets of the stage's outline at its top y (and only those); a face is
    held, loaded and observed in both models."""
    text = guide.read_text().replace('group = "ground"        #', 'group = "ground.bottom" #')
    guide.write_text(text.replace('group = "stage"\nforce', 'group = "stage.face(+y)"\nforce'))
    _with_outputs(guide, 'lift = "stage.top.uy"\nturn = "stage.rz"\n')
    spec = load_spec(guide)
    mesh = mesh_geometry(spec)
    for name, axis, level in (("stage.top", 1, 0.048), ("ground.bottom", 1, -0.005),
                              ("stage.face(+y)", 1, 0.048)):
        mid = mesh.mesh.p[:, mesh.mesh.facets[:, mesh.boundaries[name]]].mean(axis=1)
        assert np.allclose(mid[axis], level, atol=1e-12)
        share = mesh.boundaries[name].size / mesh.boundaries[name.split(".")[0]].size
        assert 0 < share < 1
    results = {m: analyze_model(spec, model=m) for m in ("continuum", "beam")}
    assert set(results["continuum"]["outputs"]) == set(results["beam"]["outputs"])
    assert set(results["continuum"]["observations"]) == set(results["beam"]["observations"])
    # the beam model: a face is its rigid body's motion at the face's centroid
    beam, mech = results["beam"]["observations"], spec.mechanism
    body, top = beam["stage"], beam["stage.top"]
    (x_top, y_top), span = face_point(mech, "stage.top", "stage", 1, 1)
    x_c, y_c = mech.outline_centre("stage")
    assert span == pytest.approx((0.03, 0.0)) and y_top == pytest.approx(0.048)
    assert top["ux"] == pytest.approx(body["ux"] - body["rz"] * (y_top - y_c), rel=1e-9)
    assert top["uy"] == pytest.approx(body["uy"] + body["rz"] * (x_top - x_c), abs=1e-15)
    assert results["continuum"]["outputs"]["lift"] == pytest.approx(
        results["continuum"]["observations"]["stage.top"]["uy"])


def test_a_face_of_a_body_in_3d_is_a_face_of_its_solid(guide):
    """--dim 3: face(+z) is the body's top at z = depth, face(-x) its lateral face."""
    _with_outputs(guide, 'up = "stage.face(+z).uz"\nside = "stage.face(-x).ux"\n')
    spec = load_spec(guide, dim=3)
    mesh = mesh_geometry(spec, size_factor=4.0)
    top = mesh.mesh.p[:, mesh.mesh.facets[:, mesh.boundaries["stage.face(+z)"]]].mean(axis=1)
    assert np.allclose(top[2], 0.01) and np.all(top[1] > 0.04 - 1e-9)
    side = mesh.mesh.p[:, mesh.mesh.facets[:, mesh.boundaries["stage.face(-x)"]]].mean(axis=1)
    assert np.allclose(side[0], -0.015)


# --- refusals at load time -----------------------------------------------------------------

@pytest.mark.parametrize("expression, words", [
    ('"stag.ux"', ["'stag' is not a group", "did you mean 'stage'", "line"]),
    ('"stage.uxx"', ["'uxx' of 'stage' is not a component", "did you mean 'ux'"]),
    ('"stage.uz"', ["'uz' of 'stage' is not a component; components (2-D): ux, uy, rz"]),
    ('"stage.tpo.uy"', ["'stage.tpo' is not a group", "did you mean 'stage.top'"]),
    ('"stage / 2"', ["'stage' is a group; name its component"]),
    ('"stage.ux / Lx"', ["'Lx' is neither a parameter", "L, d, t"]),
    ('"stage.ux.ux"', ["'stage.ux' is not a group"]),
    ('"__import__(1)"', ["is neither a parameter"]),
    ('"exp(stage.ux)"', ["'exp' is neither a parameter", "nor a function (sqrt, sin, cos"]),
    ("3", ["must be an expression string"]),
])
def test_an_unknown_group_component_or_name_is_refused_with_the_line(guide, expression, words):
    _with_outputs(guide, f"k = {expression}\n")
    line = len(guide.read_text().splitlines())
    with pytest.raises(ValueError) as error:
        load_spec(guide)
    message = str(error.value)
    assert f"guide.toml line {line}: [outputs]" in message and "\n" not in message
    for word in words:
        assert word in message


def test_an_output_named_as_a_built_in_metric_is_refused(guide):
    _with_outputs(guide, 'h = "stage.ux"\n')
    with pytest.raises(ValueError, match="'h' is a built-in metric"):
        load_spec(guide)


def test_an_output_that_cannot_be_evaluated_says_why(guide):
    """A zero divisor (the ground does not move) leaves the output null with the reason."""
    _with_outputs(guide, 'bad = "stage.ux / ground.ux"\n')
    result = analyze_model(load_spec(guide), model="beam")
    assert result["outputs"]["bad"] is None
    assert "cannot be evaluated" in result["not_available"]["outputs.bad"]


# --- the bridge amplifier --------------------------------------------------------------------

@pytest.mark.parametrize("degrees", [3.0, 10.0])
def test_bridge_ratio_of_both_models_follows_the_closed_form(degrees):
    """Both models within 2 % of R = l^2 sin a cos a / (t^2 cos^2 a + l^2 sin^2 a): found
    (continuum, beam) / closed form = 0.9939, 1.0034 at 3 degrees, 0.9998, 0.9997 at 10."""
    a = math.radians(degrees)
    expected = closed_form(0.02, 0.0005, a)
    for model in ("continuum", "beam"):
        m = evaluate({"a": a}, model=model, file=str(BRIDGE))
        assert m["R_closed_form"] == pytest.approx(expected, rel=1e-12)
        assert m["R"] == pytest.approx(expected, rel=0.02), model
        # the output stays level: across its 4 mm its tilt moves it < 0.1 % of its stroke
        assert abs(m["tilt"]) * 0.004 < 1e-3 * abs(m["observed_out_top_uy"])
        assert m["observed_out_top_uy"] == pytest.approx(-m["observed_out_bottom_uy"], rel=1e-3)


def test_bridge_outputs_at_every_step_of_a_large_deflection_solve():
    """[analysis] steps: R at each load step. The secant ratio falls as the leaf's angle
    opens: a rigid leaf of length l, (l cos a - ux)^2 + (l sin a + uy)^2 = l^2, gives
    uy / ux = cot a - ux / (2 l sin^3 a) + O(ux^2). Found: the path is linear in the load,
    extrapolates to the linear R at zero load, and falls by 0.0264 at 10 N against 0.0248
    from the rigid-leaf kinematics (the leaves' own stretch adds to the angle's change)."""
    spec = load_spec(BRIDGE, {"analysis.steps": 3})
    result = analyze_model(spec, model="beam")
    nl, linear = result["nonlinear"], result["outputs"]["R"]
    path, factors = np.array(nl["outputs_path"]["R"]), np.array(nl["load_factors"])
    assert len(path) == len(factors) == 3 and nl["outputs"]["R"] == path[-1]
    slope, at_zero = np.polyfit(factors, path, 1)
    assert at_zero == pytest.approx(linear, rel=1e-4)
    a, ux = spec.constants["a"], nl["observations"]["input"]["ux"]
    assert linear - path[-1] == pytest.approx(ux / (2 * 0.02 * math.sin(a) ** 3), rel=0.15)


def test_bridge_angle_sweep_from_its_study_file(tmp_path, capsys):
    """examples/bodies/bridge_angle.toml (beam model): R falls with the angle and follows the
    closed form within 1 % over 2 to 30 degrees."""
    assert main(["sweep", str(EXAMPLES / "bridge_angle.toml"), "--out", str(tmp_path / "out"),
                 "--workers", "1", "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["cases"] == 6 and result["failed"] == 0
    rows = sorted(result["results"], key=lambda r: r["a"])
    ratios = [r["R"] for r in rows]
    assert ratios == sorted(ratios, reverse=True)
    for r in rows:
        assert r["R"] == pytest.approx(closed_form(0.02, 0.0005, r["a"]), rel=0.01)
    assert (tmp_path / "out" / "R_vs_a.png").exists()


def test_converge_metric_r_of_the_bridge(tmp_path, capsys):
    """flexfem converge --metric R: three levels of the continuum, the extrapolated R within
    0.1 % of the finest and within 1 % of the closed form (found: 5.5594 against 5.5595)."""
    assert main(["converge", str(BRIDGE), "--metric", "R", "--levels", "3", "--out",
                 str(tmp_path / "conv"), "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["extrapolated"] == pytest.approx(result["values"][-1], rel=1e-3)
    assert result["extrapolated"] == pytest.approx(closed_form(0.02, 0.0005, math.radians(10)),
                                                   rel=0.01)


def test_a_misspelt_metric_is_refused_before_any_case(tmp_path, capsys):
    shutil.copy(BRIDGE, tmp_path / "bridge.toml")
    study = tmp_path / "study.toml"
    study.write_text((EXAMPLES / "bridge_angle.toml").read_text().replace(
        'metric = "R"', 'metric = "Rr"'))
    assert main(["sweep", str(study), "--out", str(tmp_path / "out"), "--workers", "1"]) != 0
    err = capsys.readouterr().err
    assert "plots[0].metric = 'Rr' is no metric" in err and "did you mean 'R'?" in err
    assert not (tmp_path / "out" / "results.sqlite").exists()
    assert main(["converge", str(BRIDGE), "--metric", "R_closed", "--levels", "3",
                 "--out", str(tmp_path / "c")]) != 0
    assert "did you mean 'R_closed_form'?" in capsys.readouterr().err


def test_analyze_reports_the_outputs(capsys):
    assert main(["analyze", str(BRIDGE), "--model", "beam"]) == 0
    text = capsys.readouterr().out
    assert "output R = 5.5" in text and "observed 'out_top'" in text
    assert main(["analyze", str(BRIDGE), "--model", "beam", "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert set(result["outputs"]) == {"R", "R_closed_form", "tilt"}
