"""Geometrically nonlinear topology optimisation: the large-strain quad against theory and
against flexfem's continuum St. Venant-Kirchhoff assembly, the energy interpolation, the
adjoint gradient against finite differences, and a design that beats the small-displacement
one where its geometry changes."""
from pathlib import Path

import numpy as np
import pytest
import skfem
from skfem.helpers import grad

from flexfem.fem import hyperelastic
from flexfem.topopt import optimize
from flexfem.topopt.element import element_stiffness
from flexfem.topopt.grid import Grid
from flexfem.topopt.large_displacement import Nonlinear
from flexfem.topopt.large_strain import LargeStrainQ4, energy_gamma, interpolated
from flexfem.topopt.model import Discrete
from flexfem.topopt.problem_file import problem_from_dict, read_problem_file

LARGE = Path(__file__).parents[2] / "examples" / "topopt" / "inverter_large.toml"


@skfem.BilinearForm
def _skfem_tangent(du, v, w):
    """The large-deflection tangent as skfem's generic form (the grid element's reference)."""
    return np.einsum("ij...,ijkl...,kl...->...", grad(v), np.asarray(w.A), grad(du))


def _fd_columns(f, u, h=1e-6):
    """d f / d u (n, m, k) by central differences over the k columns of u (n, k)."""
    cols = []
    for j in range(u.shape[1]):
        du = np.zeros(u.shape[1])
        du[j] = h
        cols.append((f(u + du) - f(u - du)) / (2 * h))
    return np.stack(cols, axis=-1)


def test_tangent_is_the_derivative_of_the_force_and_linear_at_rest():
    el = LargeStrainQ4(2e-3, 1e-3, 0.3, 5e-4)
    u = np.random.default_rng(0).normal(size=(4, 8)) * 2e-4
    _, K, _ = el.force_tangent(u)
    fd = _fd_columns(lambda v: el.force_tangent(v)[0], u, h=1e-10)
    assert np.max(np.abs(K - fd)) <= 1e-6 * np.max(np.abs(K))
    _, K0, det = el.force_tangent(np.zeros((1, 8)))
    KL = element_stiffness(2e-3, 1e-3, 1.0, 0.3, 5e-4)
    assert np.allclose(K0[0], KL, rtol=0, atol=1e-14 * np.abs(KL).max())
    assert det[0] == pytest.approx(1.0)


def test_a_rigid_rotation_carries_no_force():
    X = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 0.5], [0.0, 0.5]])
    th = 1.1
    R = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
    f, _, det = LargeStrainQ4(1.0, 0.5, 0.3, 1.0).force_tangent((X @ R.T - X).ravel()[None])
    assert np.max(np.abs(f)) < 1e-14
    assert det[0] == pytest.approx(1.0)


@pytest.mark.parametrize("stretch", [0.8, 1.3, 2.0])
def test_a_uniform_stretch_gives_the_st_venant_kirchhoff_force(stretch):
    # nu = 0: no lateral strain; S11 = E (s^2 - 1) / 2, P11 = s S11, over the height h, depth t
    dx, dy, t = 2.0, 0.5, 0.1
    X = np.array([[0.0, 0.0], [dx, 0.0], [dx, dy], [0.0, dy]])
    u = np.column_stack([(stretch - 1.0) * X[:, 0], np.zeros(4)]).ravel()[None]
    f, _, _ = LargeStrainQ4(dx, dy, 0.0, t).force_tangent(u)
    right = f[0].reshape(4, 2)[[1, 2], 0].sum()
    assert right == pytest.approx(stretch * (stretch**2 - 1.0) / 2.0 * dy * t, rel=1e-12)


def test_the_grid_element_matches_flexfem_continuum_assembly():
    """The vectorised quad against fem/hyperelastic.py's skfem forms on the same quads."""
    nu, t = 0.3, 2e-3
    grid = Grid(3, 2, 3e-3, 1e-3)
    mesh = skfem.MeshQuad.init_tensor(np.linspace(0, grid.lx, 4), np.linspace(0, grid.ly, 3))
    basis = skfem.Basis(mesh, skfem.ElementVector(skfem.ElementQuad1()), intorder=2)
    # flexfem's grid node n at skfem's vertex with the same coordinates
    order = [int(np.argmin(np.hypot(*(mesh.p - xy[:, None])))) for xy in grid.nodes]
    dofs = basis.nodal_dofs[:, order]          # (2, n_nodes): skfem DOF of grid DOF (x, y)
    u_grid = np.random.default_rng(3).normal(size=grid.n_dofs) * 1e-4
    u_sk = np.zeros(basis.N)
    u_sk[dofs.T.ravel()] = u_grid
    lam, mu = nu / (1 - nu**2), 1 / (2 * (1 + nu))
    F = hyperelastic.deformation(basis, u_sk)
    S = hyperelastic.svk_stress(hyperelastic.green_lagrange(F), lam, mu)
    f_sk = hyperelastic._internal_force.assemble(basis, F=F, S=S, t=t)[dofs.T.ravel()]
    K_sk = _skfem_tangent.assemble(
        basis, A=t * hyperelastic.tangent_modulus(F, S, lam, mu)).toarray()
    K_sk = K_sk[np.ix_(dofs.T.ravel(), dofs.T.ravel())]
    el = LargeStrainQ4(grid.dx, grid.dy, nu, t)
    f_e, K_e, _ = el.force_tangent(u_grid[grid.edofs])
    f = np.bincount(grid.edofs.ravel(), weights=f_e.ravel(), minlength=grid.n_dofs)
    K = np.zeros((grid.n_dofs, grid.n_dofs))
    for e, d in enumerate(grid.edofs):
        K[np.ix_(d, d)] += K_e[e]
    assert np.max(np.abs(f - f_sk)) <= 1e-12 * np.max(np.abs(f_sk))
    assert np.max(np.abs(K - K_sk)) <= 1e-12 * np.max(np.abs(K_sk))


def test_energy_interpolation_is_linear_in_void_nonlinear_in_solid_and_differentiable():
    el = LargeStrainQ4(1.0, 1.0, 0.3, 1.0)
    KL = element_stiffness(1.0, 1.0, 1.0, 0.3, 1.0)
    u = np.random.default_rng(1).normal(size=(3, 8)) * 0.2
    void = interpolated(el, KL, u, np.zeros(3))[0]
    solid = interpolated(el, KL, u, np.ones(3))[0]
    assert np.allclose(void, u @ KL.T, atol=1e-14)
    assert np.allclose(solid, el.force_tangent(u)[0], atol=1e-14)
    gamma = np.array([0.2, 0.7, 0.95])
    _, Kt, dg = interpolated(el, KL, u, gamma)
    h = 1e-6
    fd = (interpolated(el, KL, u, gamma + h)[0] - interpolated(el, KL, u, gamma - h)[0]) / (2 * h)
    assert np.max(np.abs(dg - fd)) <= 1e-7 * np.max(np.abs(dg))
    fd_K = _fd_columns(lambda v: interpolated(el, KL, v, gamma)[0], u)
    assert np.max(np.abs(Kt - fd_K)) <= 1e-7 * np.max(np.abs(Kt))
    g, dgam = energy_gamma(np.array([0.0, 0.01, 0.3, 1.0]))
    assert g[0] == pytest.approx(0.0, abs=1e-12) and g[-1] == pytest.approx(1.0)
    assert g[2] == pytest.approx(1.0, abs=1e-12) and 0.4 < g[1] < 0.6


def _small_inverter(force: float, large: bool = True, stress: float | None = None):
    data = read_problem_file(LARGE)
    if stress is not None:
        data["constraint"].append({"kind": "stress", "max": stress, "pnorm": 8.0})
    data["domain"].update(nelx=20, nely=10, size=[40.0, 20.0])
    data["load"][0]["force"] = [force, 0.0]
    if large:
        data["nonlinear"] = {"steps": 5}
    else:
        del data["nonlinear"]
    return problem_from_dict(data)


def test_adjoint_gradient_matches_finite_differences_at_a_large_load():
    d = Discrete(_small_inverter(0.6))
    rng = np.random.default_rng(2)
    z = np.clip(0.25 + 0.6 * rng.random(d.n_variables), d.lower, d.upper)
    z[rng.choice(d.n_variables, 12, replace=False)] = 0.012   # near the energy switch
    ev = d.evaluate(z)
    assert ev.displacements["input"] > 0.1 * 40   # a large stroke: over 10 % of the length
    h = 1e-6
    for j in rng.choice(np.flatnonzero(d.upper > d.lower), 6, replace=False):
        zp, zm = z.copy(), z.copy()
        zp[j] += h
        zm[j] -= h
        fd = (d.evaluate(zp).objective - d.evaluate(zm).objective) / (2 * h)
        assert ev.objective_grad[j] == pytest.approx(fd, rel=1e-4, abs=1e-6 * np.abs(
            ev.objective_grad).max())


def test_stress_norm_gradient_matches_finite_differences_at_a_large_load():
    problem = _small_inverter(0.6, stress=0.05)
    d = Discrete(problem)
    rng = np.random.default_rng(4)
    z = np.clip(0.25 + 0.6 * rng.random(d.n_variables), d.lower, d.upper)
    ev = d.evaluate(z)
    h = 1e-6
    for j in rng.choice(np.flatnonzero(d.upper > d.lower), 6, replace=False):
        zp, zm = z.copy(), z.copy()
        zp[j] += h
        zm[j] -= h
        fd = (d.evaluate(zp).constraints[1] - d.evaluate(zm).constraints[1]) / (2 * h)
        assert ev.constraint_grads[1, j] == pytest.approx(fd, rel=1e-4, abs=1e-6 * np.abs(
            ev.constraint_grads[1]).max())


def test_small_loads_give_the_linear_design_state():
    z = np.full(Discrete(_small_inverter(1e-5)).n_variables, 0.4)
    a = Discrete(_small_inverter(1e-5, stress=1e-6)).evaluate(z)
    b = Discrete(_small_inverter(1e-5, large=False, stress=1e-6)).evaluate(z)
    assert a.objective == pytest.approx(b.objective, rel=1e-4)
    assert np.allclose(a.objective_grad, b.objective_grad, rtol=1e-3,
                       atol=1e-4 * np.abs(b.objective_grad).max())
    assert np.allclose(a.constraints, b.constraints, rtol=1e-4)
    assert np.allclose(a.constraint_grads, b.constraint_grads, rtol=1e-3,
                       atol=1e-4 * np.abs(b.constraint_grads).max())


@pytest.mark.parametrize("table, message", [
    ({"steps": 0}, "nonlinear.steps"), ({"steps": 2.5}, "nonlinear.steps"),
    ({"max_iterations": 1}, "nonlinear.max_iterations"), ({"tolerance": 1.0}, "tolerance"),
    ({"step": 3}, "unknown key 'step'")])
def test_bad_nonlinear_settings_are_named(table, message):
    data = read_problem_file(LARGE)
    data["nonlinear"] = table
    with pytest.raises(ValueError, match=message):
        problem_from_dict(data)


def test_responses_without_a_large_displacement_form_are_refused():
    data = read_problem_file(LARGE)
    data["constraint"].append({"kind": "frequency", "min": 1.0})
    with pytest.raises(ValueError, match="'frequency' is not available with large"):
        problem_from_dict(data)
    data = read_problem_file(LARGE)
    data["load"].append({"where": {"point": [0.0, 0.0]}, "force": [0.0, 1.0], "case": 2})
    with pytest.raises(ValueError, match="one load case only"):
        problem_from_dict(data)
    assert Nonlinear().steps == 10


@pytest.mark.slow
def test_the_large_displacement_design_beats_the_linear_one_where_the_geometry_changes(
        tmp_path):
    """Pedersen, Buhl & Sigmund (2001): a mechanism designed with small displacements loses
    output stroke under a large load; designed with large ones it keeps more of it."""
    problem = problem_from_dict(read_problem_file(LARGE))
    result = optimize(problem, out_dir=tmp_path)
    linear = optimize(problem_from_dict({k: v for k, v in read_problem_file(LARGE).items()
                                         if k != "nonlinear"}), out_dir=tmp_path / "linear")
    d = Discrete(problem)

    def large_output(density):
        E = problem.interpolation.modulus(density)
        state = d.large.equilibrium(E, density, problem.interpolation.derivative(density))
        return float(d.spring_vectors["output"] @ state.u)

    u_nl, u_lin = large_output(result.density), large_output(linear.density)
    assert u_nl == pytest.approx(result.summary()["u_out"], rel=1e-6)
    assert u_nl < u_lin < 0           # the inverter's output moves left: more is more negative
    assert u_nl / u_lin > 1.02
    start = result.summary()["large_displacements"]
    assert start["start_objective"] == pytest.approx(u_lin, rel=1e-6)
    assert start["start_iterations"] == linear.iterations


def test_a_solid_bar_against_the_closed_form_in_both_models():
    """A solid strip (nu = 0, one element deep: equal nodal forces are then the uniform
    traction) held at its left edge, pulled at its right edge against a spring
    to 1.25 times its length: F = E A (s^3 - s) / 2 + k (s - 1) L, in the density model and in
    the body-fitted shape's continuum Newton solve (verify_large)."""
    from shapely.geometry import box

    from flexfem.topopt.outline import Outline
    from flexfem.topopt.tolerance import body_fitted_tolerance
    from flexfem.topopt.verify import verify_large

    L, h, k, s = 10.0, 2.0, 0.05, 1.25
    F = h * (s**3 - s) / 2 + k * (s - 1) * L                 # E = 1, thickness 1
    problem = problem_from_dict({
        "domain": {"nelx": 10, "nely": 1, "size": [L, h]}, "material": {"E": 1.0, "nu": 0.0},
        "support": [{"where": {"edge": "left"}, "fix": ["x", "y"]}],
        "load": [{"where": {"edge": "right"}, "force": [F, 0.0]}],
        "spring": [{"name": "output", "where": {"edge": "right"}, "dof": "x", "stiffness": k}],
        "objective": {"kind": "displacement", "spring": "output", "sense": "max"},
        "constraint": [{"kind": "volume", "max": 1.0}], "optimizer": {"kind": "mma"},
        "nonlinear": {"steps": 5}, "filter": {"kind": "density", "radius": 1.5}})
    d = Discrete(problem)
    solid = np.ones(d.grid.n_elements)
    state = d.large.equilibrium(np.ones_like(solid), solid, np.zeros_like(solid))
    assert d.spring_vectors["output"] @ state.u == pytest.approx((s - 1) * L, rel=1e-9)
    assert body_fitted_tolerance(problem, solid, "output")["u"] == pytest.approx(
        (s - 1) * L, rel=1e-9)
    shape = verify_large(problem, Outline(box(0.0, 0.0, L, h), (), 0.0))
    assert shape["load_factor"] == pytest.approx(1.0)
    assert shape["large"]["output"] == pytest.approx((s - 1) * L, rel=1e-6)
    assert shape["small"]["output"] == pytest.approx(F / (h / L + k), rel=1e-6)
    assert shape["max_strain"] == pytest.approx((s**2 - 1) / 2, rel=1e-6)
    assert not shape["strain_valid"]                          # 28 %: beyond 5 %


def test_a_load_beyond_the_design_stops_with_one_line_and_keeps_the_start(tmp_path, capsys):
    """Ten times the example's force: no equilibrium for the start design; the command says
    where Newton stopped (exit 2) and the small-displacement optimum stays saved."""
    from flexfem.studies.cli import main

    text = LARGE.read_text().replace("force = [0.6, 0.0]", "force = [6.0, 0.0]")
    text = text.replace("nelx = 40", "nelx = 20").replace("nely = 20",
                                                         "nely = 10\nsize = [40.0, 20.0]")
    path = tmp_path / "too_large.toml"
    path.write_text(text)
    assert main(["topopt", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "no equilibrium beyond load factor" in err
    assert (tmp_path / "out" / "linear" / "state.npz").is_file()


def _toml(value) -> str:
    """A TOML value (inline table, array, string or number)."""
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{k} = {_toml(v)}" for k, v in value.items()) + " }"
    if isinstance(value, list):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    return f'"{value}"' if isinstance(value, str) else repr(value)


def test_the_command_checks_a_large_displacement_design_on_its_shape(tmp_path, capsys):
    """The example at 20 x 10 elements in SI units (40 x 20 mm of a 2 GPa, 1 mm sheet, the
    same force relative to E t) with [shape]: the body-fitted shape is solved with large
    displacements and the summary says how far it got and whether its strain is valid."""
    import json

    from flexfem.studies.cli import main

    data = read_problem_file(LARGE)
    E, t, s = 2e9, 1e-3, 1e-3                       # Pa, m, m per element of the example

    def scale(where):
        return {k: [[c * s for c in p] for p in v] if k == "box" else v
                for k, v in where.items()}

    lines = ["[domain]", "nelx = 20", "nely = 10", "size = [0.04, 0.02]", f"thickness = {t}",
             "[material]", f"E = {E}", "nu = 0.3", "[filter]", 'kind = "density"',
             "radius = 1.5", "[nonlinear]", "steps = 5", "[objective]", 'kind = "displacement"',
             'spring = "output"', 'sense = "min"', "[optimizer]", 'kind = "mma"',
             "max_iterations = 30", "[shape]", "rho = 1200.0", "yield_strength = 5e7"]
    for table, rows in (("support", data["support"]), ("load", data["load"]),
                        ("spring", data["spring"]), ("passive", data["passive"])):
        for row in rows:
            row = {**row, "where": scale(row["where"])}
            if table == "load":
                row["force"] = [row["force"][0] * E * t * s, 0.0]
            if table == "spring":
                row["stiffness"] = row["stiffness"] * E * t
            lines += [f"[[{table}]]"] + [f"{k} = {_toml(v)}" for k, v in row.items()]
    lines += ["[[constraint]]", 'kind = "volume"', "max = 0.3"]
    path = tmp_path / "large_mm.toml"
    path.write_text("\n".join(lines) + "\n")
    assert main(["topopt", str(path), "--json", "--out", str(tmp_path / "out")]) == 0
    result = json.loads(capsys.readouterr().out)
    large = result["shape"]["body_fitted_large"]
    assert 0 < large["load_factor"] <= 1 and large["max_strain"] > 0
    assert large["small"]["output"] < 0 and large["small"]["input"] > 0
    assert result["shape"]["tolerance"]["u"] == pytest.approx(result["u_out"], rel=1e-9)
