"""solver='auto' above the size threshold: the direct solver wherever PARDISO's analysis says
its factor fits half the available memory, out of core where only its working set does, the
iterative path beyond; the result says which and why.
The threshold is lowered so that a small solid exercises the rule."""
import sys
from pathlib import Path

import numpy as np
import pytest
from flexfem.fem import Fixed, Force, Material, Model, linsolve, solve_static, solver_choice
from flexfem.fem.boundary import constrained_dofs
from flexfem.fem.budget import MEMORY_VARIABLE
from flexfem.fem.model import Solid3D

sys.path.insert(0, str(Path(__file__).parent))
from meshes import beam_3d  # noqa: E402

STEEL = Material("steel", E=200e9, nu=0.3, rho=7800.0)
pytestmark = pytest.mark.skipif(linsolve.direct_backend("spd") != "mkl-pardiso",
                                reason="the factor's size comes from PARDISO's analysis")


@pytest.fixture(scope="module")
def solid():
    return Model(beam_3d(0.1, 0.01, 0.01, 0.004), STEEL, Solid3D(), order=2)


def _solve(model):
    return solve_static(model, [Fixed("fixed")], [Force("tip", (0.0, -10.0, 0.0))])


def test_the_factor_is_measured_before_it_is_made(solid):
    K = linsolve.block_to_factorize(solid.stiffness_upper, np.arange(solid.n_dofs), "spd",
                                    upper=True)
    small = linsolve.factor_bytes(K[:3000][:, :3000])
    whole = linsolve.factor_bytes(K)
    assert 0 < small < whole < 2**31  # a few MiB for some 10^4 unknowns


def test_auto_keeps_the_direct_solver_where_its_factor_fits(solid, monkeypatch):
    monkeypatch.setitem(solver_choice.AMG_THRESHOLD, 3, 100)
    result = _solve(solid)
    assert result.solver == "mkl-pardiso" and "fits half the available memory" in \
        result.info["solver_choice"]
    monkeypatch.setenv(MEMORY_VARIABLE, "1e-6")  # ~1 KiB: no factor fits
    K = linsolve.block_to_factorize(solid.stiffness_upper, np.arange(solid.n_dofs), "spd",
                                    upper=True)
    chosen, why = solver_choice.solver_choice(solid.n_dofs, 3, "auto", lambda: K)
    assert chosen == "amg" and "is above half the available memory" in why
    assert solver_choice.solver_choice(solid.n_dofs, 3, "direct", lambda: K) == ("direct",
                                                                            "asked for")


def test_auto_goes_out_of_core_where_only_the_working_set_fits(solid, monkeypatch):
    """A fake budget between PARDISO's out-of-core and in-core peaks: 'auto' keeps the
    direct solver, out of core, and says why; the static result names the backend."""
    monkeypatch.setitem(solver_choice.AMG_THRESHOLD, 3, 100)
    held = constrained_dofs(solid, [Fixed("fixed")])[0]
    I = np.setdiff1d(np.arange(solid.n_dofs), held)  # the static solve's free DOFs
    K = linsolve.block_to_factorize(solid.stiffness_upper, I, "spd", upper=True)
    in_core, out_of_core = linsolve.factor_memory(K)
    available = in_core + out_of_core  # half of it lies between the two
    chosen, why = solver_choice.solver_choice(len(I), 3, "auto", lambda: K, available=available)
    assert chosen == "direct" and "out of core (the factor on disk)" in why
    chosen, why = solver_choice.solver_choice(len(I), 3, "auto", lambda: K,
                                              available=1.5 * out_of_core)
    assert chosen == "amg" and "out of core its" in why
    monkeypatch.setenv(MEMORY_VARIABLE, str(available / 2**30))
    ooc_result = _solve(solid)
    monkeypatch.setenv(MEMORY_VARIABLE, "20")
    assert ooc_result.solver == "mkl-pardiso-ooc", ooc_result.info["solver_choice"]
    assert "out of core" in ooc_result.info["solver_choice"]
    monkeypatch.setenv(MEMORY_VARIABLE, str(available / 2**30))
    asked = solve_static(solid, [Fixed("fixed")], [Force("tip", (0.0, -10.0, 0.0))],
                         solver="direct")
    monkeypatch.setenv(MEMORY_VARIABLE, "20")
    assert asked.solver == "mkl-pardiso-ooc"
    assert asked.info["solver_choice"].startswith("asked for; ")
    assert "out of core (the factor on disk)" in asked.info["solver_choice"]
    direct = _solve(solid)
    assert direct.solver == "mkl-pardiso"
    assert np.abs(ooc_result.u - direct.u).max() <= 1e-10 * np.abs(direct.u).max()


def test_auto_takes_the_iterative_path_where_the_factorization_runs_out_of_memory(solid,
                                                                                monkeypatch):
    """A direct factorization that fails for memory (PARDISO's error -2, MemoryError) is
    retried by the iterative path under 'auto', and says so; a solver asked for by name
    keeps its error."""
    from flexfem.fem import static

    direct = _solve(solid)

    def out_of_memory(*args, **kwargs):
        raise MemoryError("PARDISO error -2: not enough memory")

    monkeypatch.setattr(static, "BlockFactorization", out_of_memory)
    result = _solve(solid)
    assert result.solver == "pmg-cg" and "ran out of memory" in result.info["solver_choice"]
    assert np.abs(result.u - direct.u).max() <= 1e-5 * np.abs(direct.u).max()
    with pytest.raises(MemoryError):
        solve_static(solid, [Fixed("fixed")], [Force("tip", (0.0, -10.0, 0.0))],
                     solver="direct")
