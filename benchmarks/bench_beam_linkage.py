"""Time the beam models of the driving linkage and of the model-file examples beside the
continuum FEM of the same design and outputs, interleaved so that both see the same load.
Not a test: prints a table (and writes a JSON with ``--out``). Times are wall-clock on
whatever machine runs it; the ratios are what to read.

    .venv/bin/python benchmarks/bench_beam_linkage.py [--repeat 3] [--out bench.json]

Rows: the driving linkage's linear drive and 3 modes (beam model against the 2-D FEM at
size_factor 1.5, mesh included); the examples' parallel guide (static and 3 modes) and cross
pivot (static), `analyze_model(spec, model="beam")` against `analyze_model(spec)` (mesh
included).
"""
import argparse
import json
import os
import statistics
import time


def timed(fn):
    start = time.perf_counter()
    fn()
    return time.perf_counter() - start


def cases():
    from flexfem.geometry.user_model import load_spec
    from flexfem.studies.eightbar.driving_models import (analyze_driving_beam,
                                                         analyze_driving_continuum)
    from flexfem.studies.user_model import analyze_model

    guide = load_spec("examples/parallel_guide/guide.toml")
    pivot = load_spec("examples/cross_pivot/pivot.toml")
    return {
        "driving linkage, linear drive + 3 modes": (
            lambda: analyze_driving_beam(n_modes=3),
            lambda: analyze_driving_continuum(n_modes=3, size_factor=1.5)),
        "parallel guide (model file), static + 3 modes": (
            lambda: analyze_model(guide, model="beam"), lambda: analyze_model(guide)),
        "cross pivot (model file), static": (
            lambda: analyze_model(pivot, model="beam"), lambda: analyze_model(pivot)),
    }


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="interleaved runs of each")
    parser.add_argument("--out", help="write the rows as JSON here")
    args = parser.parse_args(argv)
    rows = []
    for name, (beam, continuum) in cases().items():
        beam()  # imports and caches (the default designs) out of the timing
        tb, tc, load = [], [], []
        for _ in range(args.repeat):
            load.append(os.getloadavg()[0])
            tb.append(min(timed(beam) for _ in range(3)))
            tc.append(timed(continuum))
        rows.append({"case": name, "beam_s": statistics.median(tb),
                     "continuum_s": statistics.median(tc),
                     "ratio": statistics.median(c / b for b, c in zip(tb, tc)),
                     "load_average": statistics.median(load)})
        print(f"{name}: beam {rows[-1]['beam_s']:.3g} s, continuum "
              f"{rows[-1]['continuum_s']:.3g} s, ratio {rows[-1]['ratio']:.3g} "
              f"(load average {rows[-1]['load_average']:.1f})", flush=True)
    if args.out:
        with open(args.out, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
