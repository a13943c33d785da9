"""Report section "Eight-bar: beam model beside the pseudo-rigid-body model and the continuum
FEM": the three-way table of the default design (the suspension, then the driving linkage)
and the path over the stroke by both models.
"""
import time
from pathlib import Path

from ...geometry.eightbar.flexure import (EightBarFlexureParams, prbm_peak_stress,
                                          prbm_stiffness)
from ..engine.tables import write_rows
from ..report.figures import axis_label, legend_outside, pyplot, save
from ..report.three_way import (STRESS_TOL, Metric, beam_comparisons, key_table,
                                three_way_rows)
from .analysis import analyze_eightbar
from .beam import analyze_eightbar_beam
from .driving_models import analyze_driving_beam, analyze_driving_continuum
from .driving_path import driving_path

NAN = float("nan")
MM = 1e-3  # m


def metrics_of(params, beam: dict, cont: dict) -> list:
    """[Metric] of the three models: stiffnesses, modes, stresses, the path and end force."""
    travel = cont["travel_m"]
    k_prbm = prbm_stiffness(params)["k_x"]
    s_prbm = max(prbm_peak_stress(params, travel / 2).values())
    rows = [Metric("k_x (along the motion)", "N/m", k_prbm, beam["k_x"], cont["k_x"]),
            Metric("k_y (across the motion)", "N/m", NAN, beam["k_y"], cont["k_y"])]
    for k, (mb, mc) in enumerate(zip(beam["modes"], cont["modes"])):
        rows.append(Metric(f"mode {k + 1} frequency: {mode_kind(mc, cont['modes'])}", "Hz",
                           NAN, mb["f_hz"], mc["f_hz"]))
    rows += [
        Metric(f"max stress, linear, x = {travel / 2 * 1e3:.3g} mm", "Pa", s_prbm,
               beam["max_von_mises"], cont["max_von_mises"], STRESS_TOL,
               note="PRBM: E w phi / (2 L); continuum: von Mises at the filleted roots"),
        Metric("path deviation over the stroke", "m", beam["rigid_deviation_m"],
               beam["fem_deviation_m"], cont["fem_deviation_m"], STRESS_TOL,
               note="PRBM column: the rigid-body linkage"),
        Metric("peak stress over the stroke", "Pa", s_prbm, beam["peak_von_mises_travel"],
               cont["peak_von_mises_travel"], STRESS_TOL),
        Metric("drive force at the end of the stroke", "N", k_prbm * travel / 2,
               beam["end_force_n"], cont["end_force_n"])]
    return rows


def mode_kind(mode: dict, modes: list) -> str:
    """What a continuum mode is, from its effective masses (kg): along the axis that carries
    the most, or internal (under 1 % of the largest effective mass of the modes)."""
    masses = {a: mode.get(f"m_eff_{a}_kg", 0.0) for a in "xyz"}
    largest = max(m.get(f"m_eff_{a}_kg", 0.0) for m in modes for a in "xyz")
    axis = max(masses, key=masses.get)
    if masses[axis] < 0.01 * largest:
        return "internal (links against each other, no net motion of the mass)"
    what = "the drive mode, " if axis == "x" else ""
    return f"{what}along {axis} (eff. mass {masses[axis] * 1e3:.3g} g)"


def driving_metrics(beam: dict, cont: dict) -> list:
    """[Metric] of the driving linkage (analyze_driving_beam / _continuum): input stiffness,
    transmission (PRBM column: the rigid linkage's), stress per input, modes."""
    rows = [Metric("driving linkage: input stiffness (shuttle, y)", "N/m", beam["k_in_prbm"],
                   beam["stiffness_n_per_m"], cont["stiffness_n_per_m"],
                   note="PRBM: sum of E I / L (d phi / d s)^2 over the 34 flexures"),
            Metric("driving linkage: transmission d x_R / d s", "-",
                   beam["rigid_transmission"], beam["transmission"], cont["transmission"],
                   note="PRBM column: the rigid linkage"),
            Metric("driving linkage: peak stress, linear, 1 mm of input", "Pa", NAN,
                   beam["max_von_mises_pa"] * MM / beam["input_m"],
                   cont["max_von_mises_pa"] * MM / cont["input_m"], STRESS_TOL,
                   note="continuum: nodal von Mises at the sharp roots the driving linkage "
                        "is drawn with (a corner: mesh-dependent)")]
    for k, (mb, mc) in enumerate(zip(beam.get("modes", []), cont.get("modes", []))):
        rows.append(Metric(f"driving linkage: mode {k + 1} frequency", "Hz", NAN, mb["f_hz"],
                           mc["f_hz"]))
    return rows


def driving_path_metrics(beam: dict, cont: dict) -> list:
    """[Metric] of the driving linkage's large-deflection path (driving_path of both models):
    the right end-effector's straight-line deviation and the input force at the end."""
    stroke = beam["stroke_m"] * 1e3
    return [Metric(f"driving linkage: path deviation over {stroke:.3g} mm (right)", "m",
                   beam["rigid_deviation_m"], beam["deviation_m"], cont["deviation_m"],
                   None, note="not judged: the suspensions' coupler is lengthened so that "
                   "the continuum's path runs straight; what is left is under 1 um in both "
                   "(PRBM column: the rigid linkage, bowed the other way by design)"),
            Metric("driving linkage: input force at the end of the stroke", "N", NAN,
                   beam["end_force_n"], cont["end_force_n"])]


def plot_paths(beam: dict, cont: dict, path) -> dict:
    """End-effector y (um, from the middle) against x (mm) by both models."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7, 4))
    for out, style, name in ((cont, "o", "continuum FEM (2-D)"), (beam, "-", "beam model")):
        rows = sorted(out["path"], key=lambda r: r["x_m"])
        ax.plot([r["x_m"] * 1e3 for r in rows], [r["y_m"] * 1e6 for r in rows], style,
                label=name)
    ax.set_xlabel(axis_label("end-effector x", "mm"))
    ax.set_ylabel(axis_label("end-effector y", "um"))
    ax.grid(True, alpha=0.3)
    legend_outside(ax)
    return save(fig, path, "Eight-bar flexure suspension: the end-effector's path over the "
                "stroke, beam model (line) against the 2-D continuum FEM (points), driven "
                "along x from the middle (the -x half mirrored).")


def reproduce(out_dir, quick: bool = False) -> dict:
    """Three-way table of the default design (quick: the continuum on a 2x coarser mesh, 4
    steps) and the path figure."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    params = EightBarFlexureParams()
    start = time.perf_counter()
    steps = 3 if quick else 8  # the same steps as the continuum: the path is sampled alike
    beam = analyze_eightbar_beam(params, steps=steps, n_modes=2 if quick else 4)
    t_beam = time.perf_counter() - start
    start = time.perf_counter()
    cont = analyze_eightbar(params, size_factor=2.0 if quick else 1.0,
                            steps=steps, both_halves=False,
                            n_modes=2 if quick else 4)
    t_cont = time.perf_counter() - start
    metrics = metrics_of(params, beam, cont)
    start = time.perf_counter()
    d_beam = analyze_driving_beam(n_modes=2 if quick else 3)
    t_d_beam = time.perf_counter() - start
    start = time.perf_counter()
    d_cont = analyze_driving_continuum(n_modes=2 if quick else 3,
                                       size_factor=3.0 if quick else 1.5)
    t_d_cont = time.perf_counter() - start
    metrics += driving_metrics(d_beam, d_cont)
    if not quick:  # the continuum's stroke takes minutes
        metrics += driving_path_metrics(driving_path(model="beam"),
                                        driving_path(model="continuum", size_factor=1.5))
    tables = [write_rows(out_dir / "eightbar_beam_three_way.csv", three_way_rows(metrics)).name]
    figure = plot_paths(beam, cont, out_dir / "eightbar_beam_path.png")
    worst = max(abs(m.beam / m.continuum - 1) for m in metrics)
    paragraph = (
        "The beam model of the eight-bar suspension is generated from the same planar layout "
        "as the continuum mesh (reduced/eightbar.py): ten flexures as beams through their "
        "root fillets, the links rigid with their masses, the common root extension. It gives "
        f"the whole analysis (stiffnesses, {len(beam['modes'])} modes, the nonlinear stroke) "
        f"in {t_beam:.2f} s against {t_cont:.0f} s for the 2-D FEM ({cont['dofs']} DOFs"
        f"{', 2x coarser mesh in this quick run' if quick else ''}); the largest difference "
        f"over the table is {100 * worst:.1f} %. The PRBM misses k_x by "
        f"{100 * (metrics[0].prbm / metrics[0].continuum - 1):+.1f} % (it neglects the "
        "flexures' shear and axial compliance and the links' shape) and has no k_y or modes. "
        "The driving linkage (two lambdas and the two suspensions, 34 flexures; "
        "reduced/driving.py, from the same flexure layout as its mesh) by the "
        f"beam model in {t_d_beam:.2f} s against {t_d_cont:.0f} s for its 2-D FEM "
        f"({d_cont['dofs']} DOFs): input stiffness "
        f"{100 * (d_beam['stiffness_n_per_m'] / d_cont['stiffness_n_per_m'] - 1):+.1f} %, "
        f"first mode {100 * (d_beam['modes'][0]['f_hz'] / d_cont['modes'][0]['f_hz'] - 1):+.1f}"
        " %.")
    return {"paragraph": paragraph, "comparisons": beam_comparisons(metrics),
            "figures": [figure], "tables": tables,
            "key_tables": [key_table(metrics, "Eight-bar (default design): PRBM, beam, "
                                     "continuum")],
            "timing_s": {"beam": t_beam, "continuum": t_cont, "driving_beam": t_d_beam,
                         "driving_continuum": t_d_cont}}
