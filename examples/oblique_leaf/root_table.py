"""Oblique roots: the beam model against the continuum of the same model file, for one leaf
(examples/oblique_leaf/leaf.toml) and the cross pivot (examples/cross_pivot/pivot.toml) at
several angles phi between leaf and block face and several L/t, with the beams' roots at the
centre line's meeting with the face (`[beam_model] roots = "centre_line"`) and at the acute
edge's (the default: the leaf's whole section free, (t/2) cot(phi) further along the leaf, then
the common root extension, as the crossing joint does; also built here independently, by moving
the model file's end points there, as a check of the builder). Prints one row per case: phi, L/t, continuum K
(N m/rad), error of each rule (%).

    python examples/oblique_leaf/root_table.py [leaf|pivot] [lc_leaf / t]
"""
import math
from pathlib import Path
import shutil
import sys
import tempfile

from flexfem.geometry.user_model import load_spec
from flexfem.studies.user_model import analyze_model

HERE = Path(__file__).resolve().parent
CASES = {"leaf": (HERE / "leaf.toml", "phi", (15, 20, 30, 45, 60, 75, 90), (15, 30, 60)),
         "pivot": (HERE.parent / "cross_pivot" / "pivot.toml", "beta", (30, 45, 60), (30, 60))}


def couple_stiffness(result, arm: float) -> float:
    """K = M / theta (N m/rad) of a unit couple F = 1 N on the faces left and right at +-arm."""
    u = result["mean_displacement"]
    return 2 * arm / ((u["right"][1] - u["left"][1]) / (2 * arm))


def acute_edge_copy(path: Path, angle: str, folder: Path) -> Path:
    """A copy of the model file whose beams' end points (and the [[rigid]] joins) lie at the
    acute edge's meeting with the face: L / 2 -> L / 2 - (t / 2) cot(angle)."""
    for f in path.parent.iterdir():
        if f.suffix == ".geo":
            shutil.copy(f, folder / f.name)
    lines = []
    for line in path.read_text().splitlines():
        if line.startswith(("points", "joins")):
            line = line.replace("L / 2 *", f"(L / 2 - t / 2 / tan({angle})) *")
        lines.append(line)
    out = folder / path.name
    out.write_text("\n".join(lines) + "\n")
    return out


def arm_of(kind: str, p: dict) -> float:
    if kind == "pivot":
        return p["arm"]
    return p["L"] / 2 * math.cos(p["phi"]) + p["t"] * (3 + 1 / math.tan(p["phi"]))


def row(kind: str, degrees: float, slenderness: float, lc: float, acute: Path) -> tuple:
    """(K continuum N m/rad, f1 continuum Hz (None without modes), errors % of K and f1 with
    centre-line roots, with acute-edge roots (the builder's default), and with the end points
    moved to the acute edge). The leaf: t = 1 mm, L = slenderness t; the pivot: its own L =
    30 mm, t = L / slenderness."""
    path, angle = CASES[kind][:2]
    if kind == "pivot":
        t = 0.03 / slenderness
        over = {angle: math.radians(degrees), "t": t, "lc_leaf": lc * t}
    else:
        t = 1e-3
        over = {angle: math.radians(degrees), "t": t, "L": slenderness * t, "lc_leaf": lc * t}
    spec = load_spec(path, over)
    arm = arm_of(kind, spec.constants)
    centre = load_spec(path, {**over, "beam_model.roots": "centre_line"})
    results = [analyze_model(spec), analyze_model(centre, model="beam"),
               analyze_model(spec, model="beam"),
               analyze_model(load_spec(acute, over), model="beam")]
    k = [couple_stiffness(r, arm) for r in results]
    f = [(r.get("frequencies_hz") or [None])[0] for r in results]
    out = [k[0], f[0]]
    for i in (1, 2, 3):
        out += [100 * (k[i] / k[0] - 1), 100 * (f[i] / f[0] - 1) if f[0] else float("nan")]
    return tuple(out)


def main(kind: str = "leaf", lc: float = 0.25) -> None:
    path, angle, degrees, slenderness = CASES[kind]
    with tempfile.TemporaryDirectory() as folder:
        acute = acute_edge_copy(path, angle, Path(folder))
        print(f"{kind} (leaf mesh {lc} t): phi (deg), L/t, continuum K (N m/rad), f1 (Hz); "
              "errors % of K, f1: centre-line roots, acute-edge roots, end points moved")
        for s in slenderness:
            for d in degrees:
                k, f, *errors = row(kind, d, s, lc, acute)
                print(f"{d:5g} {s:4g} {k:10.5g} {f or float('nan'):9.5g}  "
                      + "  ".join(f"{e:+7.2f}" for e in errors), flush=True)


if __name__ == "__main__":
    main(*(sys.argv[1:2] or ["leaf"]), *(float(a) for a in sys.argv[2:3]))
