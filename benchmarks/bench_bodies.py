"""Time the two models of each mechanism written as bodies and flexures (examples/bodies/)
side by side: the same model file, the same outputs (the analyze keys: static solve, stress,
stiffness, and the modes or compliance the file asks for), continuum (2-D, default mesh)
against the beam model derived from the same description. Not a test: prints a table and
writes a JSON (``--out``). Wall-clock times in-process (imports and gmsh's start excluded,
both models' building included: meshing the continuum, building the beam model); the ratio
is what to read.

    .venv/bin/python benchmarks/bench_bodies.py              # every example, 5 runs each
    .venv/bin/python benchmarks/bench_bodies.py --solid guide.toml   # and its 3-D solid (once)
"""
import argparse
import json
import os
import statistics
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")

from flexfem.geometry.user_model import load_spec  # noqa: E402
from flexfem.studies.user_model import analyze_model  # noqa: E402

EXAMPLES = Path(__file__).parents[1] / "examples" / "bodies"


def timed(fn, repeat: int) -> tuple[float, float, dict]:
    """(minimum s, median s, output) of ``repeat`` runs."""
    times, out = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - start)
    return min(times), statistics.median(times), out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--out", default="bench_bodies.json")
    parser.add_argument("--solid", nargs="*", default=[],
                        help="model files (names in examples/bodies/) whose 3-D continuum "
                             "(--dim 3) is timed too, once")
    args = parser.parse_args()
    rows = []
    print(f"{'model file':<18} {'continuum s':>12} {'beam s':>9} {'ratio':>7} "
          f"{'DOFs':>14} {'stiffness beam/continuum':>26}")
    cases = [(p, 2) for p in sorted(EXAMPLES.glob("*.toml")) if not p.stem.endswith("_front")]
    cases += [(EXAMPLES / name, 3) for name in args.solid]
    for path, dim in cases:
        spec, flat = load_spec(path, dim=dim), load_spec(path)
        repeat = args.repeat if dim == 2 else 1
        runs = {"continuum": timed(lambda: analyze_model(spec), repeat),
                "beam": timed(lambda: analyze_model(flat, model="beam"), args.repeat)}
        (c_min, c_med, c), (b_min, b_med, b) = runs["continuum"], runs["beam"]
        group, by_axis = next(iter(c["stiffness"].items()))
        axis, k = next(iter(by_axis.items()))
        row = {"model": path.name, "dim": dim, "continuum_s": c_min, "continuum_median_s": c_med,
               "beam_s": b_min, "beam_median_s": b_med, "ratio": c_min / b_min,
               "continuum_dofs": c["dofs"], "beam_dofs": b["dofs"],
               "stiffness": f"{group} {axis}",
               "beam_over_continuum": b["stiffness"][group][axis] / k}
        rows.append(row)
        print(f"{path.name + (' 3-D' if dim == 3 else ''):<18} {c_min:>12.3f} {b_min:>9.4f} {row['ratio']:>7.0f} "
              f"{c['dofs']:>7}/{b['dofs']:<6} {row['beam_over_continuum']:>26.4f}")
    Path(args.out).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
