"""Regenerate examples/topopt/dbma_amplifier_robust.json and .npz: the DBMA-envelope amplifier
with min_hinge = the DBMA's b (0.6 mm), its constraints computed by flexfem's DBMA model, optimised
by the robust formulation and verified body-fitted (flexfem.studies.dbma.topopt_robust; docs/
topopt_amplifier.md). The report's quick mode reads these files; the full report reruns it.

    .venv/bin/python examples/topopt/dbma_amplifier.py [--state FOLDER] [--iterations N]

With --state the optimiser's state is saved there after every iteration (a rerun resumes);
--start FOLDER begins from the design and beta of another run's state there (of the same
grid) instead of the uniform start; --verify-only verifies the stored design again.
"""
import argparse
from pathlib import Path
import sys

import numpy as np

from flexfem.studies.dbma.topopt_robust import (ITERATIONS, dbma_limits, reverify, run_robust,
                                                write_stored)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--state", default=None, help="folder for the optimiser's state")
    parser.add_argument("--iterations", type=int, default=ITERATIONS)
    parser.add_argument("--start", default=None,
                        help="state folder of an earlier run (same grid) to begin from")
    parser.add_argument("--verify-only", action="store_true",
                        help="verify the stored design again (no optimisation)")
    args = parser.parse_args()
    if args.verify_only:
        for path in write_stored(reverify()):
            print(path)
        return
    limits = dbma_limits()
    print({k: v for k, v in limits.items() if k != "quarter"}, flush=True)

    def progress(it, objective, volume, change):
        print(f"{it:4d} u_out {objective:.5g} m, volume {volume:.3f}, change {change:.3f}",
              file=sys.stderr, flush=True)

    start = None
    if args.start:
        with np.load(Path(args.start) / "state.npz") as state:
            start = (state["z"], float(state["beta"]),
                     f"iteration {int(state['iteration'])} of an earlier run at beta "
                     f"{float(state['beta']):g}")
    run = run_robust(limits, out_dir=args.state, progress=progress, iterations=args.iterations,
                     start=start)
    for path in write_stored(run):
        print(path)


if __name__ == "__main__":
    main()
