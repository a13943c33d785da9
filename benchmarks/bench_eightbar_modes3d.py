"""Time the eight-bar suspension's first 10 modes four ways, interleaved so that all see the
same load: the 3-D solid (`build_model(dim=3)`, 240k DOFs), the 2-D plane-stress FEM
(`build_model()`, 48k DOFs) and the spatial beam model (`beam_modes`) with flexible links
(link plates and anchors as beams, the default) and with rigid links. Model build, assembly
and eigensolve included. Not a test: prints medians and ratios (and writes a JSON with
``--out``); the ratios are what to read. ``--kinds beam beam_rigid``: the beam models only.

    .venv/bin/python benchmarks/bench_eightbar_modes3d.py [--repeat 3] [--out bench.json]
"""
import argparse
import json
import os
import statistics
import time

KINDS = ("solid", "plane", "beam", "beam_rigid")


def run(kind: str) -> list:
    from flexfem.fem import Fixed, solve_modes
    from flexfem.geometry.eightbar.flexure import EightBarFlexureParams
    from flexfem.studies.eightbar.analysis import build_model
    from flexfem.studies.eightbar.eightbar_modes3d import beam_modes

    params = EightBarFlexureParams()
    if kind in ("beam", "beam_rigid"):
        links = "rigid" if kind == "beam_rigid" else "flexible"
        return beam_modes(params, 10, links=links)["f_hz"]
    model, _ = build_model(params, dim=3 if kind == "solid" else 2)
    modes = solve_modes(model, n=10, supports=[Fixed("fixed")], shift_hz=-1.0)
    return modes.frequencies_hz.tolist()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--out", default=None)
    parser.add_argument("--kinds", nargs="+", default=list(KINDS), choices=KINDS)
    args = parser.parse_args()
    times, loads = {kind: [] for kind in args.kinds}, []
    for _ in range(args.repeat):
        for kind in times:
            start = time.perf_counter()
            run(kind)
            times[kind].append(time.perf_counter() - start)
            loads.append(os.getloadavg()[0])
    median = {k: statistics.median(v) for k, v in times.items()}
    first = args.kinds[0]
    for kind, t in median.items():
        print(f"{kind:10s} {t:8.3f} s   {first} / {kind} = {median[first] / t:7.2f}")
    print(f"load average {min(loads):.1f}-{max(loads):.1f}")
    if args.out:
        with open(args.out, "w") as f:
            json.dump({"times_s": times, "median_s": median, "load": loads}, f, indent=1)


if __name__ == "__main__":
    main()
