"""Time the two models of each spatial example (examples/spatial/) side by side: the same
model file, the same outputs (``analyze_model``: the static solve, stress, stiffness, the
modes the file asks for and the loaded body's 6x6 compliance, ``analysis.compliance``),
the continuum (P2 tetrahedra, default mesh) against the beam model built from the same
description. Not a test: prints a table (times, their ratio, each model's stiffness along
the load and the compliance diagonal's stiffnesses beam / continuum) and writes a JSON
(``--out``). Wall-clock times in process (imports excluded, building included: meshing the
continuum, building the beam model), the least of ``--repeat`` runs of the beam model and
one of the continuum. On a machine others load too the times move by tens of per cent; the
ratio is what to read.

    .venv/bin/python benchmarks/bench_spatial.py                    # every example
    .venv/bin/python benchmarks/bench_spatial.py --only leaf_guide --out spatial.json
"""
import argparse
import json
import time
from pathlib import Path

from flexfem.geometry.user_model import load_spec
from flexfem.studies.user_model import analyze_model

EXAMPLES = Path(__file__).parents[1] / "examples" / "spatial"
#: The moving body of each example, whose compliance both models give.
BODIES = {"wire_guide": "stage", "leaf_guide": "stage", "cross_pivot": "rotor"}


def timed(path, model: str, body: str, repeat: int) -> tuple:
    """(least wall-clock time (s) of ``repeat`` analyses, the last result)."""
    best, result = float("inf"), None
    for _ in range(repeat):
        spec = load_spec(path, {"analysis.compliance": body})
        start = time.perf_counter()
        result = analyze_model(spec, model=model)
        best = min(best, time.perf_counter() - start)
    return best, result


def run(names, repeat: int) -> dict:
    rows = {}
    for name in names:
        body = BODIES[name]
        row = {}
        for model, runs in (("beam", repeat), ("continuum", 1)):
            t, r = timed(EXAMPLES / f"{name}.toml", model, body, runs)
            matrix = r["compliance"]["matrix"]
            row[model] = {"time_s": t, "dofs": r["dofs"], "stiffness": r["stiffness"],
                          "compliance_diagonal_stiffness": [1 / matrix[i][i] for i in range(6)]}
        row["speedup"] = row["continuum"]["time_s"] / row["beam"]["time_s"]
        rows[name] = row
    return rows


def table(rows: dict) -> str:
    lines = ["example      | beam s | continuum s (DOFs) | ratio | k beam/continuum | "
             "diagonal k beam/continuum (x y z rx ry rz)"]
    for name, row in rows.items():
        b, c = row["beam"], row["continuum"]
        (group, by_axis), = b["stiffness"].items()
        axis, k = next(iter(by_axis.items()))
        ratios = " ".join(f"{kb / kc:.3f}" for kb, kc in zip(
            b["compliance_diagonal_stiffness"], c["compliance_diagonal_stiffness"]))
        lines.append(f"{name:12s} | {b['time_s']:6.3f} | {c['time_s']:8.1f} ({c['dofs']}) | "
                     f"{row['speedup']:5.0f} | {k / c['stiffness'][group][axis]:.3f} ({axis}) | "
                     f"{ratios}")
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", action="append", choices=sorted(BODIES), default=None)
    parser.add_argument("--repeat", type=int, default=3, help="beam runs (least kept)")
    parser.add_argument("--out", default=None, help="write the rows as JSON here")
    args = parser.parse_args()
    rows = run(args.only or list(BODIES), args.repeat)
    print(table(rows))
    if args.out:
        Path(args.out).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
