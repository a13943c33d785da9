"""Time the two models of each mechanism written as bodies and flexures (examples/bodies/)
side by side: the same model file, the same outputs (the analyze keys: static solve, stress,
stiffness, and the modes or compliance the file asks for), continuum (2-D, default mesh)
against the beam model derived from the same description. Not a test: prints a table and
writes a JSON (``--out``); the ratio is what to read (docs/beam_speed.md).

In-process (the default): wall-clock times of ``analyze_model`` (imports and gmsh's start
excluded, both models' building included: meshing the continuum, building the beam model),
the least of ``--repeat`` runs, and the beam model's first run in this process ("beam first":
its notch corrections included, which a process computes or looks up once per shape).

``--fresh``: each model's first analysis in a new process, what a user waits for: the
analysis after the imports (load_spec and analyze_model, timed inside the child) and the
whole ``flexfem analyze FILE --model ...`` (timed from outside: the interpreter's start and
the CLI's imports included); continuum and beam run in turn, medians of ``--repeat``.

    .venv/bin/python benchmarks/bench_bodies.py              # every example, 5 runs each
    .venv/bin/python benchmarks/bench_bodies.py --fresh --repeat 3 notch.toml
    .venv/bin/python benchmarks/bench_bodies.py --solid guide.toml   # and its 3-D solid (once)
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time
import tomllib
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")

from flexfem.geometry.user_model import load_spec  # noqa: E402
from flexfem.studies.user_model import analyze_model  # noqa: E402

EXAMPLES = Path(__file__).parents[1] / "examples" / "bodies"
MODELS = ("continuum", "beam")
# the child of --fresh: its imports, then the first analysis timed
FIRST = ("import sys, time\n"
         "from flexfem.geometry.user_model import load_spec\n"
         "from flexfem.studies.user_model import analyze_model\n"
         "start = time.perf_counter()\n"
         "analyze_model(load_spec(sys.argv[1]), model=sys.argv[2])\n"
         "print(time.perf_counter() - start)\n")


def timed(fn, repeat: int) -> tuple[float, float, float, dict]:
    """(minimum s, median s, first s, output) of ``repeat`` runs."""
    times, out = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - start)
    return min(times), statistics.median(times), times[0], out


def model_files(names=()) -> list[Path]:
    """The model files of examples/bodies/ (not the studies beside them, which name a
    ``mechanism``), those ``names`` only where given."""
    return [p for p in sorted(EXAMPLES.glob("*.toml"))
            if "mechanism" not in tomllib.loads(p.read_text())
            and (not names or p.name in names)]


def in_process(args) -> list[dict]:
    rows = []
    print(f"{'model file':<22} {'continuum s':>12} {'beam s':>9} {'ratio':>7} "
          f"{'beam first s':>13} {'ratio':>6} {'DOFs':>14} {'k beam/continuum':>17}")
    cases = [(p, 2) for p in model_files(args.names)]
    cases += [(EXAMPLES / name, 3) for name in args.solid]
    for path, dim in cases:
        spec, flat = load_spec(path, dim=dim), load_spec(path)
        repeat = args.repeat if dim == 2 else 1
        c_min, c_med, _, c = timed(lambda: analyze_model(spec), repeat)
        b_min, b_med, b_first, b = timed(lambda: analyze_model(flat, model="beam"),
                                         args.repeat)
        group, by_axis = next(iter(c["stiffness"].items()))
        axis, k = next(iter(by_axis.items()))
        row = {"model": path.name, "dim": dim, "continuum_s": c_min, "continuum_median_s": c_med,
               "beam_s": b_min, "beam_median_s": b_med, "beam_first_s": b_first,
               "ratio": c_min / b_min, "first_ratio": c_min / b_first,
               "continuum_dofs": c["dofs"], "beam_dofs": b["dofs"],
               "stiffness": f"{group} {axis}",
               "beam_over_continuum": b["stiffness"][group][axis] / k}
        rows.append(row)
        name = path.name + (" 3-D" if dim == 3 else "")
        print(f"{name:<22} {c_min:>12.3f} {b_min:>9.4f} {row['ratio']:>7.0f} "
              f"{b_first:>13.4f} {row['first_ratio']:>6.0f} "
              f"{c['dofs']:>7}/{b['dofs']:<6} {row['beam_over_continuum']:>17.4f}", flush=True)
    return rows


def fresh_run(path: Path, model: str) -> tuple[float, float]:
    """(first analysis s, timed in a new process after its imports; ``flexfem analyze``'s
    whole process s)."""
    first = float(subprocess.run([sys.executable, "-c", FIRST, str(path), model], check=True,
                                 capture_output=True, text=True).stdout.split()[-1])
    cli = Path(sys.executable).with_name("flexfem")
    start = time.perf_counter()
    subprocess.run([str(cli), "analyze", str(path), "--model", model], check=True,
                   capture_output=True, text=True)
    return first, time.perf_counter() - start


def fresh(args) -> list[dict]:
    rows = []
    print(f"{'model file':<22} {'first analysis: continuum s':>28} {'beam s':>8} {'ratio':>6}"
          f" {'flexfem analyze: continuum s':>29} {'beam s':>8} {'ratio':>6}")
    for path in model_files(args.names):
        runs = {m: [] for m in MODELS}
        try:
            for _ in range(args.repeat):
                for m in MODELS:  # in turn: a drift of the machine's speed moves both
                    runs[m].append(fresh_run(path, m))
        except subprocess.CalledProcessError as e:
            print(f"{path.name:<22} failed: {(e.stderr or '').strip().splitlines()[-1:]}")
            continue
        med = {m: [statistics.median(r[i] for r in runs[m]) for i in (0, 1)] for m in MODELS}
        (c_first, c_cli), (b_first, b_cli) = med["continuum"], med["beam"]
        row = {"model": path.name, "continuum_first_s": c_first, "beam_first_s": b_first,
               "first_ratio": c_first / b_first, "continuum_cli_s": c_cli, "beam_cli_s": b_cli,
               "cli_ratio": c_cli / b_cli}
        rows.append(row)
        print(f"{path.name:<22} {c_first:>28.3f} {b_first:>8.4f} {row['first_ratio']:>6.0f}"
              f" {c_cli:>29.2f} {b_cli:>8.2f} {row['cli_ratio']:>6.2f}", flush=True)
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", help="model files of examples/bodies/ (default all)")
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--out", default="bench_bodies.json")
    parser.add_argument("--fresh", action="store_true",
                        help="each model's first analysis in a new process (see the text)")
    parser.add_argument("--solid", nargs="*", default=[],
                        help="model files (names in examples/bodies/) whose 3-D continuum "
                             "(--dim 3) is timed too, once")
    args = parser.parse_args()
    rows = fresh(args) if args.fresh else in_process(args)
    Path(args.out).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
