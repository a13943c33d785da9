"""The optimiser's path is bit-for-bit reproducible: the same problem, run in two processes
that differ in what ran before it, ends in the same history and design. With MKL PARDISO the
single right-hand-side solves (the stress adjoint, the shift-invert eigen-solve) used to
differ in their last bits with MKL's threading layer (GNU OpenMP where libgomp was loaded
before MKL's first call, e.g. by gmsh; Intel's otherwise), and the path with them
(topopt/solver.py: iparm[33])."""
import ctypes.util
import os
import subprocess
import sys

import numpy as np
import pytest

RUN = """
import sys
import numpy as np
import scipy.sparse as sp
if sys.argv[2] == "perturbed":
    # other work first: a PARDISO factorisation of another size, a threaded matmul
    from flexfem.fem.factor import factor
    n = 5000
    A = sp.diags([-np.ones(n - 1), 4 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1], format="csr")
    with factor(A + sp.diags(np.ones(n - 50), 50) + sp.diags(np.ones(n - 50), -50),
                   "spd") as solve:
        solve(np.ones(n))
    a = np.random.default_rng(1).random((400, 400))
    a @ a
from flexfem.topopt import optimize
from flexfem.topopt.amplifier import amplifier_problem
problem = amplifier_problem(800.0, 4.36e6, 4e7, 1e5, element=2e-3, iterations=30, radius=1.5,
                            fn_min=754.0, stress_max=655e6)
result = optimize(problem)
np.savez(sys.argv[1], history=result.history, design=result.design)
"""


def _run(path, how, env):
    subprocess.run([sys.executable, "-c", RUN, str(path), how], check=True,
                   env={**os.environ, **env}, timeout=300)
    return np.load(path)


@pytest.mark.skipif(ctypes.util.find_library("gomp") is None,
                    reason="GNU OpenMP (libgomp) is not installed: MKL's GNU threading layer "
                           "cannot be chosen")
def test_the_amplifiers_path_does_not_depend_on_what_ran_before(tmp_path):
    """One process as it comes, one with MKL on GNU OpenMP (as after `import gmsh`) and other
    work before the optimisation: the same 30 iterations, to the last bit."""
    first = _run(tmp_path / "first.npz", "plain", {})
    second = _run(tmp_path / "second.npz", "perturbed", {"MKL_THREADING_LAYER": "GNU"})
    assert len(first["history"]) == len(second["history"]) == 30
    for key in ("history", "design"):
        difference = np.max(np.abs(first[key] - second[key]))
        assert np.array_equal(first[key], second[key]), f"{key} differs by {difference:.2e}"
