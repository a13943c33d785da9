"""Time flexfem.topopt on 200 x 100 grids beside a port of top88 (tests/topopt/top88_port.py)
at the same settings. Not a test: prints one JSON line a row (wall and CPU times in seconds,
the load average at its start and end: on a shared machine read the times beside the load).

    .venv/bin/python benchmarks/bench_topopt.py                    # 300 iterations a row
    .venv/bin/python benchmarks/bench_topopt.py --iterations 50 --rows mbb-flexfem mbb-top88

Rows: the MBB beam (volume 0.5, SIMP p = 3, sensitivity filter of radius 3 elements, OC with
move 0.2) by flexfem and by the port, each made to run exactly ``--iterations`` iterations;
the force inverter (volume 0.3, density filter of radius 3, MMA with move 0.2) by flexfem and
by the educational-style port (tests/topopt/inverter_port.py: top88's loop, spsolve, mmapy's
``mmasub`` as the MMA codes call it); the inverter by the robust formulation
(inverter-robust: three designs an iteration, docs/topopt_robust.md), printed with its time
over the plain inverter's of the same run. Each row runs in its own process, after its imports.
"""
import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
NELX, NELY, RMIN = 200, 100, 3.0


def _timed(run) -> dict:
    """run() -> (iterations, objective), timed: seconds (wall), cpu_seconds (this process,
    all its threads) and the load average (1 min) at the start and the end."""
    load, start, cpu = os.getloadavg()[0], time.perf_counter(), time.process_time()
    iterations, objective = run()
    return {"seconds": time.perf_counter() - start, "cpu_seconds": time.process_time() - cpu,
            "iterations": iterations, "objective": float(objective),
            "load": [round(load, 2), round(os.getloadavg()[0], 2)]}


def timed_optimize(problem) -> dict:
    """flexfem's optimisation of ``problem``, :func:`_timed`."""
    from flexfem.topopt import optimize

    def run():
        result = optimize(problem)
        return result.iterations, result.history[-1, 0]
    return _timed(run)


def mbb_flexfem(iterations: int) -> dict:
    from flexfem.topopt import (Constraint, Grid, Load, Optimizer, Problem, Region, Response,
                                Support)
    problem = Problem(Grid(NELX, NELY, float(NELX), float(NELY)), Response("compliance"),
                      filter_kind="sensitivity", radius=RMIN,
                      supports=(Support(Region("edge", "left"), ("x",)),
                                Support(Region("point", (float(NELX), 0.0)), ("y",))),
                      loads=(Load(Region("point", (0.0, float(NELY))), (0.0, -1.0)),),
                      constraints=(Constraint(Response("volume"), upper=0.5),),
                      optimizer=Optimizer("oc", 0.2, iterations, 1e-12))
    return timed_optimize(problem)


def mbb_top88(iterations: int) -> dict:
    sys.path.insert(0, str(ROOT / "tests" / "topopt"))
    from top88_port import top88
    return _timed(lambda: top88(NELX, NELY, 0.5, 3.0, RMIN, 1, max_loop=iterations)[1::-1])


def inverter_problem(iterations: int, **options):
    """The 200 x 100 force inverter of the rows below (``options``: more Problem keys)."""
    from flexfem.topopt import (Constraint, Grid, Load, Optimizer, Problem, Region, Response,
                                Spring, Support)
    return Problem(Grid(NELX, NELY, float(NELX), float(NELY)),
                      Response("displacement", "output"), filter_kind="density", radius=RMIN,
                      supports=(Support(Region("edge", "bottom"), ("y",)),
                                Support(Region("box", ((0.0, NELY - 5.0), (0.0, float(NELY)))),
                                        ("x", "y"))),
                      loads=(Load(Region("point", (0.0, 0.0)), (1.0, 0.0)),),
                      springs=(Spring("input", Region("point", (0.0, 0.0)), "x", 0.1),
                               Spring("output", Region("point", (float(NELX), 0.0)), "x", 0.1)),
                      constraints=(Constraint(Response("volume"), upper=0.3),),
                      optimizer=Optimizer("mma", 0.2, iterations, 1e-12), **options)


def inverter_flexfem(iterations: int) -> dict:
    return timed_optimize(inverter_problem(iterations))


def inverter_robust(iterations: int) -> dict:
    """The inverter by the robust formulation (thresholds 0.75 / 0.5 / 0.25: three solves an
    iteration), projection from beta 1 doubling every 50 iterations to 16."""
    from flexfem.topopt import Projection
    from flexfem.topopt.robust import Robust
    return timed_optimize(inverter_problem(
        iterations, projection=Projection(1.0, 0.5, 16.0, 50), robust=Robust(0.25)))


def inverter_port(iterations: int) -> dict:
    sys.path.insert(0, str(ROOT / "tests" / "topopt"))
    from inverter_port import inverter88
    return _timed(lambda: inverter88(NELX, NELY, 0.3, 3.0, RMIN, iterations, clamp=5)[1::-1])


ROWS = {"mbb-flexfem": mbb_flexfem, "mbb-top88": mbb_top88, "inverter-flexfem": inverter_flexfem,
        "inverter-port": inverter_port, "inverter-robust": inverter_robust}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--iterations", type=int, default=300)
    parser.add_argument("--rows", nargs="+", choices=sorted(ROWS), default=list(ROWS))
    parser.add_argument("--row", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.row:
        print(json.dumps({"row": args.row, **ROWS[args.row](args.iterations)}))
        return
    times = {}
    for row in args.rows:
        out = subprocess.run([sys.executable, __file__, "--row", row, "--iterations",
                              str(args.iterations)], capture_output=True, text=True, check=True,
                             env={**os.environ, "PYTHONHASHSEED": "0"})
        line = json.loads(out.stdout.strip().splitlines()[-1])
        times[row] = line["seconds"]
        print(json.dumps(line), flush=True)
    for name, ours, port in (("mbb flexfem / port", "mbb-flexfem", "mbb-top88"),
                             ("inverter flexfem / port", "inverter-flexfem", "inverter-port"),
                             ("inverter robust / plain", "inverter-robust",
                              "inverter-flexfem")):
        if ours in times and port in times:
            print(json.dumps({name: times[ours] / times[port]}))


if __name__ == "__main__":
    main()
