"""Write data/notch_description_factors.json: the 2-D correction of the beam model of a notch
written as bodies and flexures (a circular or elliptical notch, its profile as
geometry/mechanism/beams.py writes it), over t/R, across / along and Poisson's ratio; or check
the table against the direct solve between its nodes.

    nice -n 10 .venv/bin/python scripts/notch_description_table.py --jobs 2   # ~12 min
    nice -n 10 .venv/bin/python scripts/notch_description_table.py --check --jobs 2  # ~6 min

Each entry is flexfem.reduced.hinge_patch.profile_factors (table=False) of the profile
beams.profile draws for a Notch of neck b, semi-axes R along the centre line and aspect R
across it: the patch with a stub of its end height at each end, rigid beyond, in plane stress
(P2, NECK_ELEMENTS triangles across the local thickness, the direct solve's own mesh) against
the same as beams. flexfem's own computation, not a published source. ``--check`` solves
directly at points halfway between the nodes (in ln(t/R), ln(aspect) and nu) and prints the
largest difference of each factor from the table's interpolation (docs/beam_speed.md).
"""
import argparse
import json
from multiprocessing import Pool
from pathlib import Path
import time

T_OVER_R = (0.02, 0.03, 0.05, 0.07, 0.1, 0.14, 0.2, 0.28, 0.4, 0.56, 0.8, 1.1, 1.5, 2.0)
ASPECT = (0.25, 0.35, 0.5, 0.7, 1.0, 1.4, 2.0, 2.8, 4.0)
NU = (0.2, 0.3, 0.4)
FIELDS = ("bending", "shear", "axial", "kt_bending", "kt_tension")
TARGET = Path(__file__).resolve().parent.parent / "data" / "notch_description_factors.json"


def direct(point: tuple):
    """NotchFactors of the description's notch at (t/R, aspect, nu), solved directly."""
    from flexfem.geometry.mechanism.beams import profile
    from flexfem.geometry.mechanism.description import Notch
    from flexfem.reduced.hinge_patch import profile_factors

    t_over_r, aspect, nu = point
    b = 1e-3
    R = b / t_over_r
    notch = Notch(("a", "b"), (0.0, 0.0), (2 * R, 0.0), b, R, aspect * R)
    return profile_factors(profile(notch, 2 * R), 2 * R, nu, table=False)


def write(jobs: int) -> None:
    from flexfem.geometry.mechanism.beams import STATIONS
    from flexfem.reduced.hinge_patch import NECK_ELEMENTS

    start = time.perf_counter()
    points = [(t, a, nu) for nu in NU for a in ASPECT for t in T_OVER_R]
    with Pool(jobs) as pool:
        found = pool.map(direct, points, chunksize=1)
    print(f"{len(points)} patches in {time.perf_counter() - start:.0f} s", flush=True)
    values = {name: [getattr(f, name) for f in found] for name in FIELDS}
    TARGET.write_text(table_text(values, NECK_ELEMENTS, STATIONS))
    print(f"wrote {TARGET.name} in {time.perf_counter() - start:.0f} s")


ABOUT = [
    "The 2-D correction of the beam model of a notch written as bodies and flexures (a",
    "circular or elliptical notch: neck b, semi-axes R along its centre line and aspect R",
    "across it, its profile t(s) as geometry/mechanism/beams.py writes it, `stations` points",
    "a quarter of it), computed by flexfem: scripts/notch_description_table.py",
    "(flexfem.reduced.hinge_patch.profile_factors, the direct solve), not a published",
    "source. The notch with a stub of its end height at each end, rigid beyond, in plane",
    "stress (P2 triangles, `neck_elements` across the local thickness) against the same as",
    "beams: bending, shear and axial multiply E I, kappa G A and E A on the notch's beam",
    "elements; kt_bending and kt_tension are the neck's peak von Mises stress over",
    "6 M / (w b^2) and N / (w b) (null: a flat neck, no K_t). Each field:",
    "[nu][aspect][t_over_r], t_over_r = b / R, aspect = across / along. JSON: read in",
    "0.3 ms where TOML takes 15 (a first analysis waits for it).",
]


def table_text(values: dict, neck_elements: int, stations: int) -> str:
    """The JSON text of the table: ``values`` {field: entries in the order of
    [nu][aspect][t_over_r], t_over_r fastest}, one row of t_over_r a line."""
    fmt = lambda row: "[" + ", ".join("null" if v != v else f"{v:.12g}" for v in row) + "]"
    n_t, n_a = len(T_OVER_R), len(ASPECT)
    lines = ['{"description_notch": {', '"about": ' + json.dumps(ABOUT, indent=0) + ",",
             f'"neck_elements": {neck_elements},', f'"stations": {stations},',
             f'"t_over_r": {fmt(T_OVER_R)},', f'"aspect": {fmt(ASPECT)},', f'"nu": {fmt(NU)},']
    for k, name in enumerate(FIELDS):
        v = values[name]
        blocks = ["[\n" + ",\n".join(fmt(v[(i * n_a + j) * n_t:(i * n_a + j + 1) * n_t])
                                      for j in range(n_a)) + "]" for i in range(len(NU))]
        lines.append(f'"{name}": [' + ",\n".join(blocks) + "]" + ("," if k < 4 else ""))
    return "\n".join(lines) + "\n}}\n"


def halfway(nodes: tuple, k: int, log: bool = True) -> float:
    """The point halfway between nodes k and k + 1 (on a log axis: their geometric mean)."""
    return (nodes[k] * nodes[k + 1]) ** 0.5 if log else (nodes[k] + nodes[k + 1]) / 2


def check(jobs: int) -> None:
    """Direct solves halfway between the nodes, against the table: the largest relative
    difference of each field, and where."""
    from flexfem.reduced.hinge_patch import description_tabulated

    points = [(halfway(T_OVER_R, i), halfway(ASPECT, j), nu)
              for i in range(len(T_OVER_R) - 1) for j in range(len(ASPECT) - 1)
              for nu in (0.3,)]
    points += [(halfway(T_OVER_R, i), 1.0, halfway(NU, 0, log=False)) for i in range(0, 13, 4)]
    with Pool(jobs) as pool:
        found = pool.map(direct, points, chunksize=1)
    worst = {name: (0.0, None) for name in FIELDS}
    for point, f in zip(points, found):
        table = description_tabulated(*point)
        for name in FIELDS:
            a, b = getattr(f, name), getattr(table, name)
            if a == a and b == b and abs(b / a - 1) >= worst[name][0]:
                worst[name] = (abs(b / a - 1), point)
            print(f"{point[0]:.4g} {point[1]:.4g} {point[2]:.3g} {name:<10} direct {a:.6f} "
                  f"table {b:.6f}", flush=True)
    for name, (err, point) in worst.items():
        print(f"{name:<10} largest |table / direct - 1| = {err:.2e} at (t/R, aspect, nu) = "
              f"{point}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--jobs", type=int, default=1, help="processes (default 1)")
    parser.add_argument("--check", action="store_true",
                        help="compare the table with direct solves between its nodes")
    args = parser.parse_args()
    (check if args.check else write)(args.jobs)


if __name__ == "__main__":
    main()
