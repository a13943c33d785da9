"""A finished design as a mechanism, for the command: the outline (DXF, STEP), a model file
(design.geo, design.toml) that ``flexfem analyze`` reads, the body-fitted re-solve of the
springs and the derived tolerance. Asked for by a problem file's ``[shape]`` table."""
from pathlib import Path

from .export import write_step
from .model_file import write_model
from .neck_check import detect_width, neck_report
from .outline import extract_outline, problem_anchors, write_dxf
from .tolerance import body_fitted_tolerance
from .verify import verify_compliances, verify_large, verify_mechanism

KEYS = {"rho", "yield_strength", "min_member"}


def shape_options(data: dict) -> dict | None:
    """The checked ``[shape]`` table of a parsed problem file (None without one):
    ``rho`` (kg/m^3) and ``yield_strength`` (Pa) for the model file, ``min_member`` (m)."""
    if "shape" not in data:
        return None
    table = data["shape"]
    if not isinstance(table, dict):
        raise ValueError(f"shape: must be a table, not {table!r}")
    unknown = sorted(set(table) - KEYS)
    if unknown:
        raise ValueError(f"shape: unknown key {unknown[0]!r} (known: {sorted(KEYS)})")
    out = {}
    for key in ("rho", "yield_strength", "min_member"):
        value = table.get(key, 0.0 if key == "min_member" else None)
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
                value > 0 or (key == "min_member" and value == 0)):
            raise ValueError(f"shape.{key} = {value!r}: must be a number > 0")
        out[key] = float(value)
    return out


def write_shape(result, folder, options: dict) -> dict:
    """Write outline.dxf, outline.step, design.geo and design.toml (with several load cases
    also design_case<c>.toml) into ``folder``; returns {files, parts, islands (m^2),
    thin_area (m^2)}, necks ({detect (m), necks: [{width (m), where (m), peak_stress (Pa)}]}:
    the outline's necks thinner than detect, :func:`~.neck_check.neck_report`) and the
    body-fitted checks: with springs body_fitted {spring: m} (load
    case 1, small displacements), with several load cases body_fitted_cases (one such dict
    a case), and tolerance; without springs body_fitted_compliances (J, one a load case:
    :func:`~.verify.verify_compliances`) and compliance_tolerances (each case's
    :func:`~.tolerance.body_fitted_tolerance`); with large displacements body_fitted_large
    (:func:`~.verify.verify_large`), the tolerance then that of the large-displacement
    state."""
    problem, folder = result.problem, Path(folder)
    outline = extract_outline(result.density, problem.grid, problem_anchors(problem),
                              min_member=options["min_member"])
    write_dxf(outline, folder / "outline.dxf")
    write_step(outline, folder / "outline.step")
    write_model(problem, outline, folder, rho=options["rho"],
                yield_strength=options["yield_strength"])
    cases = [f"design_case{c}.toml" for c in range(2, problem.n_cases + 1)]
    out = {"files": ["outline.dxf", "outline.step", "design.geo", "design.toml", *cases],
           "parts": len(outline.parts), "islands": list(outline.islands),
           "thin_area": outline.thin_area}
    detect = detect_width(problem, options["min_member"])
    out["necks"] = {"detect": detect, "necks": neck_report(problem, outline, detect)}
    if problem.springs and problem.nonlinear is not None:
        out["body_fitted_large"] = verify_large(problem, outline)
    if not problem.springs:
        out["body_fitted_compliances"] = verify_compliances(problem, outline)
        out["compliance_tolerances"] = [
            body_fitted_tolerance(problem, result.density, None, c)
            for c in range(1, problem.n_cases + 1)]
    if problem.springs:
        fitted = [verify_mechanism(problem, outline, case=c)
                  for c in range(1, problem.n_cases + 1)]
        out["body_fitted"] = fitted[0]
        if problem.n_cases > 1:
            out["body_fitted_cases"] = fitted
        name = problem.objective.spring or problem.springs[-1].name
        out["tolerance"] = {"spring": name, **body_fitted_tolerance(problem, result.density,
                                                                     name)}
    return out
