"""The beam model's answers on every example model file, recorded once and compared after a
change: that a refactoring of the beam package left the numbers unchanged.

    .venv/bin/python scripts/beam_examples_unchanged.py record /tmp/before   # before the change
    .venv/bin/python scripts/beam_examples_unchanged.py compare /tmp/before  # after it

Each examples/ model file that declares a beam model is run as
``flexfem analyze FILE --model beam --json``, and again with ``--dim 3`` (the spatial beam
model) where the file allows it; ``compare`` reruns them and prints every number that moved
by more than TOLERANCE relative (and every output that appeared, vanished or failed). Exit
status 1 if any did. About 10 minutes on 2 cores.
"""
import json
import math
import pathlib
import subprocess
import sys

TOLERANCE = 1e-9  # relative
ROOT = pathlib.Path(__file__).resolve().parent.parent
RUNS = [("", ()), (".3d", ("--dim", "3"))]
FLEXFEM = str(pathlib.Path(sys.executable).parent / "flexfem")  # the environment's command


def beam_model_files() -> list:
    """The examples' model files with a [[beam]] or [[rigid]] table, or [body]/[flexure]
    bodies (whose beam model the file's layout gives)."""
    files = sorted(ROOT.glob("examples/**/*.toml"))
    keys = ("[[beam]]", "[[rigid]]", "[[body]]", "[[flexure]]")
    return [f for f in files if any(k in f.read_text() for k in keys)]


def run_all() -> dict:
    """{name: parsed JSON or None (the run was refused)} of every file and dimension."""
    out = {}
    for f in beam_model_files():
        for suffix, extra in RUNS:
            cmd = [FLEXFEM, "analyze", str(f), "--model", "beam", "--json", *extra]
            done = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT, timeout=600)
            name = str(f.relative_to(ROOT)) + suffix
            out[name] = json.loads(done.stdout) if done.returncode == 0 else None
            print(f"{name}: {'ok' if done.returncode == 0 else 'refused'}", file=sys.stderr)
    return out


def differences(a, b, path="") -> list:
    """Every number of ``a`` and ``b`` (parsed JSON) that differs by more than TOLERANCE
    relative, and every key or length that differs; timings ignored."""
    if isinstance(a, dict) and isinstance(b, dict):
        out = [f"{path}: keys {sorted(set(a) ^ set(b))}"] if set(a) != set(b) else []
        return out + [d for k in a if k in b for d in differences(a[k], b[k], f"{path}.{k}")]
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return [f"{path}: length {len(a)} -> {len(b)}"]
        return [d for i, (x, y) in enumerate(zip(a, b)) for d in differences(x, y, f"{path}[{i}]")]
    numbers = all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in (a, b))
    if numbers:
        if a == b or (math.isnan(a) and math.isnan(b)) or "time" in path or "seconds" in path:
            return []
        rel = abs(a - b) / max(abs(a), abs(b))
        return [f"{path}: {a!r} -> {b!r} ({rel:.1e})"] if rel > TOLERANCE else []
    return [] if a == b or "time" in path else [f"{path}: {a!r} -> {b!r}"]


def main(argv) -> int:
    if len(argv) != 2 or argv[0] not in ("record", "compare"):
        print(__doc__)
        return 2
    where = pathlib.Path(argv[1])
    if argv[0] == "record":
        where.mkdir(parents=True, exist_ok=True)
        (where / "beam_examples.json").write_text(json.dumps(run_all(), indent=1))
        return 0
    before = json.loads((where / "beam_examples.json").read_text())
    after = run_all()
    moved = []
    for name in sorted(set(before) | set(after)):
        a, b = before.get(name), after.get(name)
        if (a is None) != (b is None):
            moved.append(f"{name}: {'refused' if a is None else 'ran'} -> "
                         f"{'refused' if b is None else 'ran'}")
        elif a is not None:
            moved += [f"{name}{d}" for d in differences(a, b)]
    print("\n".join(moved) or f"unchanged: {len(before)} runs within {TOLERANCE:g} relative")
    return 1 if moved else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
