"""Compliance matrix and linear buckling of a 3-D cantilever: flexfem against CalculiX *BUCKLE
and the closed forms. Not a test: prints a table (and one JSON line).

    .venv/bin/python benchmarks/bench_buckling.py               # ~20k DOFs, ~1 min on 2 cores
    .venv/bin/python benchmarks/bench_buckling.py --dofs 60000

The bench_fem cantilever (steel, 1 m x 0.1 m x 0.1 m, P2 tetrahedra, fixed at x = 0): the tip
face's 6 x 6 compliance (fem.compliance_matrix) beside Timoshenko's cantilever (C_xx = L / EA,
C_yy = L^3 / 3EI + L / kGA, C_tt = L / EI about z, C_y,tz = L^2 / 2EI, k = 5/6), and the
buckling factor of a 1 N axial compressive tip load (fem.solve_buckling) beside CalculiX's
*BUCKLE on the same nodes and elements and Euler's pi^2 E I / (4 L^2) (fixed-free; the solid's
shear makes it ~0.3 % lower: 1 / (1 + P / kGA)).
"""
import argparse
import json
import math
from pathlib import Path
import re
import sys
import time

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_fem import HEIGHT, LENGTH, cantilever_model  # noqa: E402

FORCE = 1.0  # N, axial compression on the tip face


def calculix_buckling(model, supports, loads, n: int) -> tuple[np.ndarray, float]:
    """(buckling factors, wall time s) of CalculiX's *BUCKLE on the same deck."""
    from flexfem.fem.calculix import deck_lines, run_ccx

    lines = deck_lines(model, supports, loads)
    start, end = lines.index("*STATIC"), lines.index("*NODE PRINT, NSET=NALL")
    lines = lines[:start] + ["*BUCKLE", str(n)] + lines[start + 1:end] + ["*END STEP"]
    run = run_ccx(lines)
    section = run.dat.split("B U C K L I N G   F A C T O R   O U T P U T")[1]
    rows = re.findall(r"^\s*\d+\s+([-+0-9.Ee]+)\s*$", section, flags=re.M)
    return np.array([float(r) for r in rows[:n]]), run.wall_s


def closed_forms(model) -> dict:
    E, nu = model.material.E, model.material.nu
    A, I = HEIGHT ** 2, HEIGHT ** 4 / 12
    G, k, L = E / (2 * (1 + nu)), 5 / 6, LENGTH
    euler = math.pi ** 2 * E * I / (4 * L ** 2)
    return {"C_xx": L / (E * A), "C_yy": L ** 3 / (3 * E * I) + L / (k * G * A),
            "C_tz": L / (E * I), "C_y_tz": L ** 2 / (2 * E * I), "euler_n": euler,
            "euler_shear_n": euler / (1 + euler / (k * G * A))}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dofs", type=int, default=20_000)
    parser.add_argument("--modes", type=int, default=2)
    args = parser.parse_args(argv)
    from flexfem.fem import Fixed, Force, compliance_matrix, solve_buckling

    model = cantilever_model(3, args.dofs)
    supports, loads = [Fixed("fixed")], [Force("tip", (-FORCE, 0.0, 0.0))]
    t = time.perf_counter()
    C = compliance_matrix(model, supports, "tip").matrix
    t_c = time.perf_counter() - t
    t = time.perf_counter()
    ours = solve_buckling(model, supports, loads, n=args.modes).load_factors
    t_b = time.perf_counter() - t
    ccx, t_ccx = calculix_buckling(model, supports, loads, args.modes)
    ref = closed_forms(model)
    out = {"dofs": int(model.n_dofs), "C_xx": C[0, 0], "C_yy": C[1, 1], "C_tz": C[5, 5],
           "C_y_tz": C[1, 5], "buckling_flexfem": ours.tolist(), "buckling_calculix": ccx.tolist(),
           "time_compliance_s": t_c, "time_buckling_s": t_b, "time_calculix_s": t_ccx,
           "closed": ref}
    print(f"3-D cantilever, {out['dofs']} DOFs (P2 tetrahedra)")
    print(f"{'quantity':<28}{'flexfem':>12}{'reference':>12}{'diff':>9}  reference")
    for key, name, source in (("C_xx", "C_xx (m/N)", "L/EA"),
                              ("C_yy", "C_yy (m/N)", "Timoshenko"),
                              ("C_tz", "C_tz,tz (1/(N m))", "L/EI"),
                              ("C_y_tz", "C_y,tz (1/N)", "L^2/2EI")):
        v, r = out[key], ref[key]
        print(f"{name:<28}{v:>12.5g}{r:>12.5g}{100 * (abs(v) / r - 1):>8.2f}%  {source}")
    for k, (a, b) in enumerate(zip(ours, ccx)):
        print(f"{'buckling factor %d' % (k + 1):<28}{a:>12.6g}{b:>12.6g}{100 * (a / b - 1):>8.3f}%"
              "  CalculiX *BUCKLE")
    print(f"{'buckling factor 1':<28}{ours[0]:>12.6g}{ref['euler_shear_n']:>12.6g}"
          f"{100 * (ours[0] / ref['euler_shear_n'] - 1):>8.3f}%  Euler with shear (x {FORCE} N)")
    print(f"times: compliance {t_c:.2f} s, flexfem buckling {t_b:.2f} s, CalculiX {t_ccx:.2f} s")
    print(json.dumps(out))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
