"""``flexfem topopt PROBLEM.toml [--json] [--out DIR]``: optimise the design a problem file
describes; the state after every iteration, the densities and the result go into DIR, and a
rerun with the same DIR continues where the last one stopped. Its parser is
``register_topopt`` in flexfem.studies.cli, which imports this module only when the command
runs (the command line starts without importing flexfem.topopt)."""
from pathlib import Path
import sys


def _progress(iteration, objective, volume, change) -> None:
    print(f"  it {iteration:4d}  objective {objective: .5g}  volume {volume:.4f}  "
          f"change {change:.4f}", file=sys.stderr, flush=True)


def run(args) -> dict:
    from .optimize import optimize
    from .outputs import write_outputs
    from .problem_file import load_problem, read_problem_file
    from .shape import shape_options, write_shape

    options = shape_options(read_problem_file(args.problem))
    problem = load_problem(args.problem)
    out = Path(args.out) if args.out else Path(Path(args.problem).stem + "_topopt")
    if out.exists() and not out.is_dir():  # refused before the optimisation runs
        raise ValueError(f"--out {out}: is a file, not a folder; give a folder")
    progress = _progress if sys.stderr.isatty() else None
    result = optimize(problem, out_dir=out, progress=progress)
    summary = result.summary()
    summary["files"] = write_outputs(result, out)
    if options is not None:
        shape = write_shape(result, out, options)
        summary["files"] += shape.pop("files")
        summary["shape"] = shape
    summary["out"] = str(out)
    return summary


def summarize(result: dict) -> str:
    worst = ", the worst of the robust designs (KS)" if result.get("robust") else ""
    lines = [f"objective ({result['objective_kind']}{worst}): {result['objective']:.6g}",
             f"iterations: {result['iterations']}"
             f" ({'converged' if result['converged'] else 'not converged'})",
             f"volume fraction: {result['volume_fraction']:.4f}"]
    for key in ("u_in", "u_out"):
        if key in result:
            lines.append(f"{key}: {result[key]:.6g} m")
    large = result.get("large_displacements")
    if large:
        lines.append(f"large displacements: the small-displacement optimum ("
                     f"{large['start_iterations']} iterations) gives {large['start_objective']:.6g}"
                     f" with large displacements; this design {result['objective']:.6g}")
    if len(result["compliances"]) > 1:
        lines.append("compliance by load case: "
                     + ", ".join(f"{c:.6g} J" for c in result["compliances"]))
    for key, unit in (("frequency", "Hz"), ("stress", "Pa")):
        if key in result["constraints"]:
            lines.append(f"{key}: {result['constraints'][key]:.6g} {unit}")
    lines += _robust_lines(result)
    shape = result.get("shape", {})
    lines += _neck_lines(shape.get("necks"))
    tol = shape.get("tolerance")
    if tol:
        large = shape.get("body_fitted_large")
        fitted = (large["large"] if large else shape["body_fitted"])[tol["spring"]]
        lines.append(f"body-fitted u_{tol['spring']}{' (large displacements)' if large else ''}"
                     f": {fitted:.6g} m (density model {tol['u']:.6g} m, tolerance "
                     f"{tol['tolerance']:.3g} m)")
        if large and not large["strain_valid"]:
            lines.append(f"  its largest strain {large['max_strain']:.3g} is beyond the "
                         "St. Venant-Kirchhoff material's validity (5 %)")
    for c, (fitted, tol) in enumerate(zip(shape.get("body_fitted_compliances", ()),
                                          shape.get("compliance_tolerances", ())), start=1):
        lines.append(f"body-fitted compliance, load case {c}: {fitted:.6g} J (density model "
                     f"{tol['u']:.6g} J, tolerance {tol['tolerance']:.3g} J)")
    lines.append(f"written: {', '.join(result['files'])} in {result['out']}")
    return "\n".join(lines)


def _robust_lines(result: dict) -> list:
    """The robust formulation's sizes and designs, if any."""
    robust = result.get("robust")
    if not robust:
        return []
    eroded, middle, dilated = robust["thresholds"]
    lines = [f"robust: thresholds {eroded:g} / {middle:g} / {dilated:g}, filter radius "
             f"{robust['filter_radius']:.4g} elements: minimum solid "
             f"{robust['min_solid'] * 1e3:.4g} mm, minimum void {robust['min_void'] * 1e3:.4g} mm"]
    for name, d in (robust.get("designs") or {}).items():
        lines.append(f"  {name}: objective {d['objective']:.6g}, volume {d['volume']:.4f}")
    return lines


def _neck_lines(necks: dict | None) -> list:
    """The outline's necks, narrowest first."""
    if necks is None:
        return []
    if not necks["necks"]:
        return [f"necks: none thinner than {necks['detect'] * 1e3:.4g} mm"]
    lines = [f"necks thinner than {necks['detect'] * 1e3:.4g} mm (on the outline):"]
    for n in necks["necks"]:
        x, y = n["where"]
        lines.append(f"  {n['width'] * 1e3:.4g} mm at ({x * 1e3:.4g}, {y * 1e3:.4g}) mm, "
                     f"peak von Mises {n['peak_stress'] / 1e6:.4g} MPa (body-fitted)")
    return lines
