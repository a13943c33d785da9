"""Report section "DBMA: beam model beside the closed forms and the continuum FEM": the
three-way table (PRBM / elastic-beam closed forms, the generated beam model, 2-D FEM) of the
paper's design, and where the beam model stops being trustworthy over the hinge slenderness.
"""
import math
import time
from pathlib import Path

from ...fem import Force, solve_static
from ...geometry.dbma.params import paper_design
from ..engine.tables import write_rows
from ..report.three_way import (STRESS_TOL, Metric, beam_comparisons, key_table,
                                three_way_rows)
from . import analysis as fem
from .beam import analyze_dbma_beam
from ...reduced.specimen import slenderness_rows, trusted_from
from .beam_slenderness import dbma_slenderness_rows, plot_slenderness

FORCE = 100.0  # N, the actuator force of the linear solves


def continuum_metrics(p, size_factor: float, layout=None) -> dict:
    """R_fem_per_side, k_in, k_out (N/m), fn_working (Hz), max_von_mises (Pa at FORCE) of
    the 2-D FEM (``layout``: a DBMALayout, default the paper's leaf hinges), and its wall
    time (s)."""
    start = time.perf_counter()
    model = fem.build_model(p, layout, 2, size_factor)
    static = fem.static_response(model, FORCE)
    probe = solve_static(model, fem.modal_supports(), [Force("output", (0.0, FORCE))])
    modal, _ = fem.modal_response(model, 6)
    return {"R_fem_per_side": static["R_fem_per_side"], "k_in": static["k_in"],
            "k_out": FORCE / float(probe.mean_displacement("output")[1]),
            "fn_working": modal["fn_working"], "max_von_mises": static["max_von_mises"],
            "dofs": int(model.n_dofs), "time_s": time.perf_counter() - start}


def three_way(p, size_factor: float) -> tuple:
    """([Metric], beam output, continuum output) of design ``p``."""
    start = time.perf_counter()
    beam = analyze_dbma_beam(p, force=FORCE)
    beam["time_s"] = time.perf_counter() - start
    cont = continuum_metrics(p, size_factor)
    a = beam  # the analytical metrics ride along in the beam output
    metrics = [
        Metric("R, output / one pad's motion", "-", a["R_eq7"], beam["R_fem_per_side"],
               cont["R_fem_per_side"], note="PRBM: Eq. 7"),
        Metric("input stiffness k_in", "N/m", a["K_in_enhanced"], beam["k_in"], cont["k_in"],
               note="closed form: the elastic-beam (enhanced) model"),
        Metric("output stiffness k_out (input blocked)", "N/m", a["K_out_enhanced"],
               beam["k_out"], cont["k_out"], note="closed form: the enhanced model"),
        Metric("working-mode frequency", "Hz", a["fn_eq20"], beam["fn_working"],
               cont["fn_working"], note="PRBM: Eq. 20"),
        Metric(f"max stress at {FORCE:g} N", "Pa", math.nan, beam["max_von_mises"],
               cont["max_von_mises"], STRESS_TOL,
               note="sharp hinge corners: the continuum's peak is singular (mesh-dependent)"),
    ]
    return metrics, beam, cont


def out_of_plane_metric(p) -> tuple:
    """(Metric, the solid's working-mode frequency Hz): the lowest out-of-plane mode of the
    spatial beam model (the hinges' torsion with Vlasov's warping restraint) against the 3-D
    solid (size_factor 1), no closed form."""
    from ..mode_pairing import working_index
    from .dbma_modes3d import compare_modes3d

    out = compare_modes3d(p, n_modes=6)
    row = next(r for r in out["rows"] if r["family"] == "out of plane")
    solid = out["continuum"]
    return Metric("lowest out-of-plane mode (spatial beam; 3-D solid)", "Hz", math.nan,
                  row["beam_hz"], row["continuum_hz"],
                  note="3-D only; the default solid mesh reads 1-2 % high (docs/beam.md)"
                  ), solid["f_hz"][working_index(solid)]


def _axial_range(rows: list, profile: str) -> str:
    """The range of -100 x the axial error of ``profile``'s slenderness rows, "a-b %"."""
    errors = sorted(-100 * r["axial_error"] for r in rows if r["profile"] == profile)
    return f"{errors[0]:.0f}-{errors[-1]:.0f} %"


def reproduce(out_dir, quick: bool = False) -> dict:
    """Three-way table of the paper's design (quick: the continuum on a 2x coarser mesh) and
    the slenderness figure (quick: the hinge specimen only; full: also the DBMA at l/b = 2,
    5, 10, 20)."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    p = paper_design()
    metrics, beam, cont = three_way(p, 2.0 if quick else 1.0)
    spatial, solid_working = [], math.nan
    if not quick:
        metric, solid_working = out_of_plane_metric(p)
        spatial = [metric]
    tables = [write_rows(out_dir / "dbma_beam_three_way.csv",
                         three_way_rows(metrics + spatial)).name]
    rows = slenderness_rows((2.0, 3.0, 5.0, 10.0, 20.0),
                            ("leaf",) if quick else ("leaf", "circular"))
    tables.append(write_rows(out_dir / "dbma_beam_slenderness.csv", rows).name)
    mech = None if quick else dbma_slenderness_rows()
    if mech:
        tables.append(write_rows(out_dir / "dbma_beam_slenderness_mechanism.csv", mech).name)
    figure = plot_slenderness(rows, out_dir / "dbma_beam_slenderness.png", mech)
    leaf_from = trusted_from(rows, "leaf")
    err = {m.quantity.split(",")[0].split(" (")[0]: 100 * (m.beam / m.continuum - 1)
           for m in metrics}
    paragraph = (
        "The beam model of the DBMA is generated from its parameters (reduced/dbma.py): "
        "16 hinges from their profiles, elastic arms and members, the common root extension "
        "(0.38 b per root, with the root's axial compliance); where each pad bears on its "
        "input member, the member is as deep as it is long and no beam, so that part and its "
        "pad are a 2-D plane-stress patch condensed onto the member's beams "
        f"(reduced/dbma_member_patch.py). For the paper's design (l/b = "
        f"{p.l / p.b:.2f}) it solves in {beam['time_s'] * 1e3:.0f} ms against "
        f"{cont['time_s']:.1f} s for the 2-D FEM ({cont['dofs']} DOFs"
        f"{', a 2x coarser mesh in this quick run' if quick else ''}). Beam against continuum: "
        + ", ".join(f"{k} {v:+.1f} %" for k, v in err.items()) + " (with the pads as rigid "
        "blocks in beam members, k_out, two thirds of whose compliance is the members' "
        "bending next to the pads, was the output outside 3 %). The beam stress is nominal "
        "(the continuum's sharp hinge corners are singular). Over the "
        "slenderness of one hinge, the beam model with the root extension stays within 3 % of "
        f"the continuum from l/b = {leaf_from:g} for a sharp-cornered leaf, in bending and "
        "axially; without it, it is too stiff by ~b / l. A circular notch's beam is "
        "corrected by the notch's own 2-D model (its stiffness and its neck's K_t, "
        "reduced/hinge_patch.py)"
        + ("" if quick else
           f": in bending it stays within 3 % from l/b = {trusted_from(rows, 'circular'):g} "
           "(t/R = 2 b / l), while axially the notch's junction with the specimen's blocks, "
           f"several times taller than its ends, leaves it {_axial_range(rows, 'circular')} "
           "stiff")
        + ". Screen with the beam model, decide with the continuum."
        + ("" if quick else
           " Out of plane (3-D), the spatial beam model (the hinges' warping restraint, their "
           "roots compliant about the strong axis as the planar roots are axially) "
           f"puts the lowest mode at {spatial[0].beam:.0f} Hz, next to its working mode "
           f"({beam['fn_working']:.0f} Hz); the 3-D solid has it at "
           f"{spatial[0].continuum:.0f} Hz, next to its own ({solid_working:.0f} Hz): the "
           "two lie about as close as the beam's error, so only the solid tells their order."))
    comparisons = (beam_comparisons(metrics)
                   + beam_comparisons(spatial, "continuum FEM (3-D solid, same design)"))
    return {"paragraph": paragraph, "comparisons": comparisons,
            "figures": [figure], "tables": tables,
            "key_tables": [key_table(metrics + spatial,
                                     "DBMA (paper's design): PRBM, beam, continuum")],
            "timing_s": {"beam": beam["time_s"], "continuum": cont["time_s"]}}
