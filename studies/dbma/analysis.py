"""FEM analysis of the DBMA (Micromachines 2020, 11(3), 312, Section 4) beside its formulas.

Static: the actuator is a pair of equal and opposite forces on the input pads; the part is held
on its mounting face (bottom of output member 11). R_fem = output displacement (top of member
4, along y) / actuator elongation (change of the distance between the pads); R_fem_per_side =
output / one pad's motion = 2 R_fem, the reading that the paper's R = 4 dy/dx (Eq. 7) and its
test's "input displacement" take (docs/dbma.md). Modal: held on the
mounting face, with the actuator, axially ~10x stiffer than the DBMA's input stiffness, holding
the pads along x (docs/dbma.md). Forces in N, lengths in m, stresses in Pa, frequencies in Hz.
"""
import dataclasses
import math
from pathlib import Path
from typing import Literal

import numpy as np

from ...data import load_toml
from ...fem import (
    Fixed,
    Force,
    Model,
    PlaneStress,
    Prescribed,
    Solid3D,
    solve_modes,
    solve_static,
)
from ...geometry.dbma.drawing import (
    DBMALayout,
    mesh_dbma,
    part_mass,
)
from ...geometry.dbma.params import DBMAParams, paper_design
from ..engine.convergence import converge, plot_convergence
from ..engine.validate import declare
from .beam_model import beam_model
from .figures import analytical_metrics
from .material import dbma_material  # noqa: F401 (public here too)
from .guards import check_analysable, check_mesh_budget, check_result, validity_notes

OUTPUT_AXIS = 1  # the output moves along y


def published() -> dict:
    """The paper's numbers (data/dbma_paper.toml), as printed."""
    return load_toml("dbma_paper.toml")


def actuator_loads(force: float, dim: int) -> list:
    """Equal and opposite forces (N) pushing the two input pads apart."""
    z = (0.0,) if dim == 3 else ()
    return [Force("input_a", (-force, 0.0) + z), Force("input_b", (force, 0.0) + z)]


def static_supports() -> list:
    return [Fixed("fixed")]


def modal_supports() -> list:
    """Mounting face held; pads held along x by the (much stiffer) actuator."""
    return [Fixed("fixed"), Prescribed("input", x=0.0)]


def build_model(p: DBMAParams, layout: DBMALayout | None = None, dim: int = 2,
                size_factor: float = 1.0, hinge_elements: int | None = None,
                max_dofs: int | None = None) -> Model:
    """Quadratic-element model of the DBMA: plane stress of thickness d (2-D) or solid (3-D).
    Refused before meshing (studies/dbma/guards.py) for h = 0 or a mesh above ``max_dofs``
    (None: what the machine's available memory affords)."""
    check_analysable(p)
    check_mesh_budget(p, layout, dim, size_factor, hinge_elements, max_dofs)
    mesh = mesh_dbma(p, layout, dim, hinge_elements, size_factor)
    formulation = PlaneStress(p.d) if dim == 2 else Solid3D()
    return Model(mesh, dbma_material(p), formulation, order=2)


def static_response(model, force: float, peak_stress=None) -> dict:
    """R (-), elongation and output displacement (m), input stiffness k_in = F / elongation
    (N/m), max von Mises (Pa, nodal and element) and where (m), safety factor against yield,
    of the continuum or the beam model (its groups are the mesh's).

    R_fem = output / elongation; R_fem_per_side = output / (elongation / 2), the output over
    one pad's motion relative to the symmetry plane (the paper's reading, docs/dbma.md): the
    two pads move equally by symmetry, and using their mean removes the mesh's asymmetry.
    ``peak_stress(result) -> {"peak_stress": Pa, ...}``: the beam model's stress at its
    roots (:func:`flexfem.studies.dbma.beam.root_stress`), which then is max_von_mises, the
    model's own in "nominal_stress"."""
    result = solve_static(model, static_supports(), actuator_loads(force, model.dim))
    u_a = result.mean_displacement("input_a")
    u_b = result.mean_displacement("input_b")
    u_out = result.mean_displacement("output")[OUTPUT_AXIS]
    elongation = u_b[0] - u_a[0]
    out = {"force": force, "elongation": elongation, "output_displacement": u_out,
           "R_fem": u_out / elongation, "R_fem_per_side": 2 * u_out / elongation,
           "input_a_x": u_a[0], "input_b_x": u_b[0], "k_in": force / elongation,
           "max_von_mises": result.max_von_mises,
           "max_von_mises_element": result.max_von_mises_element,
           "max_von_mises_location": [float(v) for v in result.max_von_mises_location]}
    if peak_stress is not None:
        out.update(peak_stress(result), nominal_stress=out["max_von_mises"])
        out["max_von_mises"] = out["max_von_mises_element"] = out["peak_stress"]
    strength = model.material.yield_strength
    out["safety_factor"] = strength / out["max_von_mises"] if strength else math.nan
    return out


def output_stiffness(model, force: float = 100.0) -> float:
    """k_out = F / u_out (N/m): the output pushed along y, the mounting face and the pads
    held along x (a rigid actuator, :func:`modal_supports`)."""
    z = (0.0,) if model.dim == 3 else ()
    result = solve_static(model, modal_supports(), [Force("output", (0.0, force) + z)])
    return force / float(result.mean_displacement("output")[OUTPUT_AXIS])


def working_mode(modes) -> int:
    """1-based index of the mode with the largest effective mass along the output axis (y)."""
    return int(np.argmax(modes.effective_mass[:, OUTPUT_AXIS])) + 1


def modal_response(model, n_modes: int = 6) -> tuple[dict, object]:
    """First n_modes frequencies (Hz), effective masses (kg, n x dim), the working mode."""
    modes = solve_modes(model, n=n_modes, supports=modal_supports())
    k = working_mode(modes)
    return {"frequencies_hz": [float(f) for f in modes.frequencies_hz],
            "effective_mass": modes.effective_mass.tolist(), "total_mass": modes.total_mass,
            "working_mode": k, "fn_working": float(modes.frequencies_hz[k - 1])}, modes


def analyze_dbma(params: DBMAParams | None = None, layout: DBMALayout | None = None,
                 dim: int = 3, size_factor: float = 1.0, n_modes: int = 6,
                 force: float | None = None, return_modes: bool = False,
                 max_dofs: int | None = None) -> dict:
    """Static and modal FEM of one DBMA beside the analytical models (SI units).

    Keys: R_fem, R_eq7, R_enhanced, Ke_eq14, me_eq19, fn_eq20, k_in, max_von_mises (at
    ``force``, default the 800 N top of Fig. 14), safety_factor, frequencies_hz, working_mode
    (1-based), fn_working, material {E, nu, rho}, dofs, mass (kg) and the static details.
    ValueError for a result outside the models' validity (guards.check_result)."""
    p = params or paper_design()
    force = float(published()["loading"]["force_max_N"] if force is None else force)
    if not (math.isfinite(force) and force > 0):
        raise ValueError(f"force = {force!r} must be a finite number > 0 (N)")
    model = build_model(p, layout, dim, size_factor, max_dofs=max_dofs)
    out = {**analytical_metrics(p), **static_response(model, force)}
    check_result(out, p)
    out["validity_notes"] = validity_notes(p, out)
    modal, modes = modal_response(model, n_modes)
    out.update(modal)
    out.update({"dim": dim, "size_factor": size_factor, "dofs": int(model.n_dofs),
                "solver": modes.solver, "mass": part_mass(p, layout),
                "material": {"E": p.E, "nu": p.nu, "rho": p.rho,
                             "yield_strength": model.material.yield_strength}})
    if return_modes:
        out["_modes"] = modes
    return out


def params_from_dict(values: dict) -> DBMAParams:
    """The paper's design with the given fields (SI) replaced; unknown keys raise ValueError."""
    known = {f.name for f in dataclasses.fields(DBMAParams)}
    unknown = sorted(set(values) - known)
    if unknown:
        raise ValueError(f"unknown DBMA parameter(s) {unknown}; known: {sorted(known)}")
    return dataclasses.replace(paper_design(), **values)  # DBMAParams checks the types


MODELS = ("continuum", "beam")


def build(p: DBMAParams, layout: DBMALayout | None = None, model: str = "continuum",
          dim: int = 2, size_factor: float = 1.0, max_dofs: int | None = None,
          root_extension: float | None = None) -> tuple:
    """(model, peak_stress) of the DBMA, with the groups every analysis here names: the
    continuum FEM (:func:`build_model`; peak_stress None) or the reduced beam model
    (:func:`flexfem.studies.dbma.beam.beam_model`, planar; its root stress). The analyses
    (:func:`static_response`, :func:`output_stiffness`, :func:`modal_response`) are the same
    for both."""
    if model == "continuum":
        return build_model(p, layout, dim, size_factor, max_dofs=max_dofs), None
    if model == "beam":
        return beam_model(p, layout, root_extension)
    raise ValueError(f"model = {model!r} must be one of {MODELS}")


@declare(parameters=DBMAParams, positive=("k_in", "k_out", "R_fem", "fn_working", "h", "dofs"))
def evaluate(params_dict: dict | None = None, dim: int = 2, size_factor: float = 1.0,
             modes: bool = False, force: float = 100.0, max_dofs: int | None = None, *,
             model: Literal["continuum", "beam"] = "continuum",
             hinge_profile: Literal["leaf", "filleted", "circular"] = "leaf",
             root_extension: float | None = None) -> dict:
    """Metrics for the sweep engine, from the continuum FEM or the reduced beam model
    (``model``; a study selects it with ``options = { model = "beam" }``): R_fem,
    R_fem_per_side, k_in and k_out (N/m), max_von_mises (Pa, at ``force`` N), safety_factor,
    dofs, the analytical metrics, and with ``modes`` fn_working (Hz) and working_mode; the
    continuum's h (hinge element size, m). ``dim``, ``size_factor`` and ``max_dofs`` (the
    mesh budget, None: the machine's) are the continuum's; ``root_extension`` (default
    reduced/layout.py's) the beam's; each model ignores the other's."""
    p = params_from_dict(params_dict or {})
    layout = DBMALayout(hinge_profile=hinge_profile)
    fe, peak = build(p, layout, model, dim, size_factor, max_dofs, root_extension)
    static = static_response(fe, force, peak)
    out = {k: v for k, v in analytical_metrics(p).items() if isinstance(v, (int, float))}
    out.update({k: static[k] for k in ("R_fem", "R_fem_per_side", "k_in", "max_von_mises",
                                       "safety_factor")})
    out["force_N"] = float(force)  # the load case max_von_mises belongs to
    out["k_out"] = output_stiffness(fe)
    check_result(out, p)
    out["dofs"] = int(fe.n_dofs)
    if model == "continuum":
        out["h"] = p.b / (4 if dim == 2 else 2) * size_factor
    if modes:
        modal, _ = modal_response(fe)
        out.update({"fn_working": modal["fn_working"], "working_mode": modal["working_mode"]})
    return out


def fem_metrics(params_dict: dict, dim: int = 2, size_factor: float = 1.0,
                modes: bool = False) -> dict:
    """R_fem, R_fem_per_side (and with ``modes`` fn_working) of the continuum FEM: what the
    figures and the convergence study plot, without evaluate's output-stiffness solve."""
    p = params_from_dict(params_dict)
    fe = build_model(p, None, dim, size_factor)
    out = {k: v for k, v in static_response(fe, 100.0).items()
           if k in ("R_fem", "R_fem_per_side")}
    check_result(out, p)
    out.update({"dofs": int(fe.n_dofs), "h": p.b / (4 if dim == 2 else 2) * size_factor})
    if modes:
        out["fn_working"] = modal_response(fe)[0]["fn_working"]
    return out


def load_linearity(p: DBMAParams, forces, size_factor: float = 1.0) -> list[dict]:
    """Fig. 14: input (elongation) and output displacement (m) at each force (N), 2-D."""
    model = build_model(p, None, 2, size_factor)
    rows = [{"force_N": 0.0, "elongation_m": 0.0, "output_m": 0.0, "R": math.nan}]
    for f in forces:
        s = static_response(model, float(f))
        rows.append({"force_N": float(f), "elongation_m": s["elongation"],
                     "output_m": s["output_displacement"], "R": s["R_fem"]})
    return rows


def fig13_sweep(p: DBMAParams, b_values, h_values, size_factor: float = 1.0) -> list[dict]:
    """Fig. 13: R against b and against h, 2-D FEM beside Eq. 7 and the enhanced model."""
    rows = []
    for name, values in (("b", b_values), ("h", h_values)):
        for v in values:
            q = dataclasses.replace(p, **{name: float(v)})
            a = analytical_metrics(q)
            r = fem_metrics({f.name: getattr(q, f.name) for f in dataclasses.fields(q)}, 2,
                            size_factor)
            rows.append({"parameter": name, "value_m": float(v), "R_fem": r["R_fem"],
                         "R_fem_per_side": r["R_fem_per_side"], "R_eq7": a["R_eq7"],
                         "R_enhanced": a.get("R_enhanced", math.nan)})
    return rows


def convergence_study(p: DBMAParams, size_factors=(2.83, 2.0, 1.41, 1.0),
                      tol: float = 0.01, out_dir=None) -> dict:
    """Mesh convergence (2-D) of R_fem and the working-mode frequency: observed order,
    Richardson-extrapolated value, coarsest size_factor within ``tol`` of it; with ``out_dir``
    a log-log plot per metric, dbma_convergence_<metric>.png."""
    values = {f.name: getattr(p, f.name) for f in dataclasses.fields(p)}
    outputs = {}

    def cached(params, size_factor):  # one static + modal solve per level, for both metrics
        if size_factor not in outputs:
            outputs[size_factor] = fem_metrics(params, 2, size_factor, modes=True)
        return outputs[size_factor]

    levels = [{"size_factor": s} for s in size_factors]
    study = {}
    for metric in ("R_fem", "fn_working"):
        r = converge(cached, metric, levels, "h", values, tol=tol)
        best = r.coarsest_within_tol
        study[metric] = {"size_factors": list(size_factors), "values": r.values,
                         "dofs": r.dofs, "order": r.order, "extrapolated": r.extrapolated,
                         "gci": r.gci, "behaviour": r.behaviour,
                         "recommended_size_factor": None if best is None else size_factors[best]}
        if out_dir is not None:
            plot_convergence(r, Path(out_dir) / f"dbma_convergence_{metric}.png")
    return study

