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
import time

import numpy as np

from ..data import load_toml
from ..fem import (Fixed, Force, Material, Model, PlaneStress, Prescribed, Solid3D,
                         material, solve_modes, solve_static)
from ..geometry.dbma import DBMALayout, dbma_outline_figure, mesh_dbma, part_mass
from ..geometry.dbma_params import DBMAParams, paper_design
from .dbma_figures import analytical_metrics
from .tables import write_rows

OUTPUT_AXIS = 1  # the output moves along y


def published() -> dict:
    """The paper's numbers (data/dbma_paper.toml), as printed."""
    return load_toml("dbma_paper.toml")


def dbma_material(p: DBMAParams) -> Material:
    """Steel with the paper's E and the assumed nu, rho; the yield strength is not in the paper:
    that of structural steel (data/materials.toml) is used for the safety factor."""
    return Material("dbma_steel", p.E, p.nu, p.rho, material("structural_steel").yield_strength,
                    "E: DBMA paper Table 1 (215 GPa); nu, rho, yield: structural_steel")


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
                size_factor: float = 1.0, hinge_elements: int | None = None) -> Model:
    """Quadratic-element model of the DBMA: plane stress of thickness d (2-D) or solid (3-D)."""
    mesh = mesh_dbma(p, layout, dim, hinge_elements, size_factor)
    formulation = PlaneStress(p.d) if dim == 2 else Solid3D()
    return Model(mesh, dbma_material(p), formulation, order=2)


def static_response(model: Model, force: float) -> dict:
    """R (-), elongation and output displacement (m), input stiffness k_in = F / elongation
    (N/m), max von Mises (Pa, nodal and element) and where (m), safety factor against yield.

    R_fem = output / elongation; R_fem_per_side = output / (elongation / 2), the output over
    one pad's motion relative to the symmetry plane (the paper's reading, docs/dbma.md): the
    two pads move equally by symmetry, and using their mean removes the mesh's asymmetry."""
    result = solve_static(model, static_supports(), actuator_loads(force, model.dim))
    u_a = result.mean_displacement("input_a")
    u_b = result.mean_displacement("input_b")
    u_out = result.mean_displacement("output")[OUTPUT_AXIS]
    elongation = u_b[0] - u_a[0]
    vm = result.max_von_mises
    return {"force": force, "elongation": elongation, "output_displacement": u_out,
            "R_fem": u_out / elongation, "R_fem_per_side": 2 * u_out / elongation,
            "input_a_x": u_a[0], "input_b_x": u_b[0],
            "k_in": force / elongation, "max_von_mises": vm,
            "max_von_mises_element": result.max_von_mises_element,
            "max_von_mises_location": [float(v) for v in result.max_von_mises_location],
            "safety_factor": model.material.yield_strength / vm}


def working_mode(modes) -> int:
    """1-based index of the mode with the largest effective mass along the output axis (y)."""
    return int(np.argmax(modes.effective_mass[:, OUTPUT_AXIS])) + 1


def modal_response(model: Model, n_modes: int = 6) -> tuple[dict, object]:
    """First n_modes frequencies (Hz), effective masses (kg, n x dim), the working mode."""
    modes = solve_modes(model, n=n_modes, supports=modal_supports())
    k = working_mode(modes)
    return {"frequencies_hz": [float(f) for f in modes.frequencies_hz],
            "effective_mass": modes.effective_mass.tolist(), "total_mass": modes.total_mass,
            "working_mode": k, "fn_working": float(modes.frequencies_hz[k - 1])}, modes


def analyze_dbma(params: DBMAParams | None = None, layout: DBMALayout | None = None,
                 dim: int = 3, size_factor: float = 1.0, n_modes: int = 6,
                 force: float | None = None, return_modes: bool = False) -> dict:
    """Static and modal FEM of one DBMA beside the analytical models (SI units).

    Keys: R_fem, R_eq7, R_enhanced, Ke_eq14, me_eq19, fn_eq20, k_in, max_von_mises (at
    ``force``, default the 800 N top of Fig. 14), safety_factor, frequencies_hz, working_mode
    (1-based), fn_working, material {E, nu, rho}, dofs, mass (kg) and the static details."""
    p = params or paper_design()
    force = float(published()["loading"]["force_max_N"] if force is None else force)
    if not (math.isfinite(force) and force > 0):
        raise ValueError(f"force = {force!r} must be a finite number > 0 (N)")
    model = build_model(p, layout, dim, size_factor)
    out = {**analytical_metrics(p), **static_response(model, force)}
    modal, modes = modal_response(model, n_modes)
    out.update(modal)
    out.update({"dim": dim, "size_factor": size_factor, "dofs": int(model.n_dofs),
                "mass": part_mass(p, layout),
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
    return dataclasses.replace(paper_design(), **{k: float(v) for k, v in values.items()})


def evaluate(params_dict: dict, dim: int = 2, size_factor: float = 1.0,
             modes: bool = False, force: float = 100.0) -> dict:
    """Metrics for the sweep engine: R_fem, k_in (N/m), max_von_mises (Pa, at ``force`` N),
    dofs, h (hinge element size, m), the analytical metrics, and with ``modes`` fn_working
    (Hz) and working_mode."""
    p = params_from_dict(params_dict)
    model = build_model(p, None, dim, size_factor)
    static = static_response(model, force)
    out = {k: v for k, v in analytical_metrics(p).items() if isinstance(v, (int, float))}
    out.update({k: static[k] for k in ("R_fem", "R_fem_per_side", "k_in", "max_von_mises")})
    out.update({"dofs": int(model.n_dofs), "h": p.b / (4 if dim == 2 else 2) * size_factor})
    if modes:
        modal, _ = modal_response(model)
        out.update({"fn_working": modal["fn_working"], "working_mode": modal["working_mode"]})
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
            r = evaluate({f.name: getattr(q, f.name) for f in dataclasses.fields(q)}, 2, size_factor)
            rows.append({"parameter": name, "value_m": float(v), "R_fem": r["R_fem"],
                         "R_fem_per_side": r["R_fem_per_side"], "R_eq7": a["R_eq7"],
                         "R_enhanced": a.get("R_enhanced", math.nan)})
    return rows


def rel_diff(value: float, reference: float) -> float:
    return (value - reference) / reference


def comparison_rows(result: dict) -> list[dict]:
    """flexfem FEM and analytical numbers beside the paper's theory, FEM and experiment."""
    pub = published()
    amp, freq = pub["amplification"], pub["frequency"]
    r_meas = 0.5 * (amp["R_measured_min"] + amp["R_measured_max"])
    row = lambda q, v, ref, note: {"quantity": q, "flexfem": v, "published": ref,
                                   "rel_diff": rel_diff(v, ref), "note": note}
    return [
        row("R, FEM (output / one pad's displacement)", result["R_fem_per_side"], amp["R_fem"],
            "paper FEM, Sec. 4; the paper's and Eq. 7's reading of R"),
        row("R, FEM vs experiment (mid of 15.43-16.25)", result["R_fem_per_side"], r_meas,
            "Sec. 5, Fig. 17"),
        row("R, FEM (output / actuator elongation)", result["R_fem"], amp["R_fem"],
            "half the above by symmetry: not the paper's R"),
        row("R, Eq. 7 (flexfem evaluation)", result["R_eq7"], amp["R_fem"], "vs paper FEM"),
        row("R, enhanced beam model", result["R_enhanced"], amp["R_fem"], "vs paper FEM"),
        row("working-mode frequency, FEM (Hz)", result["fn_working"], freq["fn_fem_Hz"],
            f"flexfem mode {result['working_mode']} of {result['dim']}-D, paper mode 4"),
        row("working-mode frequency, FEM vs experiment (Hz)", result["fn_working"],
            freq["fn_measured_Hz"], "Sec. 5, Fig. 18"),
        row("working-mode frequency, FEM vs Eq. 20 (Hz)", result["fn_working"], freq["fn_eq20_Hz"],
            "paper theory"),
        row("Eq. 20 frequency (flexfem evaluation, Hz)", result["fn_eq20"], freq["fn_eq20_Hz"],
            "same formula, this project's arm masses"),
    ]


def convergence_study(p: DBMAParams, size_factors=(2.83, 2.0, 1.41, 1.0),
                      tol: float = 0.01, out_dir=None) -> dict:
    """Mesh convergence (2-D) of R_fem and the working-mode frequency: observed order,
    Richardson-extrapolated value, coarsest size_factor within ``tol`` of it; with ``out_dir``
    a log-log plot per metric, dbma_convergence_<metric>.png."""
    from .convergence import converge, plot_convergence

    values = {f.name: getattr(p, f.name) for f in dataclasses.fields(p)}
    outputs = {}

    def cached(params, size_factor):  # one static + modal solve per level, for both metrics
        if size_factor not in outputs:
            outputs[size_factor] = evaluate(params, 2, size_factor, modes=True)
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


def _plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _outline_edges(mesh) -> np.ndarray:
    """(2, n) vertex pairs of the in-plane outline: boundary edges (2-D) or the edges of the
    boundary facets on the top face z = max (3-D)."""
    facets = mesh.facets[:, mesh.boundary_facets()]
    if mesh.dim() == 2:
        return facets
    top = np.all(np.isclose(mesh.p[2, facets], mesh.p[2].max()), axis=0)
    tri = facets[:, top]
    return np.hstack([tri[[0, 1]], tri[[1, 2]], tri[[2, 0]]])


def plot_mode_shapes(modes, path: Path, scale: float = 4e-3) -> Path:
    """The modes' shapes (top view of the deformed outline, largest motion ``scale`` m),
    titled with the frequency (Hz) and the dominant effective-mass direction."""
    plt = _plt()
    from matplotlib.collections import LineCollection

    mesh = modes.model.mesh.mesh
    edges = _outline_edges(mesh)
    n = len(modes.frequencies_hz)
    fig, axes = plt.subplots(2, (n + 1) // 2, figsize=(4 * ((n + 1) // 2), 8))
    fractions = modes.effective_mass_fraction
    for k, ax in enumerate(np.ravel(axes)[:n]):
        shape = modes.vertex_shape(k)
        xy = (mesh.p[:2] + scale / max(np.abs(shape).max(), 1e-30) * shape[:, :2].T) * 1e3
        ax.add_collection(LineCollection(np.transpose(mesh.p[:2, edges] * 1e3, (2, 1, 0)),
                                         colors="0.8", linewidths=0.4))
        ax.add_collection(LineCollection(np.transpose(xy[:, edges], (2, 1, 0)),
                                         colors="tab:blue", linewidths=0.6))
        axis = "xyz"[int(np.argmax(fractions[k]))]
        ax.set_title(f"mode {k + 1}: {modes.frequencies_hz[k]:.1f} Hz\n"
                     f"eff. mass {100 * fractions[k].max():.0f} % along {axis}", fontsize=9)
        ax.set_aspect("equal")
        ax.autoscale_view()
        ax.set_axis_off()
    fig.suptitle("DBMA modes (top view; out-of-plane motion not drawn)")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def plot_fig13(rows: list[dict], path: Path) -> Path:
    plt = _plt()
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, name in zip(axes, ("b", "h")):
        sel = [r for r in rows if r["parameter"] == name]
        x = [r["value_m"] * 1e3 for r in sel]
        for key, style in (("R_fem", "o-"), ("R_fem_per_side", "s--"), ("R_eq7", "^-"),
                           ("R_enhanced", "v-")):
            ax.plot(x, [r[key] for r in sel], style, label=key)
        ax.set_xlabel(f"{name} (mm)")
        ax.set_ylabel("R")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle("Fig. 13: R against hinge thickness b and hinge offset h (2-D FEM, formulas)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def plot_linearity(rows: list[dict], path: Path) -> Path:
    plt = _plt()
    fig, ax = plt.subplots(figsize=(5, 4))
    f = [r["force_N"] for r in rows]
    ax.plot(f, [r["elongation_m"] * 1e6 for r in rows], "o-", label="input (elongation)")
    ax.plot(f, [r["output_m"] * 1e6 for r in rows], "s-", label="output")
    ax.set_xlabel("actuator force (N)")
    ax.set_ylabel("displacement (um)")
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def markdown_table(rows: list[dict]) -> str:
    lines = ["| quantity | flexfem | published | rel. diff | note |", "|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['quantity']} | {r['flexfem']:.4g} | {r['published']:.4g} | "
                     f"{100 * r['rel_diff']:+.1f} % | {r['note']} |")
    return "\n".join(lines) + "\n"


def reproduce(out_dir, quick: bool = False) -> dict:
    """Tables (CSV, markdown) and figures (PNG) of the DBMA study into ``out_dir``: the
    comparison with the paper, Fig. 13 and Fig. 14 studies, modes, mesh convergence."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    p = paper_design()
    start = time.perf_counter()
    # statics on the 2-D default mesh (R is converged there to 0.3 %, see the convergence
    # table); modes on the 3-D default mesh (2-D in quick mode)
    model2 = build_model(p, None, 2, 2.0 if quick else 1.0)
    result = {**analytical_metrics(p), **static_response(model2, 800.0)}
    modal_model = model2 if quick else build_model(p, None, 3, 1.0)
    modal, modes = modal_response(modal_model)
    result.update(modal)
    result.update({"dim": modal_model.dim, "dofs": int(modal_model.n_dofs)})
    rows = comparison_rows(result)
    tables = [write_rows(out / "dbma_comparison.csv", rows).name]
    (out / "dbma_comparison.md").write_text(markdown_table(rows))
    tables.append("dbma_comparison.md")
    mode_rows = [{"mode": k + 1, "frequency_hz": f, **{f"effective_mass_{a}_kg": m
                  for a, m in zip("xyz", result["effective_mass"][k])}}
                 for k, f in enumerate(result["frequencies_hz"])]
    tables.append(write_rows(out / "dbma_modes.csv", mode_rows).name)
    figures = [dbma_outline_figure(p, None, out / "dbma_outline.png").name,
               plot_mode_shapes(modes, out / "dbma_modes.png").name]
    from ..fem.export import write_result
    write_result(modes, out / "dbma_modes.vtu")
    figures.append("dbma_modes.vtu")
    forces = [200.0, 800.0] if quick else [200.0, 400.0, 600.0, 800.0]
    lin = load_linearity(p, forces, 2.0 if quick else 1.0)
    tables.append(write_rows(out / "dbma_fig14_linearity.csv", lin).name)
    figures.append(plot_linearity(lin, out / "dbma_fig14_linearity.png").name)
    b_values = [0.4e-3, 1.0e-3] if quick else [0.4e-3, 0.6e-3, 0.8e-3, 1.0e-3]
    h_values = [0.8e-3, 3.0e-3] if quick else [0.8e-3, 1.0e-3, 1.2e-3, 1.6e-3, 2.0e-3, 2.6e-3,
                                               3.0e-3]
    # R converges fast (0.3 % between size_factor 2.83 and 1): the sweep uses 2.83
    sweep = fig13_sweep(p, b_values, h_values, 2.83)
    tables.append(write_rows(out / "dbma_fig13.csv", sweep).name)
    figures.append(plot_fig13(sweep, out / "dbma_fig13.png").name)
    summary = {"comparisons": rows, "figures": figures, "tables": tables,
               "R_fem": result["R_fem"], "R_fem_per_side": result["R_fem_per_side"],
               "fn_working": result["fn_working"], "working_mode": result["working_mode"],
               "frequencies_hz": result["frequencies_hz"], "dofs": result["dofs"],
               "max_von_mises": result["max_von_mises"], "safety_factor": result["safety_factor"],
               "k_in": result["k_in"]}
    if not quick:
        conv = convergence_study(p, out_dir=out)
        conv_rows = [{"metric": m, "size_factor": f, "value": v, "dofs": d}
                     for m, c in conv.items() for f, v, d in zip(c["size_factors"], c["values"],
                                                                  c["dofs"])]
        tables.append(write_rows(out / "dbma_convergence.csv", conv_rows).name)
        figures += [f"dbma_convergence_{m}.png" for m in conv]
        summary["convergence"] = conv
        summary["notes"] = [
            f"mesh convergence (2-D, size_factor {', '.join(map(str, c['size_factors']))}) of "
            f"{m}: {', '.join(f'{v:.5g}' for v in c['values'])}; observed order {c['order']:.2f} "
            f"({c['behaviour']}), Richardson {c['extrapolated']:.5g}, recommended size_factor "
            f"{c['recommended_size_factor']}" for m, c in conv.items()]
    from .dbma_hinges import hinge_profile_study  # hinge-profile sensitivity
    hinges = hinge_profile_study(out, quick=quick)
    tables += hinges["tables"]
    figures += hinges["figures"]
    summary["hinge_profiles"] = hinges["rows"]
    summary.setdefault("notes", []).extend(hinges.get("notes", []))
    summary["wall_time_s"] = time.perf_counter() - start
    return summary
