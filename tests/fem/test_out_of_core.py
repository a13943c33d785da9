"""PARDISO out of core (its factor in files): the same solution as in core, the files in a
folder of their own that free() removes, and the choice by memory (fem/budget.py's
factor_plan) on fixed budgets, never on the machine's free memory."""
import os
import sys
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp
from flexfem.fem import Material, Model, SingularStiffness, linsolve
from flexfem.fem.budget import MEMORY_VARIABLE, factor_plan
from flexfem.fem.factor import factor
from flexfem.fem.model import Solid3D

sys.path.insert(0, str(Path(__file__).parent))
from meshes import beam_3d  # noqa: E402

needs_pardiso = pytest.mark.skipif(linsolve.direct_backend("spd") != "mkl-pardiso",
                                   reason="PARDISO's out-of-core mode")
MIB = 2**20


@pytest.fixture(scope="module")
def stiffness():
    """The free-DOF block of a 3-D P2 bar (about 13k unknowns; its factor ~35 MiB)."""
    model = Model(beam_3d(0.1, 0.01, 0.01, 0.003), Material("steel", E=200e9, nu=0.3,
                                                            rho=7800.0), Solid3D(), order=2)
    I = np.arange(300, model.n_dofs)  # the first 100 nodes held
    return linsolve.block_to_factorize(model.stiffness_upper, I, "spd", upper=True)


@needs_pardiso
def test_out_of_core_solves_as_in_core_and_removes_its_files(stiffness, tmp_path,
                                                             monkeypatch):
    monkeypatch.delenv("MKL_PARDISO_OOC_PATH", raising=False)
    b = np.random.default_rng(1).standard_normal((stiffness.shape[0], 2))
    with factor(stiffness, "spd", out_of_core=False) as F:
        assert F.backend == "mkl-pardiso"
        x_in = F.solve(b)
    with factor(stiffness, "spd", out_of_core=True, scratch=str(tmp_path)) as F:
        assert F.backend == "mkl-pardiso-ooc"
        (folder,) = list(tmp_path.iterdir())
        assert sum(f.stat().st_size for f in folder.iterdir()) > 5 * MIB  # the factor
        x_out = F.solve(b)
        assert np.array_equal(F.solve(b), x_out)  # solves again from the files
    assert list(tmp_path.iterdir()) == []  # free() removed the folder
    assert np.abs(x_out - x_in).max() <= 1e-10 * np.abs(x_in).max()
    assert "MKL_PARDISO_OOC_PATH" not in os.environ  # the environment as it was


@needs_pardiso
def test_the_factorization_goes_out_of_core_where_only_its_working_set_fits(
        stiffness, tmp_path, monkeypatch):
    in_core, out_of_core = linsolve.factor_memory(stiffness)
    assert 0 < out_of_core < in_core
    # half of this memory lies between the two peaks
    monkeypatch.setenv(MEMORY_VARIABLE, str((in_core + out_of_core) / 2**30))
    with linsolve.Factorization(stiffness, "spd", scratch=str(tmp_path)) as F:
        assert F.backend == "mkl-pardiso-ooc"
    monkeypatch.setenv(MEMORY_VARIABLE, str(2.1 * in_core / 2**30))
    with linsolve.Factorization(stiffness, "spd", scratch=str(tmp_path)) as F:
        assert F.backend == "mkl-pardiso"


def test_the_plan_by_memory_on_a_fixed_budget():
    gib = 2**30
    plan, why = factor_plan(8 * gib, 3 * gib, available=20 * gib)
    assert plan == "in-core" and "8.00 GiB" in why and "fits half" in why
    plan, why = factor_plan(17 * gib, 3 * gib, available=20 * gib)
    assert plan == "out-of-core" and "17.00 GiB" in why and "3.00 GiB in memory" in why
    plan, why = factor_plan(17 * gib, 11 * gib, available=20 * gib)
    assert plan == "iterative" and "11.00 GiB in memory too" in why
    assert factor_plan(17 * gib, None, available=20 * gib)[0] == "iterative"


def test_no_out_of_core_plan_under_an_address_space_limit_below_the_factor():
    """PARDISO's out-of-core mode fails under an address-space limit below its in-core
    factor (measured on the 1M-DOF cube): such a limit sends the plan to the iterative path,
    saying why; a limit above the factor, or none, keeps out of core."""
    gib = 2**30
    plan, why = factor_plan(17 * gib, 3 * gib, available=20 * gib, address_space=16 * gib)
    assert plan == "iterative" and "ulimit -v" in why and "16.00 GiB" in why
    assert factor_plan(17 * gib, 3 * gib, available=20 * gib,
                       address_space=18 * gib)[0] == "out-of-core"
    assert factor_plan(17 * gib, 3 * gib, available=20 * gib,
                       address_space=float("inf"))[0] == "out-of-core"
    assert factor_plan(8 * gib, 3 * gib, available=20 * gib, address_space=9 * gib)[0] == "in-core"


def test_out_of_core_is_refused_by_other_backends():
    A = sp.identity(4, format="csr")
    with pytest.raises(ValueError, match="out_of_core: PARDISO's mode only"):
        linsolve.Factorization(A, "spd", backend="superlu", out_of_core=True)


@needs_pardiso
def test_a_failed_out_of_core_factorization_raises_and_leaves_no_files(tmp_path):
    negative = -sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(300, 300), format="csr")
    with pytest.raises(SingularStiffness, match="not positive definite"):
        linsolve.Factorization(negative, "spd", out_of_core=True, scratch=str(tmp_path))
    assert list(tmp_path.iterdir()) == []


@needs_pardiso
@pytest.mark.parametrize("kind", ["symmetric", "general"])
def test_out_of_core_of_the_other_kinds(stiffness, kind, tmp_path):
    """The symmetric indefinite (shifted modal solves) and general kinds out of core."""
    A = stiffness - 1e-3 * abs(stiffness.diagonal()).mean() * sp.identity(stiffness.shape[0])
    A = sp.csr_matrix(A if kind == "symmetric" else A + sp.triu(A, 1).T)
    b = np.ones(A.shape[0])
    with linsolve.Factorization(A, kind, out_of_core=False) as F:
        x_in = F.solve(b)
    with linsolve.Factorization(A, kind, out_of_core=True, scratch=str(tmp_path)) as F:
        assert F.backend == "mkl-pardiso-ooc"
        x_out = F.solve(b)
    assert np.abs(x_out - x_in).max() <= 1e-10 * np.abs(x_in).max()


def test_the_memory_plan_keeps_within_the_address_space_limit():
    """Under ``ulimit -v`` the memory a plan counts on (and PARDISO's out-of-core budget) is
    at most what the limit leaves above the process, whatever else is free or asked for. Run
    in a process of its own under a fixed 3 GiB limit."""
    import subprocess

    code = ("import resource; resource.setrlimit(resource.RLIMIT_AS, (3 * 2**30, 3 * 2**30)); "
            "from flexfem.fem.budget import available_memory_bytes; "
            "size = next(int(l.split()[1]) * 1024 for l in open('/proc/self/status') "
            "if l.startswith('VmSize:')); "
            "print(available_memory_bytes(), size)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env={**os.environ, MEMORY_VARIABLE: "1000"})
    available, size = (int(v) for v in done.stdout.split())
    assert 0 < available <= 3 * 2**30 - size + 2**20  # the limit's, not the 1000 GiB asked
