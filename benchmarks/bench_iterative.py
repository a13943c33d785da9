"""The iterative path (p-multigrid CG, fem/pmultigrid.py) against the direct solver (PARDISO)
on 3-D P2 plates and a thin-leaf mechanism: iterations, time and peak memory, each method in a
process of its own. Not a test: prints one JSON line per run and a table.

    .venv/bin/python benchmarks/bench_iterative.py --cases plate-141k guide-3d
    .venv/bin/python benchmarks/bench_iterative.py --cases plate-1M    # ~9 GB for the direct run
    .venv/bin/python benchmarks/bench_iterative.py --cases plate-141k --methods amg-p2

Methods: 'direct' (``solve_static(solver="direct")``: in core, or out of core where PARDISO's
analysis says only that fits, fem/budget.py's plan), 'direct-ooc' (the same, planned for a
memory that only out of core fits: PARDISO out of core forced), 'pmg' (``solver="amg"``: p-multigrid
CG on P2) and 'amg-p2' (smoothed-aggregation AMG-CG on the P2 matrix itself,
``linsolve.solve_amg``, the iterative path before p-multigrid). Plates: 1 x T x 1 m, clamped
on x = 0, a 100 N force through the thickness (-y) on x = 1 (a cantilever plate in bending);
structured tetrahedra, 6 per cell. guide-3d: examples/bodies/guide.toml extruded to 3-D
(``--dim 3``) at the mesh size factor named. Peak memory: ``getrusage`` of the process (the
mesh, K and the solve; PARDISO's factor included, it lives in the process).
"""
import argparse
import json
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
# solids: (cells along x, through the thickness, along z, thickness m); plates 1 x T x 1 m,
# blocks 1 m cubes (compact: the largest factor a DOF)
PLATES = {"plate-36k": (24, 2, 24, 0.042), "plate-141k": (48, 2, 48, 0.042),
          "plate-449k": (64, 4, 64, 0.0625), "plate-1M": (96, 4, 96, 0.042),
          "plate-2M": (136, 4, 136, 0.042),
          "block-47k": (12, 12, 12, 1.0), "block-1M": (34, 34, 34, 1.0)}
GUIDES = {"guide-3d": 1.0, "guide-3d-fine": 0.5}
CASES = list(PLATES) + list(GUIDES)
METHODS = ("direct", "direct-ooc", "pmg", "amg-p2")


def plate_problem(case: str):
    """(model, supports, loads) of a plate case."""
    import skfem
    from flexfem.fem import (FEMesh, Fixed, Force, Material, Model, Solid3D, facets_where)

    nx, ny, nz, thickness = PLATES[case]
    mesh = skfem.MeshTet.init_tensor(np.linspace(0, 1.0, nx + 1),
                                     np.linspace(0, thickness, ny + 1),
                                     np.linspace(0, 1.0, nz + 1))
    groups = {"fixed": facets_where(mesh, lambda x: np.isclose(x[0], 0.0)),
              "tip": facets_where(mesh, lambda x: np.isclose(x[0], 1.0))}
    fe = FEMesh(mesh, groups, {"body": np.arange(mesh.t.shape[1])})
    steel = Material("steel", E=200e9, nu=0.3, rho=7800.0)
    return Model(fe, steel, Solid3D(), order=2), [Fixed("fixed")], [Force("tip", (0.0, -100.0,
                                                                                 0.0))]


def guide_problem(case: str):
    """(model, supports, loads) of the 3-D leaf guide at the case's mesh size factor."""
    from flexfem.geometry.user_model import load_spec
    from flexfem.studies.user_model.analysis import build_model, supports_and_loads

    spec = load_spec(REPO / "examples" / "bodies" / "guide.toml", dim=3)
    model = build_model(spec, GUIDES[case])
    return (model, *supports_and_loads(spec))


def run_case(case: str, method: str) -> dict:
    """One method on one case, in this process: times (s), peak memory (MB), the largest
    displacement (m) and, for the iterative methods, the CG iterations."""
    from flexfem.fem import linsolve, solve_static
    from flexfem.fem.budget import MEMORY_VARIABLE
    from flexfem.fem.boundary import constrained_dofs, load_vector
    from flexfem.fem.static_result import rigid_body_dof_modes

    t = time.perf_counter()
    model, supports, loads = (plate_problem if case in PLATES else guide_problem)(case)
    out = {"case": case, "method": method, "n_dofs": int(model.n_dofs),
           "mesh_s": time.perf_counter() - t}
    t = time.perf_counter()
    K = model.stiffness_upper
    out["assemble_s"] = time.perf_counter() - t
    t = time.perf_counter()
    try:
        if method == "amg-p2":
            D, _, _ = constrained_dofs(model, supports)
            I = np.setdiff1d(np.arange(model.n_dofs), D)
            b = load_vector(model, loads)[I]
            x = linsolve.solve_amg(linsolve.block_to_factorize(K, I, "general", upper=True), b,
                                   rigid_body_dof_modes(model)[I])
            out["u_max_m"] = float(np.abs(x).max())
        else:
            if method.startswith("direct"):
                out.update(direct_plan(model, supports, K))
            if method == "direct-ooc" and "factor_gib" in out:
                # plan for a memory whose half lies between the two peaks: out of core
                os.environ[MEMORY_VARIABLE] = str(out["factor_gib"] + out["ooc_gib"])
            t = time.perf_counter()
            result = solve_static(model, supports, loads,
                                  solver="amg" if method == "pmg" else "direct")
            out["u_max_m"] = float(np.abs(result.u).max())
            out["solver"] = result.solver
            out["why"] = result.info["solver_choice"]
        out["solve_s"] = time.perf_counter() - t
    except Exception as error:  # AMG-CG's non-convergence, or out of memory
        out["error"] = f"after {time.perf_counter() - t:.1f} s: {type(error).__name__} {error}"
    out["peak_rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    return out


def direct_plan(model, supports, K) -> dict:
    """PARDISO's analysis of the free block (its own, untimed): the in-core and out-of-core
    peaks (GiB) and fem/budget.py's plan, which the direct solve follows."""
    from flexfem.fem import linsolve
    from flexfem.fem.boundary import constrained_dofs
    from flexfem.fem.budget import factor_plan

    I = np.setdiff1d(np.arange(model.n_dofs), constrained_dofs(model, supports)[0])
    t = time.perf_counter()
    need = linsolve.factor_memory(linsolve.block_to_factorize(K, I, "spd", upper=True))
    out = {"analysis_s": time.perf_counter() - t}
    if need is not None:
        out.update(factor_gib=need[0] / 2**30, ooc_gib=need[1] / 2**30)
        out["plan"], out["plan_why"] = factor_plan(*need)
    return out


def table(rows: list[dict]) -> str:
    lines = ["| case | DOFs | method | assembly s | solve s | peak MB | max abs u (m) | note |",
             "|---|---:|---|---:|---:|---:|---:|---|"]
    for r in rows:
        note = r.get("error") or r.get("why", "")
        lines.append(f"| {r['case']} | {r['n_dofs']:,} | {r.get('solver', r['method'])} | "
                     f"{r['assemble_s']:.1f} | {r.get('solve_s', float('nan')):.1f} | "
                     f"{r['peak_rss_mb']:.0f} | {r.get('u_max_m', float('nan')):.6e} | "
                     f"{note} |")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", nargs="+", choices=CASES, default=["plate-141k", "guide-3d"])
    parser.add_argument("--methods", nargs="+", choices=METHODS, default=["direct", "pmg"])
    parser.add_argument("--one", nargs=2, metavar=("CASE", "METHOD"), help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.one:
        print(json.dumps(run_case(*args.one)), flush=True)
        return 0
    rows = []
    for case in args.cases:
        for method in args.methods:
            done = subprocess.run([sys.executable, __file__, "--one", case, method],
                                  capture_output=True, text=True, cwd=REPO)
            line = done.stdout.strip().splitlines()[-1] if done.stdout.strip() else ""
            if not line.startswith("{"):
                print(done.stderr[-2000:], file=sys.stderr)
                continue
            print(line, flush=True)
            rows.append(json.loads(line))
    print(table(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main())
