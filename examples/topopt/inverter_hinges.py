"""The force inverter with and without a minimum hinge width, side by side (docs/topopt_robust.md):
examples/topopt/inverter_robust.toml (the robust formulation, min_hinge) and the same problem
without length control ([robust] removed, filter radius 1.5, the same projection), each
optimised, its outline's necks measured with their body-fitted stress, and its body-fitted
u_out beside the density model's. Prints a Markdown table (lengths in mm, u_out in um).

    .venv/bin/python examples/topopt/inverter_hinges.py [--nelx N --nely M] [--min-hinge M]
"""
import argparse
from dataclasses import replace
from pathlib import Path

from flexfem.topopt import optimize, problem_from_dict
from flexfem.topopt.neck_check import neck_report
from flexfem.topopt.outline import extract_outline, problem_anchors
from flexfem.topopt.problem_file import read_problem_file
from flexfem.topopt.verify import verify_mechanism

FILE = Path(__file__).with_name("inverter_robust.toml")


def row(name: str, problem, detect: float) -> str:
    """One table row: the design optimised, verified body-fitted, its necks measured."""
    result = optimize(problem)
    outline = extract_outline(result.density, problem.grid, problem_anchors(problem))
    fitted = verify_mechanism(problem, outline)["output"]
    density = result.summary()["u_out"]
    designs = result.designs or {}
    three = (f" (eroded {designs['eroded']['objective'] * 1e6:.3f}, dilated "
             f"{designs['dilated']['objective'] * 1e6:.3f})" if designs else "")
    necks = neck_report(problem, outline, detect)
    widths = ", ".join(f"{n['width'] * 1e3:.2f}" for n in necks) + " mm" if necks else "none"
    stresses = ", ".join(f"{n['peak_stress'] / 1e6:.2f}" for n in necks) + " MPa" if necks \
        else "-"
    state = "" if result.converged else " (not converged)"
    return (f"| {name} | {result.iterations}{state} | {density * 1e6:.3f} um{three} | "
            f"{fitted * 1e6:.3f} um | {100 * abs(fitted / density - 1):.1f} % | {widths} | "
            f"{stresses} |")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nelx", type=int, default=None)
    parser.add_argument("--nely", type=int, default=None)
    parser.add_argument("--min-hinge", type=float, default=None, help="m")
    args = parser.parse_args()
    data = read_problem_file(FILE)
    for key in ("nelx", "nely"):
        if getattr(args, key):
            data["domain"][key] = getattr(args, key)
    if args.min_hinge:
        data["robust"]["min_hinge"] = args.min_hinge
    robust = problem_from_dict(data)
    hinge = robust.robust.min_size
    plain = replace(robust, robust=None, radius=1.5)
    g = robust.grid
    print(f"{g.nelx} x {g.nely} elements of {g.dx * 1e3:g} mm; min_hinge {hinge * 1e3:g} mm "
          f"(filter radius {robust.radius:.3g} elements); necks under {2 * hinge * 1e3:g} mm")
    print("| design | iterations | u_out, density model | body-fitted u_out | difference | "
          f"necks under {2 * hinge * 1e3:g} mm (outline) | peak von Mises there |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    print(row(f"robust, min_hinge {hinge * 1e3:g} mm", robust, 2 * hinge), flush=True)
    print(row("no length control", plain, 2 * hinge))


if __name__ == "__main__":
    main()
