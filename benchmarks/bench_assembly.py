"""3-D P2 stiffness assembly (the upper triangle the solvers read, node pattern included)
of this checkout against an earlier revision's fem/assembly.py, side by side in one process
on the same mesh, the order of the two alternated. Not a test: prints one JSON line.

    .venv/bin/python benchmarks/bench_assembly.py --cells 96 4 96 --thickness 0.042  # 1M DOFs
    .venv/bin/python benchmarks/bench_assembly.py --baseline 4d13785 --repeats 3

The earlier module is read with ``git show REV:fem/assembly.py`` and imported as a module of
its own; its full CSR stiffness is cut to its upper triangle (``symmetric.upper``) as the model
did then. Both start from the same vector basis (its DOF numbering is not timed). The mesh:
a plate 1 x T x 1 m of structured tetrahedra, 6 per cell.
"""
import argparse
import importlib.util
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]


def earlier_assembly(revision: str):
    """fem/assembly.py at ``revision`` as a module (its relative imports replaced)."""
    source = subprocess.run(["git", "show", f"{revision}:fem/assembly.py"], cwd=REPO,
                            capture_output=True, text=True, check=True).stdout
    source = source.replace("from .symmetric import", "from flexfem.fem.symmetric import")
    path = Path(tempfile.mkdtemp()) / "earlier_assembly.py"
    path.write_text(source)
    spec = importlib.util.spec_from_file_location("earlier_assembly", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cells", nargs=3, type=int, default=[64, 4, 64])
    parser.add_argument("--thickness", type=float, default=0.0625)
    parser.add_argument("--baseline", default="4d13785", help="the earlier revision")
    parser.add_argument("--repeats", type=int, default=2)
    args = parser.parse_args(argv)

    import skfem
    from flexfem.fem import FEMesh, Material, Model, Solid3D, assembly, symmetric
    from flexfem.fem.model import scalar_element

    earlier = earlier_assembly(args.baseline)
    nx, ny, nz = args.cells
    mesh = skfem.MeshTet.init_tensor(np.linspace(0, 1, nx + 1),
                                     np.linspace(0, args.thickness, ny + 1),
                                     np.linspace(0, 1, nz + 1))
    model = Model(FEMesh(mesh, {}, {}), Material("steel", E=200e9, nu=0.3, rho=7800.0),
                  Solid3D(), order=2)
    element, quadrature = scalar_element(mesh, 2), model.stiffness_quadrature
    lam, mu = model.lame
    nodes = assembly.node_dofs(model.basis.element_dofs, 3)
    n_nodes = model.n_dofs // 3

    def run_earlier():
        pattern = earlier.node_pattern(nodes, n_nodes)
        t = time.perf_counter()
        K = symmetric.upper(earlier.elasticity_stiffness(mesh, element, quadrature, pattern, 3,
                                                         lam, mu, 1.0))
        return K, t

    def run_this():
        pattern = assembly.node_pattern(nodes, n_nodes)
        t = time.perf_counter()
        return assembly.elasticity_stiffness_upper(mesh, element, quadrature, pattern, 3,
                                                   lam, mu, 1.0), t

    times = {"earlier": [], "this": []}
    stiffness_times = {"earlier": [], "this": []}
    for repeat in range(args.repeats):
        order = [("earlier", run_earlier), ("this", run_this)]
        for name, run in (order if repeat % 2 == 0 else order[::-1]):
            start = time.perf_counter()
            K, after_pattern = run()
            end = time.perf_counter()
            times[name].append(end - start)
            stiffness_times[name].append(end - after_pattern)
            if name == "earlier":
                K_earlier = K
            else:
                K_this = K
            del K
    difference = abs(K_this - K_earlier).max() / abs(K_earlier).max()
    best = {name: min(v) for name, v in times.items()}
    print(json.dumps({"n_dofs": int(model.n_dofs), "tetrahedra": int(mesh.t.shape[1]),
                      "baseline": args.baseline, "pattern_and_K_s": times,
                      "K_s": stiffness_times, "speedup": best["earlier"] / best["this"],
                      "max_abs_dK_over_max_abs_K": float(difference)}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
